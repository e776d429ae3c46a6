// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/fitmap/tips.h"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cmath>

#include "quadsimp/util/parallel.h"

namespace qs {
namespace {

struct Scratch {
  std::vector<Index> mark, queue;
  Index stamp = 0;
};

}  // namespace

std::vector<Index> find_tips(const TriMesh& t, const TipOptions& o) {
  const Index nv = t.n_vertices();
  if (nv == 0 || !(o.radius > 0)) return {};
  const VertexRings rings = vertex_rings(t);
  // Angle-weighted: with area weights a cube's corner was a tip or not depending on how its
  // sides were split (2 of the 8 corners of tri_cube(20) at the scale of 150 quads).
  const std::vector<Vec3> normal = vertex_angle_normals(t);
  const double r = o.radius, near = 0.7 * r, rise = 0.1 * r;
  std::vector<double> slope(nv, -1);  // the least fall at the rim; -1: not a tip
  tbb::enumerable_thread_specific<Scratch> scratch;
  parallel_for_as_here(Index(0), nv, [&](Index v) {
    if (rings.border[v] || !(normal[v].squaredNorm() > 0)) return;
    Scratch& s = scratch.local();
    if (s.mark.size() != nv) s.mark.assign(nv, 0), s.stamp = 0;
    const Index stamp = ++s.stamp;
    const Vec3 p = t.positions[v], n = normal[v];
    s.queue.assign(1, v);
    s.mark[v] = stamp;
    double least = 1;
    bool rim = false;
    for (std::size_t i = 0; i < s.queue.size(); ++i) {
      const Index u = s.queue[i];
      for (Index j = rings.start[u]; j < rings.start[u + 1]; ++j) {
        const Index w = rings.next[j];
        if (s.mark[w] == stamp) continue;
        s.mark[w] = stamp;
        const Vec3 d = t.positions[w] - p;
        const double len = d.norm();
        // The rim: from 0.7 radius, and the first vertices past the ball, so that an input
        // whose edges are as long as the radius still has one. Most vertices fail here early.
        if (len >= near) {
          const double fall = -d.dot(n) / len;
          if (fall < o.min_slope) return;
          least = std::min(least, fall), rim = true;
        }
        if (len >= r) continue;
        // Anything above v, or a border within the ball: v is not the end of a closed tip.
        if (d.dot(n) > rise || rings.border[w]) return;
        s.queue.push_back(w);
      }
    }
    if (rim) slope[v] = least;
  });
  std::vector<Index> candidates;
  for (Index v = 0; v < nv; ++v)
    if (slope[v] >= 0) candidates.push_back(v);
  std::sort(candidates.begin(), candidates.end(),
            [&](Index a, Index b) { return slope[a] != slope[b] ? slope[a] > slope[b] : a < b; });
  // A tip's own neighbours qualify too, less steeply: the steepest stands for them all.
  std::vector<Index> tips;
  for (Index v : candidates) {
    if (o.max_tips > 0 && tips.size() == o.max_tips) break;
    const bool taken = std::any_of(tips.begin(), tips.end(), [&](Index w) {
      return (t.positions[w] - t.positions[v]).squaredNorm() < r * r;
    });
    if (!taken) tips.push_back(v);
  }
  std::sort(tips.begin(), tips.end());
  return tips;
}

TipOptions tip_options_for(const TriMesh& mesh, double quads) {
  TipOptions o;
  o.radius = std::sqrt(surface_area(mesh) / quads);
  o.max_tips = std::size_t(0.05 * quads) + 1;
  return o;
}

}  // namespace qs
