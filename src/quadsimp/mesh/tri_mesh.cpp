// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/mesh/tri_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <utility>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "quadsimp/util/errors.h"

namespace qs {
namespace {

// True when face f walks edge a->b in that direction.
bool has_directed(const std::array<Index, 3>& t, Index a, Index b) {
  for (int k = 0; k < 3; ++k)
    if (t[k] == a && t[(k + 1) % 3] == b) return true;
  return false;
}

// The corners (3 * face + k) at each vertex, as compressed rows: those of vertex v are
// corner[start[v]] to corner[start[v + 1] - 1].
struct CornersAround {
  std::vector<Index> start, corner;
};
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

// Whether u and w are corners of one face (an edge, in a manifold mesh).
bool share_a_face(const TriMesh& m, const CornersAround& around, Index u, Index w) {
  for (Index i = around.start[u]; i < around.start[u + 1]; ++i) {
    const auto& t = m.faces[around.corner[i] / 3];
    if (t[0] == w || t[1] == w || t[2] == w) return true;
  }
  return false;
}

// The neighbour across edge a-b is the other face around a that also has b. Linear,
// and twice as fast as sorting the 3F edges, which was a tenth of loading a mesh. With
// `nonmanifold`, each edge's faces are counted until one edge has more than two, which
// sets it (the adjacency is then only good for finding out).
std::vector<std::array<Index, 3>> adjacency_from(const TriMesh& t, const CornersAround& around,
                                                 bool* nonmanifold = nullptr) {
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

struct UnionFind {
  std::vector<Index> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), Index(0)); }
  Index find(Index x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(Index a, Index b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

void remove_unreferenced(TriMesh& m, CleanReport& r) {
  std::vector<Index> map(m.n_vertices(), kNone);
  for (const auto& t : m.faces)
    for (Index v : t) map[v] = 0;
  Index n = 0;
  for (Index v = 0; v < m.n_vertices(); ++v)
    if (map[v] == 0) {
      map[v] = n;
      m.positions[n++] = m.positions[v];
    }
  r.removed_unreferenced_vertices = m.n_vertices() - n;
  m.positions.resize(n);
  for (auto& t : m.faces)
    for (Index& v : t) v = map[v];
}

// Exact copies of a point are mostly one vertex written more than once: an unwelded seam,
// a triangle soup or a pole written once per segment, where the copies are on a border,
// or a surface written twice (a double-sided export), where every vertex of a piece has
// a copy. Other interior copies are two sheets that touch there: a grid vertex pushed
// across an edge exactly onto another vertex, its triangle folded flat onto its
// neighbour. Merged, their edges met: up to 30 faces were dropped at the edges made
// non-manifold, the result depended on face order, and one such grid was refused as not
// orientable. They stay apart, as close interior vertices do
// (merge_close_border_vertices()), and the fold is laid flat.
void merge_duplicate_vertices(TriMesh& m, CleanReport& r) {
  const std::vector<Index> same = first_equal_positions(m.positions);
  std::vector<Index> map = same;
  const Index n = Index(map.size());
  std::vector<char> copied(n, 0);
  for (Index v = 0; v < n; ++v)
    if (same[v] != v) copied[v] = copied[same[v]] = 1;
  if (std::find(copied.begin(), copied.end(), 1) != copied.end()) {
    // On a border: a neighbour in only one of its faces.
    const CornersAround around = corners_around(m);
    std::vector<Index> ring;
    const auto on_border = [&](Index v) {
      ring.clear();
      for (Index i = around.start[v]; i < around.start[v + 1]; ++i) {
        const auto& t = m.faces[around.corner[i] / 3];
        const Index k = around.corner[i] % 3;
        ring.push_back(t[(k + 1) % 3]);
        ring.push_back(t[(k + 2) % 3]);
      }
      std::sort(ring.begin(), ring.end());
      for (std::size_t i = 0; i < ring.size(); ++i)
        if ((i == 0 || ring[i] != ring[i - 1]) && (i + 1 == ring.size() || ring[i] != ring[i + 1])) return true;
      return false;
    };
    std::vector<char> seam(n, 0);  // per first copy: whether any copy is on a border
    for (Index v = 0; v < n; ++v)
      if (copied[v] && on_border(v)) seam[same[v]] = 1;
    UnionFind piece(n);
    for (const auto& t : m.faces) piece.unite(t[0], t[1]), piece.unite(t[0], t[2]);
    std::vector<char> all_copied(n, 1);  // per piece
    for (const auto& t : m.faces)
      for (Index v : t)
        if (!copied[v]) all_copied[piece.find(v)] = 0;
    for (Index v = 0; v < n; ++v)
      if (same[v] != v && !seam[same[v]] && !(all_copied[piece.find(v)] && all_copied[piece.find(same[v])]))
        map[v] = v;
  }
  for (Index v = 0; v < n; ++v) r.merged_duplicate_vertices += map[v] != v;
  for (auto& t : m.faces)
    for (Index& v : t) v = map[v];
}

std::pair<Vec3, Vec3> bbox(const std::vector<Vec3>& positions) {
  Vec3 lo = positions.empty() ? Vec3::Zero() : positions[0], hi = lo;
  for (const Vec3& p : positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return {lo, hi};
}

// Rounding leaves copies of one point a few ulps apart (a pole written once per
// triangle of its fan, an unwelded seam): exact merging misses them, and they bound a
// hole of no size whose border the simplifier must keep (on a sphere: edges of length
// 0 in the result, and with the border preserved a crumpled one). Border vertices closer
// than a millionth of the diagonal, far below any sampled surface's spacing and above
// float32 rounding, are merged into the lowest index, with any vertex that close to one
// of them. Not two interior vertices: two sheets of a scan can touch closer than that (a
// 1.1M-triangle subdivided armadillo: 6 pairs), and merging them would make the edges
// there non-manifold. `adj` as adjacency_from() gives it; returns whether any vertex
// was merged.
bool merge_close_border_vertices(TriMesh& m, const std::vector<std::array<Index, 3>>& adj, CleanReport& r) {
  // 0: unreferenced (exact copies merged before), 1: referenced, 2: on the border.
  std::vector<char> kind(m.n_vertices(), 0);
  for (const auto& t : m.faces)
    for (Index v : t) kind[v] = 1;
  bool any_border = false;
  for (Index f = 0; f < m.n_faces(); ++f)
    for (Index k = 0; k < 3; ++k)
      if (adj[f][k] == kNone) kind[m.faces[f][k]] = kind[m.faces[f][(k + 1) % 3]] = 2, any_border = true;
  if (!any_border) return false;
  // Cells of 1024 eps, 21 bits per axis from the box's corner (the box spans 1000):
  // a vertex is compared with the border vertices in its cell, and with a neighbour
  // cell's only when within eps of it.
  const auto box = used_bbox(m);
  const Vec3 corner = box.first;  // a lambda below captures it: not a structured binding
  const double eps = 1e-6 * (box.second - box.first).norm(), cell = 1024 * eps;
  if (!(eps > 0)) return false;
  const auto cell_of = [&](Index v, int i) { return std::int64_t(std::floor((m.positions[v][i] - corner[i]) / cell)); };
  const auto key_of = [](std::int64_t x, std::int64_t y, std::int64_t z) {
    return std::uint64_t(x) << 42 | std::uint64_t(y) << 21 | std::uint64_t(z);
  };
  std::vector<std::pair<std::uint64_t, Index>> sorted;
  for (Index v = 0; v < m.n_vertices(); ++v)
    if (kind[v] == 2) sorted.push_back({key_of(cell_of(v, 0), cell_of(v, 1), cell_of(v, 2)), v});
  std::sort(sorted.begin(), sorted.end());
  UnionFind sets(m.n_vertices());
  // Every referenced vertex joins the border vertices within eps of it: border copies
  // with each other, and a copy that exact merging joined with its mirror image
  // (sin(pi - x) == sin(x) on a pole written once per segment, away from the origin),
  // which can sit inside a fold of the zero-size hole with no border edge of its own.
  // Interior vertices near no border vertex stay apart (see above).
  for (Index v = 0; v < m.n_vertices(); ++v) {
    if (!kind[v]) continue;
    std::int64_t c[3];
    int lo[3], hi[3];  // neighbour cells within eps along each axis
    for (int i = 0; i < 3; ++i) {
      c[i] = cell_of(v, i);
      const double x = m.positions[v][i] - corner[i] - cell * double(c[i]);
      lo[i] = x < eps && c[i] > 0 ? -1 : 0;
      hi[i] = cell - x < eps ? 1 : 0;
    }
    for (int dx = lo[0]; dx <= hi[0]; ++dx)
      for (int dy = lo[1]; dy <= hi[1]; ++dy)
        for (int dz = lo[2]; dz <= hi[2]; ++dz) {
          const std::pair<std::uint64_t, Index> k{key_of(c[0] + dx, c[1] + dy, c[2] + dz), 0};
          const auto [first, last] = std::equal_range(sorted.begin(), sorted.end(), k,
                                                      [](const auto& a, const auto& b) { return a.first < b.first; });
          for (auto it = first; it != last; ++it)
            if ((m.positions[v] - m.positions[it->second]).squaredNorm() <= eps * eps) sets.unite(v, it->second);
        }
  }
  Index merged = 0;
  for (Index v = 0; v < m.n_vertices(); ++v) merged += kind[v] && sets.find(v) != v;
  if (!merged) return false;
  r.merged_close_vertices += merged;
  for (auto& t : m.faces)
    for (Index& v : t) v = sets.find(v);
  return true;
}

// A crack: two paths of border edges between the same two vertices, one along the other.
// CAD tessellations make them where they mesh neighbouring patches apart: each side's
// vertices lie along the other side's edges (T-junctions), on them while the patches are
// flat, off them by the sagitta when curved (a twentieth of an edge that turns by 25
// degrees). The simplifier kept such a crack open, a hole's border. A border edge a-b is
// split at the border vertices that follow a, or b, along it: each further along than the
// one before, no further from it than an arc through a and b whose middle is kCrackSagitta
// of its length off it, and the walk reaching the other end or going on past it (a hole's
// sharp corner does not). The split gives the other side's edges new vertices along them
// in turn, and the passes go on until the sides share every edge (kCrackPasses at most). A
// thin hole so bounded closes too; a hole's far side is not along its edges. The edge's
// triangle is fanned out from its third corner; a split that would give that corner an
// edge it has already is left. Returns the number of vertices taken into edges.
constexpr double kCrackSagitta = 0.125;
constexpr int kCrackPasses = 16;
Index zip_cracks(TriMesh& m, std::vector<std::array<Index, 3>> adj) {
  const auto& P = m.positions;
  Index zipped = 0;
  std::vector<Index> start, along, fill;
  std::vector<char> leaves;  // per entry of `along`: whether its border edge runs from the vertex
  std::vector<std::pair<double, Index>> cut;  // the vertices an edge is split at, by where along it
  std::vector<Index> fan;                     // a, the vertices of `cut`, b
  for (int pass = 0; pass < kCrackPasses; ++pass) {
    // Each vertex's neighbours along the border, as compressed rows.
    start.assign(m.n_vertices() + 1, 0);
    bool any_border = false;
    for (Index f = 0; f < m.n_faces(); ++f)
      for (Index k = 0; k < 3; ++k)
        if (adj[f][k] == kNone) ++start[m.faces[f][k] + 1], ++start[m.faces[f][(k + 1) % 3] + 1], any_border = true;
    if (!any_border) break;
    std::partial_sum(start.begin(), start.end(), start.begin());
    along.resize(start.back());
    leaves.resize(start.back());
    fill.assign(start.begin(), start.end() - 1);
    for (Index f = 0; f < m.n_faces(); ++f)
      for (Index k = 0; k < 3; ++k)
        if (adj[f][k] == kNone) {
          const Index a = m.faces[f][k], b = m.faces[f][(k + 1) % 3];
          leaves[fill[a]] = 1, along[fill[a]++] = b;
          leaves[fill[b]] = 0, along[fill[b]++] = a;
        }
    CornersAround corners;  // built for the first split tried
    const auto has_edge = [&](Index u, Index w) {
      if (corners.start.empty()) corners = corners_around(m);
      return share_a_face(m, corners, u, w);
    };
    std::vector<char> taken(m.n_vertices(), 0);  // split into an edge this pass
    std::set<std::pair<Index, Index>> made;      // the edges this pass's fans made (lowest vertex first)
    const auto key = [](Index x, Index y) { return std::pair<Index, Index>(std::min(x, y), std::max(x, y)); };
    // Into `cut`, the border vertices that follow a (or b) along a-b, each further along
    // than the one before, the nearest step first. True when the walk reaches the other
    // end or goes on past it: a crack, not a hole's corner.
    const auto walk = [&](Index a, Index b, Index o, bool from_a) {
      const Vec3 ab = P[b] - P[a];
      const double len2 = ab.squaredNorm();
      cut.clear();
      if (!(len2 > 0)) return false;
      Index v = from_a ? a : b;
      double t_v = from_a ? 0.0 : 1.0;
      for (;;) {
        Index next = kNone;
        double t_next = 0;
        for (Index i = start[v]; i < start[v + 1]; ++i) {
          // The far side of a crack runs against a-b: from b back to a. A walk along a
          // border running the other way (around a hole, through a vertex where holes
          // touch) made a fan edge run the way its other triangle does, and glmark2's
          // bunny, split once, with a tenth of its triangles taken out at random, could no
          // longer be oriented.
          if (leaves[i] != !from_a) continue;
          const Index w = along[i];
          if (w == (from_a ? b : a) && !cut.empty()) return true;
          if (w == a || w == b || w == o || taken[w]) continue;
          const double t = (P[w] - P[a]).dot(ab) / len2;
          if (from_a ? t >= 1 : t <= 0) {
            if (!cut.empty()) return true;
            continue;
          }
          const double reach = 4 * kCrackSagitta * t * (1 - t);  // an arc's offset from its chord
          if (!(from_a ? t > t_v : t < t_v) || (P[a] + t * ab - P[w]).squaredNorm() > reach * reach * len2)
            continue;
          if (next == kNone || std::abs(t - t_v) < std::abs(t_next - t_v)) next = w, t_next = t;
        }
        if (next == kNone) return false;
        cut.push_back({t_next, next});
        v = next, t_v = t_next;
      }
    };
    // An edge a fan may make: one no other fan of this pass made, and new or, for the
    // walk's own edges, on the border. Else an edge got a third triangle: with a tenth of
    // the triangles of glmark2's bunny (split twice) taken out at random, the bunny could
    // then no longer be oriented.
    const auto may_make = [&](Index x, Index y, bool border_too) {
      if (made.count(key(x, y))) return false;
      if (!has_edge(x, y)) return true;
      return border_too && std::find(along.begin() + start[x], along.begin() + start[x + 1], y) !=
                               along.begin() + start[x + 1];
    };
    Index zipped_now = 0;
    const Index nf = m.n_faces();
    for (Index f = 0; f < nf; ++f)
      for (Index k = 0; k < 3; ++k) {
        if (adj[f][k] != kNone) continue;
        const Index a = m.faces[f][k], b = m.faces[f][(k + 1) % 3], o = m.faces[f][(k + 2) % 3];
        // One walk makes the fan, so that its edges along a-b are the walk's, and the one
        // from its last vertex to the end it went past.
        if (!walk(a, b, o, true) && !walk(a, b, o, false)) continue;
        std::sort(cut.begin(), cut.end());
        fan.assign(1, a);
        for (const auto& c : cut) fan.push_back(c.second);
        fan.push_back(b);
        bool ok = true;
        for (std::size_t x = 0; ok && x + 1 < fan.size(); ++x)
          ok = may_make(fan[x], fan[x + 1], true) && (x == 0 || may_make(o, fan[x], false));
        if (!ok) continue;
        m.faces[f] = {fan[0], fan[1], o};
        for (std::size_t x = 1; x + 1 < fan.size(); ++x) {
          m.faces.push_back({fan[x], fan[x + 1], o});
          taken[fan[x]] = 1;
          made.insert(key(o, fan[x]));
        }
        for (std::size_t x = 0; x + 1 < fan.size(); ++x) made.insert(key(fan[x], fan[x + 1]));
        zipped_now += Index(cut.size());
        break;  // one edge per triangle and pass
      }
    if (!zipped_now) break;
    zipped += zipped_now;
    adj = triangle_adjacency(m);
  }
  return zipped;
}

void remove_degenerate_and_duplicate_faces(TriMesh& m, CleanReport& r) {
  const auto [lo, hi] = used_bbox(m);
  const double min_area2 = std::pow(1e-12 * (hi - lo).norm(), 4);  // squared twice-area, relative to size
  std::vector<std::array<Index, 3>> kept;
  kept.reserve(m.faces.size());
  for (const auto& t : m.faces) {
    const bool repeated = t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    const bool flat = !repeated && m.area_normal(t).squaredNorm() <= min_area2;
    if (repeated || flat)
      ++r.removed_degenerate_faces;
    else
      kept.push_back(t);
  }
  // Duplicates: the same vertex set in any order; keep the first occurrence.
  std::vector<std::pair<std::array<Index, 3>, Index>> key(kept.size());
  for (Index f = 0; f < kept.size(); ++f) {
    auto s = kept[f];
    std::sort(s.begin(), s.end());
    key[f] = {s, f};
  }
  std::sort(key.begin(), key.end());
  std::vector<char> drop(kept.size(), 0);
  for (std::size_t i = 1; i < key.size(); ++i)
    if (key[i].first == key[i - 1].first) drop[key[i].second] = 1;
  m.faces.clear();
  for (Index f = 0; f < kept.size(); ++f)
    if (!drop[f]) m.faces.push_back(kept[f]);
    else ++r.removed_duplicate_faces;
}

// At an edge with more than two triangles, the two across which the surface runs on
// straightest are kept and the others removed: the pair whose wings (the directions from
// the edge to their third corners, across it) are the most opposite. A fin or a flap
// standing on a surface goes, whatever its size, and the surface stays whole. MeshLab's
// "Repair non Manifold Edges" removes the smallest triangles instead, which takes the
// surface's own triangle where a fin is larger than it and leaves a hole with the fin
// hinged on its edge (the bunny with 300 random fins: folded quads in the result).
// Splitting the edge's vertices, MeshLab's other method, keeps every triangle but cuts
// the surface open along the edge, and its sides would then be simplified apart.
void remove_faces_at_nonmanifold_edges(TriMesh& m, const CornersAround& around, CleanReport& r) {
  const Index nf = m.n_faces();
  std::vector<char> drop(nf, 0);
  std::vector<Index> on_edge;                 // the faces on edge a-b, in face order
  std::vector<std::pair<Index, Vec3>> wings;  // (face, unit wing) of those still there
  for (Index f = 0; f < nf; ++f)
    for (Index k = 0; k < 3; ++k) {
      const Index a = m.faces[f][k], b = m.faces[f][(k + 1) % 3];
      on_edge.clear();
      for (Index i = around.start[a]; i < around.start[a + 1]; ++i) {
        const auto& t = m.faces[around.corner[i] / 3];
        if (t[0] == b || t[1] == b || t[2] == b) on_edge.push_back(around.corner[i] / 3);
      }
      if (on_edge.size() < 3 || on_edge.front() != f) continue;  // each such edge once, from its first face
      const Vec3 along = (m.positions[b] - m.positions[a]).normalized();
      wings.clear();
      for (Index g : on_edge) {
        if (drop[g]) continue;
        Index third = 0;
        while (m.faces[g][third] == a || m.faces[g][third] == b) ++third;
        const Vec3 to_third = m.positions[m.faces[g][third]] - m.positions[a];
        wings.push_back({g, (to_third - to_third.dot(along) * along).normalized()});
      }
      if (wings.size() < 3) continue;
      std::size_t keep0 = 0, keep1 = 1;
      for (std::size_t p = 0; p < wings.size(); ++p)
        for (std::size_t q = p + 1; q < wings.size(); ++q)
          if (wings[p].second.dot(wings[q].second) < wings[keep0].second.dot(wings[keep1].second)) keep0 = p, keep1 = q;
      for (std::size_t p = 0; p < wings.size(); ++p)
        if (p != keep0 && p != keep1) drop[wings[p].first] = 1, ++r.removed_nonmanifold_faces;
    }
  Index kept = 0;
  for (Index f = 0; f < nf; ++f)
    if (!drop[f]) m.faces[kept++] = m.faces[f];
  m.faces.resize(kept);
}

// Flips faces so that every manifold edge is walked in opposite directions by its
// two faces. Per component, the orientation kept is the one most faces already had.
// The adjacency follows the flips, so that later steps can use it.
void orient(TriMesh& m, std::vector<std::array<Index, 3>>& adj, CleanReport& r, const std::string& src) {
  const Index nf = m.n_faces();
  std::vector<int> flip(nf, -1);
  std::vector<Index> stack, members;
  for (Index seed = 0; seed < nf; ++seed) {
    if (flip[seed] != -1) continue;
    flip[seed] = 0;
    stack = {seed};
    members.clear();
    while (!stack.empty()) {
      const Index f = stack.back();
      stack.pop_back();
      members.push_back(f);
      for (Index k = 0; k < 3; ++k) {
        const Index g = adj[f][k];
        if (g == kNone) continue;
        // f runs a -> b along this edge; g agrees with f if it runs b -> a.
        const Index a = m.faces[f][k], b = m.faces[f][(k + 1) % 3];
        const bool same_dir = has_directed(m.faces[g], a, b);
        const int want = flip[f] ^ int(same_dir);
        if (flip[g] == -1) {
          flip[g] = want;
          stack.push_back(g);
        } else if (flip[g] != want) {
          throw InvalidInput(src + ": the surface is not orientable (a Moebius-like strip)");
        }
      }
    }
    Index flipped = 0;
    for (Index f : members) flipped += Index(flip[f]);
    const bool invert = 2 * flipped > members.size();
    for (Index f : members) {
      if (bool(flip[f]) != invert) {
        std::swap(m.faces[f][1], m.faces[f][2]);
        std::swap(adj[f][0], adj[f][2]);  // edges 0-1, 1-2, 2-0 are now 0-2, 2-1, 1-0
        ++r.flipped_faces;
      }
    }
  }
}

// A vertex whose triangles form several fans (joined only at the vertex) gets one
// copy per extra fan; afterwards every vertex is a disc or half-disc.
void split_nonmanifold_vertices(TriMesh& m, CleanReport& r) {
  const Index nv = m.n_vertices();
  const CornersAround around = corners_around(m);
  const auto& start = around.start;
  const auto& corner = around.corner;

  std::vector<std::pair<Index, Index>> spokes;  // (other vertex, local corner index)
  for (Index v = 0; v < nv; ++v) {
    const Index b = start[v], n = start[v + 1] - b;
    if (n < 2) continue;
    UnionFind uf(n);
    spokes.clear();
    for (Index i = 0; i < n; ++i) {
      const Index f = corner[b + i] / 3, k = corner[b + i] % 3;
      spokes.push_back({m.faces[f][(k + 1) % 3], i});
      spokes.push_back({m.faces[f][(k + 2) % 3], i});
    }
    std::sort(spokes.begin(), spokes.end());
    for (std::size_t s = 1; s < spokes.size(); ++s)
      if (spokes[s].first == spokes[s - 1].first) uf.unite(spokes[s].second, spokes[s - 1].second);
    std::vector<Index> copy_of_root(n, kNone);
    for (Index i = 0; i < n; ++i) {
      const Index root = uf.find(i);
      if (root == 0) continue;  // the fan holding the first corner keeps v
      if (copy_of_root[root] == kNone) {
        copy_of_root[root] = Index(m.positions.size());
        m.positions.push_back(m.positions[v]);
        ++r.split_nonmanifold_vertices;
      }
      const Index f = corner[b + i] / 3, k = corner[b + i] % 3;
      m.faces[f][k] = copy_of_root[root];
    }
  }
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

// Whether the corner opposite edge k stands over the edge's inner four fifths: a thin
// triangle with its apex there is a cap, one with its apex near an end a needle (two
// corners almost together), whose flip only makes another needle.
bool apex_over_middle(const TriMesh& m, const std::array<Index, 3>& t, Index k) {
  const Vec3 &a = m.positions[t[k]], &b = m.positions[t[(k + 1) % 3]], &c = m.positions[t[(k + 2) % 3]];
  const double s = (c - a).dot(b - a) / (b - a).squaredNorm();
  return s > 0.1 && s < 0.9;
}

// Two kinds of triangle are mended by flipping one of their edges, the standard repairs
// (Botsch and Kobbelt 2001 for caps; MeshLab's "Remove Isolated Folded Faces by Edge
// Flip" for folds). No vertex moves, and the pair covers the same ground as before up to
// the cap's height or the fold's depth.
// - A cap: its apex lies almost on its longest edge (thinner than kCapThinness). A wall
//   no working mesh resolves, yet its normal is its own: glmark2's bunny has four, two
//   where it closes a hole along its base, standing at 64 degrees to it. Split finely,
//   a cap's inner vertices have only cap faces; the conversion paired them into quads
//   with no area, whose orientation every later move was checked against, and on one
//   machine a quad there kept an edge of 0.03 mu. Its longest edge is flipped when the
//   thinner of the two new triangles is less thin than before. Needles (the apex near
//   an end of that edge) are left: their flip is another needle. The datasets have no
//   cap (their thinnest triangle: 3.9e-3).
// - A fold: a single triangle turned back against all three neighbours by over 120
//   degrees (kFoldedBackCos; a Z-fold of a scan: glmark2's bunny has 2, bunny.ply 1, the armadillo 17,
//   16 of them mended). The edge flipped is one whose far neighbour lies under the
//   fold's apex. Over a fold the working mesh kept a flipped quad on that machine.
// Either flip is made only when both new triangles face like the neighbour they replace.
// Rounds of independent flips, so that a row of caps is taken from its ends inwards.
constexpr double kCapThinness = 1e-3;

// `adj` and `normals` (the faces' unit normals) are kept up to date.
Index mend_by_edge_flips(TriMesh& m, std::vector<std::array<Index, 3>>& adj, std::vector<Vec3>& normals) {
  // The longest edge of a cap, kNone for any other triangle.
  const auto cap_edge = [&](Index f, double& thin) {
    Index longest = 0;
    thin = thinness(m, m.faces[f], longest);
    return thin < kCapThinness && apex_over_middle(m, m.faces[f], longest) ? longest : kNone;
  };
  const auto folded = [&](Index f) {
    for (Index g : adj[f])
      if (g == kNone || normals[f].dot(normals[g]) >= kFoldedBackCos) return false;
    return true;
  };
  std::vector<Index> todo;  // most meshes have neither: nothing more is built for them
  double thin = 0;
  for (Index f = 0; f < m.n_faces(); ++f)
    if (cap_edge(f, thin) != kNone || folded(f)) todo.push_back(f);
  Index flips = 0;
  bool stale = false;  // flips since `adj` was built
  for (int round = 0; !todo.empty() && round < 64; ++round) {
    CornersAround around;  // built for the first flip tried
    if (stale) adj = adjacency_from(m, around = corners_around(m)), stale = false;
    // Flips edge k of f (corners k, k+1) if `better` accepts the new pair; f = (a, b, c)
    // and g = (b, a, o) become (c, a, o) and (c, o, b), oriented alike.
    std::vector<char> touched(m.n_vertices(), 0);
    const auto try_flip = [&](Index f, Index k, auto&& better) {
      const Index g = adj[f][k];
      if (g == kNone) return false;
      const auto& t = m.faces[f];
      const auto& tg = m.faces[g];
      const Index a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
      const Index o = tg[0] != a && tg[0] != b ? tg[0] : tg[1] != a && tg[1] != b ? tg[1] : tg[2];
      if (o == c || touched[a] || touched[b] || touched[c] || touched[o]) return false;
      if (around.start.empty()) around = corners_around(m);
      if (share_a_face(m, around, c, o)) return false;  // c-o an edge already
      const std::array<Index, 3> f2{c, a, o}, g2{c, o, b};
      const Vec3 ng = m.area_normal(tg);
      if (m.area_normal(f2).dot(ng) <= 0 || m.area_normal(g2).dot(ng) <= 0 || !better(f2, g2, tg)) return false;
      m.faces[f] = f2;
      m.faces[g] = g2;
      normals[f] = m.area_normal(f2).normalized();
      normals[g] = m.area_normal(g2).normalized();
      touched[a] = touched[b] = touched[c] = touched[o] = 1;
      stale = true;
      ++flips;
      return true;
    };
    std::vector<Index> left;
    const Index flips_before = flips;
    for (Index f : todo) {
      if (const Index k = cap_edge(f, thin); k != kNone) {
        left.push_back(f);
        try_flip(f, k, [&](const auto& f2, const auto& g2, const auto& tg) {
          Index unused;
          return std::min(thinness(m, f2, unused), thinness(m, g2, unused)) > std::min(thin, thinness(m, tg, unused));
        });
      } else if (folded(f)) {
        left.push_back(f);
        for (Index k = 0; k < 3; ++k)
          if (try_flip(f, k, [](const auto&...) { return true; })) break;
      }
    }
    if (flips == flips_before) break;
    todo.swap(left);
  }
  if (stale) adj = adjacency_from(m, corners_around(m));
  return flips;
}

// Gauss-Seidel's sweeps grow with the square of a patch's width: a noisy scan's rings of
// 100 to 400 vertices took 100 to 450 sweeps each, and bunny.ply with noise of 0.2% of its
// diagonal spent 5 of the 5.8 s it took to convert there. From this many vertices the
// embedding is solved directly; below, sweeps are cheaper than a factorisation (the
// datasets' patches have at most 13 vertices, and keep their positions to the bit).
constexpr std::size_t kSolveDirectlyFrom = 32;

// Puts each vertex of `vs` at the mean of the other corners of its triangles, all at
// once: a sparse symmetric system (each pair of corners counted as often as they share a
// triangle), the vertices outside `vs` fixed. False, with nothing moved, where that has no
// sound solution: a part of `vs` that reaches no fixed vertex makes the system singular
// (its unknowns came out at the origin), and a harmonic map lies within the box of the
// fixed vertices, so a solution outside it is rounding gone wrong.
// `row` maps vertices to unknowns: kNone everywhere on entry, and again on return.
bool solve_neighbour_means(TriMesh& m, const CornersAround& around, const std::vector<Index>& vs,
                           std::vector<Index>& row) {
  auto& P = m.positions;
  const Index n = Index(vs.size());
  for (Index i = 0; i < n; ++i) row[vs[i]] = i;
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixX3d fixed = Eigen::MatrixX3d::Zero(n, 3);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Vec3 lo = Vec3::Constant(kInf), hi = Vec3::Constant(-kInf);
  std::vector<Index> reached;  // unknowns with a fixed neighbour, then those connected to them
  for (Index i = 0; i < n; ++i) {
    const Index v = vs[i];
    entries.emplace_back(i, i, 2.0 * (around.start[v + 1] - around.start[v]));
    for (Index c = around.start[v]; c < around.start[v + 1]; ++c) {
      const auto& t = m.faces[around.corner[c] / 3];
      const Index k = around.corner[c] % 3;
      for (const Index u : {t[(k + 1) % 3], t[(k + 2) % 3]}) {
        if (row[u] != kNone) {
          entries.emplace_back(i, row[u], -1.0);
          continue;
        }
        fixed.row(i) += P[u].transpose();
        lo = lo.cwiseMin(P[u]), hi = hi.cwiseMax(P[u]);
        if (reached.empty() || reached.back() != i) reached.push_back(i);
      }
    }
  }
  for (Index v : vs) row[v] = kNone;
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  std::vector<char> linked(n, 0);
  for (Index i : reached) linked[i] = 1;
  for (std::size_t q = 0; q < reached.size(); ++q)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, reached[q]); it; ++it)
      if (!linked[it.row()]) linked[it.row()] = 1, reached.push_back(Index(it.row()));
  if (reached.size() < n) return false;
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(A);
  if (solver.info() != Eigen::Success) return false;
  const Eigen::MatrixX3d x = solver.solve(fixed);
  const Vec3 slack = 1e-6 * (hi - lo).cwiseMax(0.0).norm() * Vec3::Ones();
  for (Index i = 0; i < n; ++i) {
    const Vec3 p = x.row(i).transpose();
    if (!p.allFinite() || (p.array() < (lo - slack).array()).any() || (p.array() > (hi + slack).array()).any())
      return false;
  }
  for (Index i = 0; i < n; ++i) P[vs[i]] = x.row(i).transpose();
  return true;
}

// Moves each vertex of `vs` to the mean of the other corners of its triangles, sweep
// after sweep (Gauss-Seidel), until no vertex moves by more than `settled` (or 1,000
// sweeps); from kSolveDirectlyFrom vertices, solved directly where that is sound.
// `row`: as solve_neighbour_means() takes it.
void move_to_neighbour_means(TriMesh& m, const CornersAround& around, const std::vector<Index>& vs, double settled,
                             std::vector<Index>& row) {
  if (vs.size() >= kSolveDirectlyFrom && solve_neighbour_means(m, around, vs, row)) return;
  auto& P = m.positions;
  for (int sweep = 0; sweep < 1000; ++sweep) {
    double largest = 0;
    for (Index v : vs) {
      Vec3 sum = Vec3::Zero();
      for (Index i = around.start[v]; i < around.start[v + 1]; ++i) {
        const auto& t = m.faces[around.corner[i] / 3];
        const Index k = around.corner[i] % 3;
        sum += P[t[(k + 1) % 3]] + P[t[(k + 2) % 3]];
      }
      const Vec3 mean = sum / double(2 * (around.start[v + 1] - around.start[v]));
      largest = std::max(largest, (mean - P[v]).squaredNorm());
      P[v] = mean;
    }
    if (largest <= settled * settled) return;
  }
}

// A patch of several triangles folded back (glmark2's bunny's fold split in four twice is
// 16) has no one edge to flip. Its vertices move instead, each to the mean of the other
// corners of its triangles, in sweeps until they settle: a Tutte embedding of the patch
// inside the ring of vertices that stay, which lays it flat between them. Kept only if
// every triangle around a moved vertex then faces like the unmoved triangles there did
// (their summed normal) and none turns back against a neighbour. Else the vertices around
// the ones moved join them, ring by ring, while their region faces the way the patch's
// own surroundings do: a Tutte embedding lies flat inside a convex ring, and the ring of
// a sliver is long and thin (the armadillo split in four twice has 23 folded patches; 12
// lay flat inside their own ring, the others inside 1 to 6 more). A patch whose rings met
// another patch's vertices gets a second try at the end, and one still folded a last try
// that need only leave its region with fewer defects than it had. If none lays it flat,
// the patch stays as it was, for ReferenceSurface to mark. Border vertices stay. A quad mesh cannot
// follow a Z-fold, and the simplifier's care over a marked one (over_flap()) is not
// enough everywhere: on glmark2's bunny split before cleaning it left a flipped quad and
// homeometry down to 0.18 at 20,000 quads, on the armadillo split twice two flipped quads
// and 0.07. Returns the vertices moved; `mended` counts the patches laid flat.
constexpr int kUnfoldRings = 8;
// Rings are added while fewer vertices than this move: a large patch that will not lie
// flat costs sweeps over all of it for each ring (the unit tests' thin leaf on a stalk,
// 2,000 vertices: 0.1 s to put back, 0.9 s with eight rings).
constexpr std::size_t kUnfoldMostVertices = 1024;

// Folded patches that face the same way and share a vertex that may move are laid flat as
// one: one at a time, each held the vertices it shared with the other still, and neither
// lay flat (two slivers side by side on a grid split twice). Patches facing opposite ways
// stay apart: a post's overhanging wall and its head are both patches, and laid flat as
// one they flattened the post. Renumbers `patch` in the order of the patches' first
// triangles and returns the count.
Index join_patches_sharing_a_vertex(const TriMesh& m, const std::vector<char>& border, Index patches,
                                    std::vector<Index>& patch) {
  std::vector<Vec3> facing(patches, Vec3::Zero());
  for (Index f = 0; f < m.n_faces(); ++f)
    if (patch[f] != kNone) facing[patch[f]] += m.area_normal(m.faces[f]);
  std::vector<std::array<Index, 2>> at;  // (vertex, patch) for every corner that may move
  for (Index f = 0; f < m.n_faces(); ++f)
    if (patch[f] != kNone)
      for (Index v : m.faces[f])
        if (!border[v]) at.push_back({v, patch[f]});
  std::sort(at.begin(), at.end());
  at.erase(std::unique(at.begin(), at.end()), at.end());
  UnionFind sets(patches);
  for (std::size_t i = 0; i < at.size(); ++i)  // every two patches at one vertex
    for (std::size_t j = i + 1; j < at.size() && at[j][0] == at[i][0]; ++j)
      if (facing[at[i][1]].dot(facing[at[j][1]]) > 0) sets.unite(at[i][1], at[j][1]);
  std::vector<Index> number(patches, kNone);
  Index n = 0;
  for (Index p = 0; p < patches; ++p)  // the lowest part of each set is its root, and comes first
    if (sets.find(p) == p) number[p] = n++;
  for (Index& p : patch)
    if (p != kNone) p = number[sets.find(p)];
  return n;
}

// Whether each patch is a disc of triangles, by its Euler characteristic (V - E + F = 1;
// discs joined at a vertex count too). A fold is one: the surface turns back over itself
// and forward again. The overhanging wall of a post is a band round the post (0), and laid
// flat it squashed the post: coarse posts of 16 to 64 sides, walls leaning out by 20 to 60
// degrees, lost their overhang, rim moved in.
std::vector<char> patches_that_are_discs(const TriMesh& m, const std::vector<Index>& patch, Index patches) {
  std::vector<int> euler(patches, 0);
  std::vector<std::array<Index, 2>> corners;
  std::vector<std::array<Index, 3>> edges;
  for (Index f = 0; f < m.n_faces(); ++f)
    if (const Index p = patch[f]; p != kNone) {
      ++euler[p];
      for (int k = 0; k < 3; ++k) {
        const Index a = m.faces[f][k], b = m.faces[f][(k + 1) % 3];
        corners.push_back({p, a});
        edges.push_back({p, std::min(a, b), std::max(a, b)});
      }
    }
  std::sort(corners.begin(), corners.end());
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < corners.size(); ++i)
    if (i == 0 || corners[i] != corners[i - 1]) ++euler[corners[i][0]];
  for (std::size_t i = 0; i < edges.size(); ++i)
    if (i == 0 || edges[i] != edges[i - 1]) --euler[edges[i][0]];
  std::vector<char> disc(patches);
  for (Index p = 0; p < patches; ++p) disc[p] = euler[p] == 1;
  return disc;
}

Index unfold_patches(TriMesh& m, const std::vector<std::array<Index, 3>>& adj, const std::vector<Vec3>& normals,
                     Index& mended) {
  std::vector<Index> patch;
  // A sheet's two sides are about half of it each. 1e-4 missed five vertices of a
  // 128 x 128 grid pushed past their neighbours, 1e-3 a column of twelve pushed 3.5
  // cells on a 64 x 64 one (flipped quads followed); the datasets' patches are the same
  // at any share from 1e-4 to 1e-2. The side of a thin part with a sharp rim, a leaf on
  // a stalk, is a patch too, but laid flat it still faces against its surroundings, and
  // the check below puts it back.
  Index patches = folded_patches(m, adj, normals, patch, kLaidFlatShare, kLaidFlatCos);
  if (patches == 0) return 0;
  const CornersAround around = corners_around(m);
  std::vector<char> border(m.n_vertices(), 0);
  for (Index f = 0; f < m.n_faces(); ++f)
    for (Index k = 0; k < 3; ++k)
      if (adj[f][k] == kNone) border[m.faces[f][k]] = border[m.faces[f][(k + 1) % 3]] = 1;
  patches = join_patches_sharing_a_vertex(m, border, patches, patch);
  // held[v]: the patch whose vertices v is among, its own from the start, or one of its
  // rings while it tries and after it lay flat. A try's rings take vertices no patch holds.
  std::vector<std::vector<Index>> to_move(patches);
  std::vector<Index> held(m.n_vertices(), kNone);
  for (Index f = 0; f < m.n_faces(); ++f)
    if (patch[f] != kNone)
      for (Index v : m.faces[f])
        if (!border[v] && held[v] == kNone) held[v] = patch[f], to_move[patch[f]].push_back(v);

  auto& P = m.positions;
  std::vector<Index> seen(m.n_faces(), kNone), region, in_try(m.n_vertices(), kNone), newly_held;
  std::vector<Index> row(m.n_vertices(), kNone);  // move_to_neighbour_means()' unknowns
  Index visit = 0, tries = 0;  // mark `seen` per region and `in_try` per try
  std::vector<Vec3> before;
  Index moved = 0;
  bool met = false;  // whether the last try's rings met vertices another patch holds
  // Whether triangle f faces against `facing`, plus its edges turning back by more than
  // kFoldedBackCos: 0 for a sound triangle.
  const auto defects_of = [&](Index f, const Vec3& facing) {
    const Vec3 n = m.area_normal(m.faces[f]);
    Index bad = !(n.dot(facing) > 0);
    for (Index g : adj[f])
      bad += g != kNone && n.normalized().dot(m.area_normal(m.faces[g]).normalized()) < kFoldedBackCos;
    return bad;
  };
  // Lays patch p flat, ring by ring. `strict`: only a region left with no defect counts;
  // else (a last pass) one left with fewer defects than it had, whose patch itself is flat.
  const auto lay_flat = [&](Index p, bool strict) {
    std::vector<Index>& vs = to_move[p];
    const Index own = Index(vs.size()), try_id = tries++;
    for (Index v : vs) in_try[v] = try_id;
    newly_held.clear();
    met = false;
    // The way the triangles around the patch itself face (ring 0). The rings stop where
    // their region as a whole turns to face the other way: grown from a leaf's top down
    // its underside and a short stalk onto the disc below, the disc's triangles came to
    // outweigh the underside's, and the whole leaf and stalk laid flat on the disc passed
    // the checks. Stopping at the first triangle facing the other way kept the leaf too,
    // but laid 7 to 55% fewer of a noisy scan's folds flat (bunny.ply with noise added),
    // and checking every ring against ring 0's direction left one of the 23 folds of the
    // armadillo split twice, where the surface curves.
    Vec3 facing0 = Vec3::Zero();
    for (int ring = 0; ring <= kUnfoldRings && !vs.empty(); ++ring) {
      if (ring > 0) {  // the region's other vertices join the ones that move
        if (vs.size() >= kUnfoldMostVertices) break;
        for (Index f : region)
          for (Index v : m.faces[f]) {
            if (border[v] || in_try[v] == try_id) continue;
            if (held[v] != kNone) {
              met = true;
              continue;
            }
            if (held[v] == kNone) held[v] = p, newly_held.push_back(v);
            in_try[v] = try_id, vs.push_back(v);
          }
      }
      region.clear();
      ++visit;
      Vec3 facing = Vec3::Zero();
      double extent = 0;
      for (Index v : vs)
        for (Index i = around.start[v]; i < around.start[v + 1]; ++i) {
          const Index f = around.corner[i] / 3;
          if (seen[f] == visit) continue;
          seen[f] = visit;
          region.push_back(f);
          if (patch[f] == kNone) facing += m.area_normal(m.faces[f]);
          for (Index k = 0; k < 3; ++k) extent = std::max(extent, (P[m.faces[f][k]] - P[v]).norm());
        }
      if (facing == Vec3::Zero()) break;  // not isZero(): fuzzy by an absolute 1e-12
      if (ring == 0) facing0 = facing;
      else if (!(facing.dot(facing0) > 0)) break;
      before.clear();
      for (Index v : vs) before.push_back(P[v]);
      Index defects_before = 0;
      if (!strict)
        for (Index f : region) defects_before += defects_of(f, facing);
      move_to_neighbour_means(m, around, vs, 1e-9 * extent, row);
      // Strict: every triangle of the region sound. Last try: the patch's own, and fewer
      // defects in the region than before.
      bool flat = true;
      Index defects_after = 0;
      for (Index f : region) {
        const Index d = defects_of(f, facing);
        if (d > 0 && (strict || patch[f] == p)) {
          flat = false;
          break;
        }
        defects_after += d;
      }
      if (flat && (strict || defects_after < defects_before)) {
        ++mended, moved += Index(vs.size());
        return true;
      }
      for (std::size_t i = 0; i < vs.size(); ++i) P[vs[i]] = before[i];
    }
    for (Index v : newly_held) held[v] = kNone;  // free for the patches after it
    vs.resize(own);
    return false;
  };
  const std::vector<char> disc = patches_that_are_discs(m, patch, patches);
  // A patch whose rings met another patch's vertices is tried again at the end, once every
  // patch has moved: whether two folds a few triangles apart both lay flat depended on
  // which came first. Letting the second try take the vertices of patches laid flat was
  // not needed for that, and is not done: no try moves another patch's vertices.
  std::vector<Index> retry, left;
  for (Index p = 0; p < patches; ++p)
    if (disc[p] && !lay_flat(p, true)) (met ? retry : left).push_back(p);
  for (Index p : retry)
    if (!lay_flat(p, true)) left.push_back(p);
  // Noise turns triangles around a fold too, and a region with one of them left turned
  // never counted as flat: glmark2's bunny split twice, with noise of a tenth of its mean
  // edge, kept 10 of its 29 folds, and 11 defective quads at 20,000 over them. What the
  // strict tries left is laid flat where that leaves its region with fewer defects. Only
  // patches no strict try laid flat come here, so inputs without such leave as they were.
  std::sort(left.begin(), left.end());
  for (Index p : left) lay_flat(p, false);
  return moved;
}

}  // namespace

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

std::pair<Vec3, Vec3> used_bbox(const TriMesh& m) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& f : m.faces)
    for (Index v : f)
      if (v < m.n_vertices()) lo = lo.cwiseMin(m.positions[v]), hi = hi.cwiseMax(m.positions[v]);
  if (m.faces.empty()) lo = hi = Vec3::Zero();
  return {lo, hi};
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
  UnionFind uf(nf);
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

namespace {

// Lengths are squared and raised to the fourth power in double precision, and fitmaps
// (per length) are kept in single precision: bunny.ply gives the same quads, scaled, from
// 2^-100 to 2^120 times its size (2e-31 to 3e35 across; bench/RESULTS.md, "Units of
// length"). Past that the results degrade (2^150: 39 quads at automatic halting instead of
// 657; 2^1000: no quad at all), so meshes beyond these sizes, with a margin, are refused,
// before any tolerance relative to the size is taken.
constexpr double kSmallestDiagonal = 1e-30, kLargestDiagonal = 1e30;

void check_size(const TriMesh& m, const std::string& src) {
  const auto [lo, hi] = used_bbox(m);
  const double d = (hi - lo).stableNorm();  // norm() overflows past 1e154
  if (d >= kSmallestDiagonal && d <= kLargestDiagonal) return;
  char size[32];
  std::snprintf(size, sizeof size, "%.3g", d);
  throw InvalidInput(src + ": the mesh is " + size + " units across (its bounding box's diagonal); quadsimp takes "
                     "meshes from 1e-30 to 1e30 units across: scale it first (MeshLab: \"Transform: Scale, "
                     "Normalize\")");
}

}  // namespace

CleanReport clean(TriMesh& m, const std::string& src, const LogFn& log) {
  CleanReport r;
  if (m.positions.empty()) throw InvalidInput(src + ": the mesh is empty (no vertices)");
  if (m.faces.empty())
    throw InvalidInput(src + ": the mesh has no faces (" + std::to_string(m.n_vertices()) +
                       " vertices: a point cloud?); quadsimp needs a triangle surface");
  for (Index v = 0; v < m.n_vertices(); ++v)
    if (!m.positions[v].allFinite())
      throw InvalidInput(src + ": vertex " + std::to_string(v) + " has a NaN or infinite coordinate");
  for (Index f = 0; f < m.n_faces(); ++f)
    for (Index v : m.faces[f])
      if (v >= m.n_vertices())
        throw InvalidInput(src + ": face " + std::to_string(f) + " refers to vertex " +
                           std::to_string(v) + ", out of range (" + std::to_string(m.n_vertices()) +
                           " vertices)");
  check_size(m, src);

  merge_duplicate_vertices(m, r);
  remove_degenerate_and_duplicate_faces(m, r);
  if (m.faces.empty()) throw InvalidInput(src + ": every face is degenerate (zero area)");
  std::vector<std::array<Index, 3>> adj;
  {
    // adjacency_from() finds a non-manifold edge as it goes; the repair runs only for a
    // mesh that has one, on the same corners.
    const auto manifold_adjacency = [&] {
      bool nonmanifold = false;
      const CornersAround around = corners_around(m);
      auto found = adjacency_from(m, around, &nonmanifold);
      if (!nonmanifold) return found;
      remove_faces_at_nonmanifold_edges(m, around, r);
      return adjacency_from(m, corners_around(m));
    };
    adj = manifold_adjacency();
    if (merge_close_border_vertices(m, adj, r)) {
      remove_degenerate_and_duplicate_faces(m, r);
      adj = manifold_adjacency();
    }
    if ((r.zipped_t_junctions = zip_cracks(m, adj))) adj = manifold_adjacency();
    orient(m, adj, r, src);
  }
  split_nonmanifold_vertices(m, r);  // faces keep their neighbours
  std::vector<Vec3> normals = unit_normals(m);  // for both mends
  r.flipped_edges = mend_by_edge_flips(m, adj, normals);
  r.moved_vertices = unfold_patches(m, adj, normals, r.unfolded_patches);
  remove_unreferenced(m, r);
  // merged copies are not "unreferenced"
  r.removed_unreferenced_vertices -= r.merged_duplicate_vertices + r.merged_close_vertices;

  if (log) {
    auto note = [&](Index n, const char* what) {
      if (n) log(src + ": " + std::to_string(n) + " " + what);
    };
    note(r.merged_duplicate_vertices, "duplicate vertices merged");
    note(r.merged_close_vertices, "vertices merged with a border vertex closer than 1e-6 of the bounding-box diagonal");
    note(r.zipped_t_junctions,
         "border vertices lying along a border edge across a crack (T-junctions) taken into that edge, "
         "closing the crack");
    note(r.removed_degenerate_faces, "degenerate faces removed");
    note(r.removed_duplicate_faces, "duplicate faces removed");
    note(r.removed_nonmanifold_faces,
         "faces removed at edges shared by more than two triangles (non-manifold edges; at each, the two "
         "across which the surface runs on straightest are kept)");
    note(r.removed_unreferenced_vertices, "unreferenced vertices removed");
    note(r.split_nonmanifold_vertices, "non-manifold vertices split");
    note(r.flipped_faces, "faces re-oriented to match their neighbours");
    note(r.flipped_edges,
         "edges flipped to mend caps (triangles whose height is under 1e-3 of their longest edge) and "
         "single triangles folded back onto their neighbours");
    if (r.unfolded_patches)
      log(src + ": " + std::to_string(r.unfolded_patches) + " patches of triangles folded back onto the surface " +
          "laid flat (" + std::to_string(r.moved_vertices) + " vertices moved, each to the mean of its neighbours)");
  }
  return r;
}

}  // namespace qs
