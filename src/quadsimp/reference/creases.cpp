// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/reference/creases.h"

#include <tbb/blocked_range.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include "quadsimp/util/parallel.h"

namespace qs {
namespace {

// A network of creases (curves meeting at corners) shorter than this many mean input
// edges in all is dropped (Creases::Creases()).
constexpr double kShortestNetwork = 4.0;

// How far on either side a curve must still turn for a corner (Creases::chain()), in mean
// input edges.
constexpr double kTurnReach = 2.0;

// The triangles' unit normals after a few passes of bilateral filtering: each becomes the
// mean of its own and its neighbours', weighted by area and by how close they are to its
// own, on the scale of the crease angle (normals a third as far apart as two parting by
// the angle weigh 0.6; at the angle, 0.01). A scan's noise below that scale is averaged out,
// while the normals across a crease count for next to nothing.
std::vector<Vec3> filtered_normals(const TriMesh& mesh, const std::vector<std::array<Index, 3>>& adjacency,
                                   double angle_deg) {
  constexpr int kPasses = 8;
  const double spread = 2 * std::sin(angle_deg * M_PI / 360.0) / 3;  // the distance between normals
  std::vector<Vec3> normal(mesh.n_faces()), next(mesh.n_faces());
  std::vector<double> area(mesh.n_faces());
  for (Index f = 0; f < mesh.n_faces(); ++f) {
    const Vec3 n = mesh.area_normal(mesh.faces[f]);
    normal[f] = n.normalized(), area[f] = 0.5 * n.norm();
  }
  for (int pass = 0; pass < kPasses; ++pass) {
    parallel_for_as_here(tbb::blocked_range<Index>(0, mesh.n_faces()), [&](const tbb::blocked_range<Index>& faces) {
      for (Index f = faces.begin(); f != faces.end(); ++f) {
        Vec3 sum = area[f] * normal[f];
        for (Index g : adjacency[f])
          if (g != kNone && normal[g].allFinite())
            sum += area[g] * std::exp(-(normal[g] - normal[f]).squaredNorm() / (2 * spread * spread)) * normal[g];
        next[f] = normal[f].allFinite() ? sum.normalized() : normal[f];
      }
    });
    normal.swap(next);
  }
  return normal;
}

// Clears the crease edges of every network (edges meeting at vertices: curves meeting at
// corners) shorter than kShortestNetwork mean input edges in all. Such a network is a
// scan's noise, not a part's edge: kept, its vertices stay at the input's spacing for
// good. Loose short curves left the shortest edge of bunny.ply at 60 degrees, adaptive, at
// 0.05 of the mean; at 60 degrees every network of the armadillo is a cluster of one or
// two input edges' curves meeting at corners (71 curves, 31 networks).
void drop_short_networks(const TriMesh& mesh, const std::vector<std::array<Index, 3>>& adjacency,
                         std::vector<char>& crease) {
  std::vector<Index> network(mesh.n_vertices());
  std::iota(network.begin(), network.end(), Index(0));
  auto root = [&](Index v) {
    while (network[v] != v) v = network[v] = network[network[v]];
    return v;
  };
  auto ends = [&](Index e) { return std::pair(mesh.faces[e / 3][e % 3], mesh.faces[e / 3][(e % 3 + 1) % 3]); };
  // Each edge once: as the half of its lower-numbered triangle.
  auto once = [&](Index e) { return crease[e] && adjacency[e / 3][e % 3] > e / 3; };
  const Index halves = Index(crease.size());
  for (Index e = 0; e < halves; ++e)
    if (once(e)) network[root(ends(e).first)] = root(ends(e).second);
  std::vector<double> length(mesh.n_vertices(), 0.0);
  for (Index e = 0; e < halves; ++e)
    if (once(e)) length[root(ends(e).first)] += (mesh.positions[ends(e).first] - mesh.positions[ends(e).second]).norm();
  const double shortest = kShortestNetwork * mean_edge_length(mesh);
  for (Index e = 0; e < halves; ++e)
    if (crease[e] && length[root(ends(e).first)] < shortest) crease[e] = 0;
}

}  // namespace

std::vector<char> crease_edges(const TriMesh& mesh, const std::vector<std::array<Index, 3>>& adjacency,
                               double angle_deg) {
  std::vector<char> crease(3 * std::size_t(mesh.n_faces()), 0);
  if (!(angle_deg > 0 && angle_deg < 180)) return crease;
  const double cos_max = std::cos(angle_deg * M_PI / 180.0);
  const std::vector<Vec3> normal = filtered_normals(mesh, adjacency, angle_deg);
  for (Index f = 0; f < mesh.n_faces(); ++f)
    for (Index k = 0; k < 3; ++k) {
      const Index g = adjacency[f][k];
      // A triangle of no area has no normal (NaN): its edges are not creases.
      crease[3 * f + k] = g != kNone && normal[f].dot(normal[g]) < cos_max;
    }
  drop_short_networks(mesh, adjacency, crease);
  return crease;
}

Creases::Creases(const TriMesh& mesh, const std::vector<std::array<Index, 3>>& adjacency, double angle_deg) {
  chain(mesh, adjacency, crease_edges(mesh, adjacency, angle_deg));
}

void Creases::chain(const TriMesh& mesh, const std::vector<std::array<Index, 3>>& adjacency,
                    const std::vector<char>& crease) {
  const Index nv = mesh.n_vertices(), nf = mesh.n_faces();
  auto from = [&](Index e) { return mesh.faces[e / 3][e % 3]; };
  auto to = [&](Index e) { return mesh.faces[e / 3][(e % 3 + 1) % 3]; };
  // Each crease edge once, as the half of its lower-numbered triangle, listed per vertex.
  std::vector<Index> start(nv + 1, 0), edges;
  std::vector<char> border(nv, 0);
  auto canonical = [&](Index f, Index k) { return adjacency[f][k] > f; };
  for (Index f = 0; f < nf; ++f)
    for (Index k = 0; k < 3; ++k) {
      const Index e = 3 * f + k;
      if (adjacency[f][k] == kNone) border[from(e)] = border[to(e)] = 1;
      if (crease[e] && canonical(f, k)) ++start[from(e) + 1], ++start[to(e) + 1], ++edges_;
    }
  // None (every run without a crease angle): empty() answers every query, and the arrays
  // below would be 30 bytes a triangle of kNone.
  if (edges_ == 0) return;
  for (Index v = 0; v < nv; ++v) start[v + 1] += start[v];
  edges.resize(start[nv]);
  std::vector<Index> fill(start.begin(), start.end() - 1);
  for (Index f = 0; f < nf; ++f)
    for (Index k = 0; k < 3; ++k)
      if (crease[3 * f + k] && canonical(f, k))
        edges[fill[from(3 * f + k)]++] = edges[fill[to(3 * f + k)]++] = 3 * f + k;
  auto other_end = [&](Index e, Index v) { return from(e) == v ? to(e) : from(e); };
  // The point `reach` along the creases from v by edge e, or where they stop short of it
  // (an end, a meeting, the border, or back at v round a loop).
  auto along = [&](Index v, Index e, double reach) {
    const Index first = v;
    for (double gone = 0;;) {
      const Index w = other_end(e, v);
      gone += (mesh.positions[w] - mesh.positions[v]).norm();
      if (gone >= reach || w == first || border[w] || start[w + 1] - start[w] != 2) return mesh.positions[w];
      e = edges[start[w]] == e ? edges[start[w] + 1] : edges[start[w]];
      v = w;
    }
  };
  const double reach = kTurnReach * mean_edge_length(mesh);
  corner_.assign(nv, 0);
  for (Index v = 0; v < nv; ++v) {
    const Index degree = start[v + 1] - start[v];
    if (degree == 0) continue;
    bool corner = degree != 2 || border[v];
    // A turn counts where the curve turns at v and still does a few edges on: a noisy
    // crease zigzags from edge to edge, and corners at its zigzags held its vertices at the
    // input's spacing.
    auto turns = [&](const Vec3& back, const Vec3& ahead) {
      const Vec3& p = mesh.positions[v];
      return (p - back).normalized().dot((ahead - p).normalized()) < std::cos(M_PI / 4);
    };
    if (!corner) {
      const Index in = edges[start[v]], out = edges[start[v] + 1];
      corner = turns(mesh.positions[other_end(in, v)], mesh.positions[other_end(out, v)]) &&
               turns(along(v, in, reach), along(v, out, reach));
    }
    corner_[v] = corner;
    corners_ += corner;
  }
  // Chains, first from every corner, then round the loops that are left.
  std::vector<char> used(3 * std::size_t(nf), 0);
  edge_curve_.assign(3 * std::size_t(nf), kNone);
  edge_segment_.assign(3 * std::size_t(nf), kNone);
  vertex_curve_.assign(nv, kNone);
  vertex_index_.assign(nv, kNone);
  auto walk = [&](Index v, Index e) {
    Curve c;
    c.vertices.push_back(v);
    const Index id = Index(curves_.size());
    for (;;) {
      used[e] = 1;
      const Index f = e / 3, k = e % 3, g = adjacency[f][k];
      Index l = 0;
      while (adjacency[g][l] != f || !crease[3 * g + l]) ++l;  // the same edge in g
      const Index seg = Index(c.faces.size());
      for (Index half : {e, 3 * g + l}) edge_curve_[half] = id, edge_segment_[half] = seg;
      c.faces.push_back(f);
      c.edge.push_back(std::uint8_t(k));
      const Index w = other_end(e, v);
      if (corner_[w]) {  // possibly the corner it started from
        c.vertices.push_back(w);
        break;
      }
      if (w == c.vertices.front()) {  // round a loop without a corner
        c.closed = true;
        break;
      }
      vertex_curve_[w] = id, vertex_index_[w] = Index(c.vertices.size());
      c.vertices.push_back(w);
      const Index next = edges[start[w]] == e ? edges[start[w] + 1] : edges[start[w]];
      v = w, e = next;
    }
    if (c.closed) vertex_curve_[c.vertices[0]] = id, vertex_index_[c.vertices[0]] = 0;
    curves_.push_back(std::move(c));
  };
  for (Index v = 0; v < nv; ++v)
    if (corner_[v])
      for (Index i = start[v]; i < start[v + 1]; ++i)
        if (!used[edges[i]]) walk(v, edges[i]);
  for (Index v = 0; v < nv; ++v)
    for (Index i = start[v]; i < start[v + 1]; ++i)
      if (!used[edges[i]]) walk(v, edges[i]);
}

Creases::Place Creases::place_of_vertex(Index v) const {
  Place place;
  if (empty() || v >= corner_.size()) return place;
  place.corner = corner_[v];
  place.curve = vertex_curve_[v];
  if (place.curve != kNone) place.s = double(vertex_index_[v]);
  return place;
}

Creases::Place Creases::place_of(const TriMesh& mesh, Index face, const Vec3& p, double tolerance) const {
  Place place;
  if (empty() || face >= mesh.n_faces()) return place;
  const auto& t = mesh.faces[face];
  for (Index v : t)
    if ((p - mesh.positions[v]).norm() <= tolerance) return place_of_vertex(v);
  for (Index k = 0; k < 3; ++k) {
    const Index e = 3 * face + k;
    if (edge_curve_[e] == kNone) continue;
    const Vec3 &a = mesh.positions[t[k]], &b = mesh.positions[t[(k + 1) % 3]];
    const double len2 = (b - a).squaredNorm();
    const double x = len2 > 0 ? std::clamp((p - a).dot(b - a) / len2, 0.0, 1.0) : 0.0;
    if ((a + x * (b - a) - p).norm() > tolerance) continue;
    const Curve& c = curves_[edge_curve_[e]];
    const Index seg = edge_segment_[e];
    const bool forward = c.vertices[seg] == t[k];
    place.curve = edge_curve_[e];
    place.s = double(seg) + (forward ? x : 1 - x);
    return place;
  }
  return place;
}

Creases::CurvePoint Creases::on_segment(const TriMesh& mesh, const Curve& c, Index i, double t) const {
  const Index f = c.faces[i], k = c.edge[i];
  const auto& tri = mesh.faces[f];
  const bool forward = tri[k] == c.vertices[i];
  double w[3] = {0, 0, 0};
  w[k] = forward ? 1 - t : t;
  w[(k + 1) % 3] = forward ? t : 1 - t;
  CurvePoint x;
  x.foot.face = f;
  x.foot.u = w[1], x.foot.v = w[2];
  x.foot.point = w[0] * mesh.positions[tri[0]] + w[1] * mesh.positions[tri[1]] + w[2] * mesh.positions[tri[2]];
  x.s = double(i) + t;
  return x;
}

Creases::CurvePoint Creases::at(const TriMesh& mesh, Index c, double s) const {
  const Curve& curve = curves_[c];
  const double n = span(c);
  if (curve.closed) s -= n * std::floor(s / n);
  s = std::clamp(s, 0.0, n);
  const Index i = std::min(Index(s), Index(curve.faces.size()) - 1);
  return on_segment(mesh, curve, i, s - double(i));
}

Creases::CurvePoint Creases::closest(const TriMesh& mesh, Index c, const Vec3& p, double s, double back,
                                     double ahead) const {
  const Curve& curve = curves_[c];
  const double n = span(c);
  double lo = s - back, hi = s + ahead;
  if (!curve.closed) lo = std::max(lo, 0.0), hi = std::min(hi, n);
  if (hi - lo > n) lo = s - 0.5 * n, hi = s + 0.5 * n;  // once round a loop
  CurvePoint best;
  const auto& P = mesh.positions;
  const Index segments = Index(curve.faces.size());
  for (double i = std::floor(lo); i < hi; ++i) {
    const Index seg = curve.closed ? Index(i - n * std::floor(i / n)) : Index(i);
    if (seg >= segments) break;
    const Vec3 &a = P[curve.vertices[seg]], &b = P[curve.vertices[(seg + 1) % curve.vertices.size()]];
    const double len2 = (b - a).squaredNorm();
    const double t0 = std::max(lo - i, 0.0), t1 = std::min(hi - i, 1.0);
    const double t = std::clamp(len2 > 0 ? (p - a).dot(b - a) / len2 : 0.0, t0, t1);
    const double d = (a + t * (b - a) - p).norm();
    if (best.foot.found() && d >= best.foot.distance) continue;
    best = on_segment(mesh, curve, seg, t);
    best.foot.distance = d;
  }
  return best;
}

double Creases::ahead_of(Index c, double s, double t) const {
  const double d = t - s, n = span(c);
  return curves_[c].closed ? d - n * std::floor(d / n) : d;
}

}  // namespace qs
