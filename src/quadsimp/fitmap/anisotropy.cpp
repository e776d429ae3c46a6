// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/fitmap/anisotropy.h"

#include <tbb/enumerable_thread_specific.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "quadsimp/fitmap/cells.h"
#include "quadsimp/util/parallel.h"

namespace qs {
namespace {

// What a cell holds: its triangles' area, area-weighted centroid, normal sum and
// second moment of the unit normals.
struct NormalMoments {
  double area = 0;
  Vec3 first = Vec3::Zero();
  Vec3 normal = Vec3::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  // A ball's sum: its centroid is never read.
  void add(const NormalMoments& o) { area += o.area, normal += o.normal, second += o.second; }
};

struct Scratch {
  std::vector<Index> mark, queue;
  Index stamp = 0;
};

}  // namespace

Anisotropy compute_anisotropy(const TriMesh& t, const std::vector<std::array<Index, 3>>& adjacency,
                              double radius, double max_aspect) {
  Anisotropy out;
  const Index nv = t.n_vertices(), nf = t.n_faces();
  out.g.assign(nv, {1.f, 0.f, 0.f, 1.f, 0.f, 1.f});
  if (nf == 0 || !(radius > 0) || !(max_aspect > 1)) return out;

  std::vector<Vec3> centroid(nf);
  for (Index f = 0; f < nf; ++f)
    centroid[f] = (t.positions[t.faces[f][0]] + t.positions[t.faces[f][1]] + t.positions[t.faces[f][2]]) / 3.0;
  const detail::CellGrid grid = detail::cluster_triangles(centroid, adjacency, radius / 4);
  const Index nc = grid.n_cells();
  std::vector<NormalMoments> cell(nc);
  for (Index f = 0; f < nf; ++f) {
    const Vec3 &a = t.positions[t.faces[f][0]], &b = t.positions[t.faces[f][1]], &c = t.positions[t.faces[f][2]];
    const Vec3 n = (b - a).cross(c - a);
    const double area = 0.5 * n.norm();
    NormalMoments& m = cell[grid.cell_of_triangle[f]];
    m.area += area, m.first += area * centroid[f], m.normal += 0.5 * n;
    if (area > 0) {
      const Vec3 u = n.normalized();
      m.second += area * u * u.transpose();
    }
  }
  std::vector<Vec3> centre(nc);
  for (Index c = 0; c < nc; ++c) centre[c] = cell[c].first / std::max(cell[c].area, 1e-300);
  std::vector<Index> start(nv, kNone);  // a cell each vertex's search starts from: one of its triangles'
  for (Index f = nf; f-- > 0;)
    for (Index v : t.faces[f]) start[v] = grid.cell_of_triangle[f];

  const double r2 = radius * radius;
  tbb::enumerable_thread_specific<Scratch> scratch;
  parallel_for_as_here(Index(0), nv, [&](Index v) {
    if (start[v] == kNone) return;
    Scratch& s = scratch.local();
    if (s.mark.size() != nc) s.mark.assign(nc, 0), s.stamp = 0;
    const Index stamp = ++s.stamp;
    const Vec3& p = t.positions[v];
    s.queue.assign(1, start[v]);
    s.mark[start[v]] = stamp;
    NormalMoments sum;
    sum.add(cell[start[v]]);
    detail::grow_ball(grid, centre, p, r2, s.queue, s.mark, stamp, stamp, [&](Index c) { sum.add(cell[c]); });
    if (!(sum.area > 0) || !(sum.normal.squaredNorm() > 0)) return;
    const Vec3 n = sum.normal.normalized();
    const Eigen::Matrix3d tangent = Eigen::Matrix3d::Identity() - n * n.transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
    es.computeDirect(tangent * (sum.second / sum.area) * tangent);
    const double l1 = es.eigenvalues()(2), l2 = es.eigenvalues()(1);  // ascending; the least is along n
    // Flat (l1 = 0): the eigenvectors are arbitrary, t1 possibly n itself; G stays I.
    if (!(l1 > 0)) return;
    const double stretch = l2 > 0 ? std::clamp(std::pow(l1 / l2, 0.25), 1.0, max_aspect) : max_aspect;
    const Vec3 t1 = es.eigenvectors().col(2), t2 = n.cross(t1);
    const Eigen::Matrix3d G =
        stretch * t1 * t1.transpose() + (1 / stretch) * t2 * t2.transpose() + n * n.transpose();
    const double entries[6] = {G(0, 0), G(0, 1), G(0, 2), G(1, 1), G(1, 2), G(2, 2)};
    for (int k = 0; k < 6; ++k) out.g[v][k] = float(entries[k]);
  });
  return out;
}

Anisotropy anisotropy_for(const TriMesh& mesh, const std::vector<std::array<Index, 3>>& adjacency, double quads,
                          double max_aspect) {
  return compute_anisotropy(mesh, adjacency, 2 * std::sqrt(surface_area(mesh) / quads), max_aspect);
}

Stretch stretch_at(const Anisotropy& a, Index v) {
  if (a.empty()) return {};
  const auto& g = a.g[v];
  Eigen::Matrix3d G;
  G << g[0], g[1], g[2], g[1], g[3], g[4], g[2], g[4], g[5];
  // Eigenvalues 1/s, 1 and s, in that order: t2, n and t1.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(G);
  const auto& l = eigen.eigenvalues();
  Stretch out;
  out.aspect = l(0) > 0 ? std::max(1.0, std::sqrt(l(2) / l(0))) : 1.0;
  if (out.aspect > kLeastStretch) out.along = eigen.eigenvectors().col(0).normalized();
  return out;
}

}  // namespace qs
