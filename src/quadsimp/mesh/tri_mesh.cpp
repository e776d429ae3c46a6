// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/mesh/tri_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <utility>

#include "quadsimp/mesh/tri_topology.h"

namespace qs {
namespace detail {

CornersAround corners_around(const TriMesh& m) {
  CornersAround a;
  a.start.assign(m.n_vertices() + 1, 0);
  for (const auto& t : m.faces)
    for (Index v : t) ++a.start[v + 1];
  std::partial_sum(a.start.begin(), a.start.end(), a.start.begin());
  a.corner.resize(a.start.back());
  std::vector<Index> fill(a.start.begin(), a.start.end() - 1);
  for (Index f = 0; f < m.n_faces(); ++f)
    for (Index k = 0; k < 3; ++k) a.corner[fill[m.faces[f][k]]++] = 3 * f + k;
  return a;
}

std::vector<std::array<Index, 3>> adjacency_from(const TriMesh& t, const CornersAround& around, bool* nonmanifold) {
  std::vector<std::array<Index, 3>> adj(t.faces.size(), {kNone, kNone, kNone});
  if (nonmanifold) *nonmanifold = false;
  for (Index f = 0; f < t.n_faces(); ++f)
    for (Index k = 0; k < 3; ++k) {
      if (adj[f][k] != kNone) continue;
      const Index a = t.faces[f][k], b = t.faces[f][(k + 1) % 3];
      int others = 0;
      for (Index i = around.start[a]; i < around.start[a + 1]; ++i) {
        const Index g = around.corner[i] / 3;
        if (g == f) continue;
        const auto& tg = t.faces[g];
        Index j = 0;
        while (j < 3 && !((tg[j] == a && tg[(j + 1) % 3] == b) || (tg[j] == b && tg[(j + 1) % 3] == a))) ++j;
        if (j == 3) continue;
        if (++others == 1) {
          adj[f][k] = g;
          adj[g][j] = f;
        }
        if (!nonmanifold || *nonmanifold) break;
      }
      if (others > 1) *nonmanifold = true;
    }
  return adj;
}

}  // namespace detail

namespace {

std::pair<Vec3, Vec3> bbox(const std::vector<Vec3>& positions) {
  Vec3 lo = positions.empty() ? Vec3::Zero() : positions[0], hi = lo;
  for (const Vec3& p : positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return {lo, hi};
}

// The low 21 bits of x spread to every third bit: one axis of a Morton code.
std::uint64_t spread_bits3(std::uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

}  // namespace

using detail::adjacency_from;
using detail::corners_around;

double thinness(const TriMesh& m, const std::array<Index, 3>& t, Index& longest) {
  const auto& P = m.positions;
  double l2 = -1;
  for (Index k = 0; k < 3; ++k) {
    const double e2 = (P[t[(k + 1) % 3]] - P[t[k]]).squaredNorm();
    if (e2 > l2) l2 = e2, longest = k;
  }
  return m.area_normal(t).norm() / l2;
}

void sort_spatially(TriMesh& m) {
  if (m.faces.empty()) return;
  Vec3 lo = m.positions[0], hi = m.positions[0];
  for (const Vec3& p : m.positions) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double scale = double((1u << 21) - 1) / std::max((hi - lo).maxCoeff(), 1e-300);
  std::vector<std::pair<std::uint64_t, Index>> order(m.faces.size());  // (Morton code of the centroid, face)
  for (Index f = 0; f < m.n_faces(); ++f) {
    const auto& t = m.faces[f];
    const Vec3 c = ((m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]) / 3.0 - lo) * scale;
    order[f] = {spread_bits3(std::uint64_t(c.x())) | spread_bits3(std::uint64_t(c.y())) << 1 |
                    spread_bits3(std::uint64_t(c.z())) << 2,
                f};
  }
  std::sort(order.begin(), order.end());
  // Vertices are renumbered in the order the sorted faces first use them.
  std::vector<Index> new_id(m.n_vertices(), kNone);
  std::vector<Vec3> positions;
  positions.reserve(m.positions.size());
  std::vector<std::array<Index, 3>> faces(m.faces.size());
  for (std::size_t i = 0; i < order.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const Index old = m.faces[order[i].second][k];
      if (new_id[old] == kNone) {
        new_id[old] = Index(positions.size());
        positions.push_back(m.positions[old]);
      }
      faces[i][k] = new_id[old];
    }
  m.faces = std::move(faces);
  m.positions = std::move(positions);
}

std::vector<std::array<Index, 3>> triangle_adjacency(const TriMesh& t) { return adjacency_from(t, corners_around(t)); }

double surface_area(const TriMesh& t) {
  double area = 0;
  for (const auto& f : t.faces) area += 0.5 * t.area_normal(f).norm();
  return area;
}

std::vector<Vec3> vertex_area_normals(const TriMesh& t) {
  std::vector<Vec3> normals(t.n_vertices(), Vec3::Zero());
  for (const auto& f : t.faces) {
    const Vec3 n = t.area_normal(f);
    for (Index v : f) normals[v] += n;
  }
  return normals;
}

std::vector<Vec3> vertex_angle_normals(const TriMesh& t) {
  std::vector<Vec3> normals(t.n_vertices(), Vec3::Zero());
  for (const auto& f : t.faces) {
    const Vec3 area_normal = t.area_normal(f);
    if (!(area_normal.squaredNorm() > 0)) continue;
    const Vec3 n = area_normal.normalized();
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = t.positions[f[k]];
      const Vec3 a = t.positions[f[(k + 1) % 3]] - p, b = t.positions[f[(k + 2) % 3]] - p;
      normals[f[k]] += std::atan2(a.cross(b).norm(), a.dot(b)) * n;
    }
  }
  for (Vec3& n : normals)
    if (n.squaredNorm() > 0) n.normalize();
  return normals;
}

VertexRings vertex_rings(const TriMesh& t) {
  const Index nv = t.n_vertices();
  VertexRings r;
  r.start.assign(nv + 1, 0);
  for (const auto& f : t.faces)
    for (Index v : f) r.start[v + 1] += 2;
  std::partial_sum(r.start.begin(), r.start.end(), r.start.begin());
  std::vector<Index> all(r.start[nv]), fill(r.start.begin(), r.start.end() - 1);
  for (const auto& f : t.faces)
    for (int k = 0; k < 3; ++k) {
      all[fill[f[k]]++] = f[(k + 1) % 3];
      all[fill[f[k]]++] = f[(k + 2) % 3];
    }
  // Sorted, an inner edge's other end appears twice in a row (once per triangle).
  r.border.assign(nv, 0);
  r.next.reserve(all.size() / 2);
  for (Index v = 0; v < nv; ++v) {
    const auto first = all.begin() + r.start[v], last = all.begin() + r.start[v + 1];
    std::sort(first, last);
    r.start[v] = Index(r.next.size());
    for (auto i = first; i != last;) {
      const auto j = std::find_if(i, last, [&](Index x) { return x != *i; });
      if (j - i == 1) r.border[v] = 1;
      r.next.push_back(*i);
      i = j;
    }
  }
  r.start[nv] = Index(r.next.size());
  return r;
}

std::pair<Vec3, Vec3> used_bbox(const TriMesh& m) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& f : m.faces)
    for (Index v : f)
      if (v < m.n_vertices()) lo = lo.cwiseMin(m.positions[v]), hi = hi.cwiseMax(m.positions[v]);
  if (m.faces.empty()) lo = hi = Vec3::Zero();
  return {lo, hi};
}

double mean_edge_length(const TriMesh& t) {
  double sum = 0;
  for (const auto& f : t.faces)
    for (int k = 0; k < 3; ++k) sum += (t.positions[f[k]] - t.positions[f[(k + 1) % 3]]).norm();
  return t.n_faces() ? sum / (3.0 * t.n_faces()) : 0.0;
}

double bbox_diagonal(const std::vector<Vec3>& positions) {
  const auto [lo, hi] = bbox(positions);
  return (hi - lo).norm();
}

Vec3 working_origin(const std::vector<Vec3>& positions) {
  const auto [lo, hi] = bbox(positions);
  const Vec3 centre = 0.5 * (lo + hi);
  return centre.norm() > (hi - lo).norm() ? centre : Vec3::Zero();
}

std::vector<Vec3> unit_normals(const TriMesh& m) {
  std::vector<Vec3> normals(m.n_faces());
  for (Index f = 0; f < m.n_faces(); ++f) normals[f] = m.area_normal(m.faces[f]).normalized();
  return normals;
}

Index face_components(const std::vector<std::array<Index, 3>>& adjacency, std::vector<Index>& component,
                      const std::function<bool(Index, Index)>& joined) {
  const Index nf = Index(adjacency.size());
  detail::UnionFind uf(nf);
  for (Index f = 0; f < nf; ++f)
    for (Index g : adjacency[f])
      if (g != kNone && (!joined || joined(f, g))) uf.unite(f, g);
  component.assign(nf, kNone);
  std::vector<Index> id(nf, kNone);
  Index n = 0;
  for (Index f = 0; f < nf; ++f) {
    const Index root = uf.find(f);
    if (id[root] == kNone) id[root] = n++;
    component[f] = id[root];
  }
  return n;
}

Index folded_patches(const TriMesh& m, const std::vector<std::array<Index, 3>>& adjacency,
                     const std::vector<Vec3>& normals, std::vector<Index>& patch, double largest_share,
                     double turned_cos) {
  patch.clear();
  const auto joined = [&](Index f, Index g) { return normals[f].dot(normals[g]) >= turned_cos; };
  bool folds = false;  // most meshes have no edge turning back: no components to find
  for (Index f = 0; f < m.n_faces() && !folds; ++f)
    for (Index g : adjacency[f]) folds = folds || (g != kNone && !joined(f, g));
  if (!folds) return 0;
  std::vector<Index> piece, part;
  const Index pieces = face_components(adjacency, piece), parts = face_components(adjacency, part, joined);
  std::vector<double> piece_area(pieces, 0.0), part_area(parts, 0.0);  // twice the areas
  for (Index f = 0; f < m.n_faces(); ++f) {
    const double area = m.area_normal(m.faces[f]).norm();
    piece_area[piece[f]] += area, part_area[part[f]] += area;
  }
  std::vector<Index> number(parts, kNone);
  Index n = 0;
  patch.assign(m.n_faces(), kNone);
  for (Index f = 0; f < m.n_faces(); ++f)
    if (part_area[part[f]] < largest_share * piece_area[piece[f]]) {
      if (number[part[f]] == kNone) number[part[f]] = n++;
      patch[f] = number[part[f]];
    }
  if (n == 0) patch.clear();
  return n;
}

TriMesh split_in_four(const TriMesh& t) {
  TriMesh out;
  out.positions = t.positions;
  std::map<std::pair<Index, Index>, Index> mid;
  auto midpoint = [&](Index a, Index b) {
    const auto [it, fresh] = mid.emplace(std::minmax(a, b), out.n_vertices());
    if (fresh) out.positions.push_back(0.5 * (t.positions[a] + t.positions[b]));
    return it->second;
  };
  for (const auto& f : t.faces) {
    const Index ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
    out.faces.push_back({f[0], ab, ca});
    out.faces.push_back({ab, f[1], bc});
    out.faces.push_back({ca, bc, f[2]});
    out.faces.push_back({ab, bc, ca});
  }
  return out;
}

std::vector<Index> first_equal_positions(const std::vector<Vec3>& positions) {
  // Sorted copies (position, then id), so that equal positions are neighbours and the
  // lowest id of each comes first; a copy sorts faster than ids that each look up
  // their position.
  std::vector<Index> first(positions.size());
  std::vector<std::pair<std::array<double, 3>, Index>> sorted;
  sorted.reserve(first.size());
  for (Index v = 0; v < Index(first.size()); ++v) {
    const Vec3& p = positions[v];
    first[v] = v;
    if (p.allFinite()) sorted.push_back({{p.x(), p.y(), p.z()}, v});  // NaN would break the order
  }
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 1; i < sorted.size(); ++i)
    if (sorted[i].first == sorted[i - 1].first) first[sorted[i].second] = first[sorted[i - 1].second];
  return first;
}

}  // namespace qs
