// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/mesh/clean.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <stdexcept>
#include <utility>

#include "quadsimp/mesh/mend_folds.h"
#include "quadsimp/mesh/tri_topology.h"
#include "quadsimp/util/errors.h"

namespace qs {
namespace {

using detail::adjacency_from;
using detail::corners_around;
using detail::CornersAround;
using detail::mend_by_edge_flips;
using detail::share_a_face;
using detail::UnionFind;
using detail::unfold_patches;

// An undirected edge, its smaller vertex first.
std::pair<Index, Index> edge_key(Index a, Index b) { return {std::min(a, b), std::max(a, b)}; }
// Whether the edge a-b is among `edges` (edge_key()s, sorted).
bool is_among(const std::vector<std::pair<Index, Index>>& edges, Index a, Index b) {
  return !edges.empty() && std::binary_search(edges.begin(), edges.end(), edge_key(a, b));
}

// True when face f walks edge a->b in that direction.
bool has_directed(const std::array<Index, 3>& t, Index a, Index b) {
  for (int k = 0; k < 3; ++k)
    if (t[k] == a && t[(k + 1) % 3] == b) return true;
  return false;
}

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
// A non-orientable component (a Moebius strip; pymeshfix's planar_mesh.ply, whose twist
// is a few triangles wide) cannot be oriented whole: it is cut open along the edges where
// the orientation met itself reversed, as CGAL's orient_polygon_soup() cuts, and those
// edges are returned (each as its two vertices, in order) for split_nonmanifold_vertices()
// to part their sides. Breadth first, so that the search meets itself reversed half way
// round the twist, across the strip: a Moebius strip 128 quads long and 8 wide is cut
// along 8 edges, where depth first cut it along 128, its whole length (a Klein bottle
// 160 x 40: 40 edges against 320). Orientable components are oriented the same either
// way (an orientation is unique up to the flip of the whole).
std::vector<std::pair<Index, Index>> orient(TriMesh& m, std::vector<std::array<Index, 3>>& adj, CleanReport& r) {
  const Index nf = m.n_faces();
  const auto& P = m.positions;
  std::vector<int> flip(nf, -1);
  std::vector<Index> members;  // a component's faces in the order the search reached them
  std::vector<std::pair<Index, Index>> cut;
  // The flip that f's neighbour across edge k needs to agree with f: f runs a -> b along
  // the edge, and the neighbour agrees if it runs b -> a.
  auto wanted = [&](Index f, Index k) {
    return flip[f] ^ int(has_directed(m.faces[adj[f][k]], m.faces[f][k], m.faces[f][(k + 1) % 3]));
  };
  // Whether edge k of f, to an oriented neighbour, joins two faces that disagree.
  auto disagree = [&](Index f, Index k) { return adj[f][k] != kNone && flip[adj[f][k]] != wanted(f, k); };
  auto length = [&](Index f, Index k) { return (P[m.faces[f][k]] - P[m.faces[f][(k + 1) % 3]]).norm(); };
  std::vector<Index> work;
  for (Index seed = 0; seed < nf; ++seed) {
    if (flip[seed] != -1) continue;
    flip[seed] = 0;
    members.assign(1, seed);
    bool twisted = false;
    for (std::size_t next = 0; next < members.size(); ++next) {
      const Index f = members[next];
      for (Index k = 0; k < 3; ++k) {
        const Index g = adj[f][k];
        if (g == kNone) continue;
        const int want = wanted(f, k);
        if (flip[g] == -1) {
          flip[g] = want;
          members.push_back(g);
        } else {
          twisted |= flip[g] != want;
        }
      }
    }
    if (twisted) {
      // Where the search met itself the cut zigzags from triangle to triangle. Turning a
      // triangle over swaps its cut and uncut edges: turned wherever its cut edges are the
      // longer, the cut straightens (the Moebius strip 128 x 8: 15 edges and, at 300 quads,
      // a Hausdorff distance of 10.2e-3 of the diagonal at the zigzag, whose two sides were
      // coarsened apart; straightened, 8 edges and 5.9e-3). Each turn shortens the cut; the
      // bound only guards against rounding.
      work.assign(members.rbegin(), members.rend());
      for (std::size_t turns = 0; !work.empty() && turns < 8 * members.size();) {
        const Index f = work.back();
        work.pop_back();
        double on_cut = 0, off_cut = 0;
        for (Index k = 0; k < 3; ++k)
          if (adj[f][k] != kNone) (disagree(f, k) ? on_cut : off_cut) += length(f, k);
        if (!(on_cut > off_cut * (1 + 1e-9))) continue;
        flip[f] ^= 1, ++turns;
        for (Index k = 0; k < 3; ++k)
          if (adj[f][k] != kNone) work.push_back(adj[f][k]);
      }
      // Cut edges become border edges of both their faces.
      for (Index f : members)
        for (Index k = 0; k < 3; ++k) {
          const Index g = adj[f][k];
          if (g == kNone || g < f || !disagree(f, k)) continue;
          cut.push_back(edge_key(m.faces[f][k], m.faces[f][(k + 1) % 3]));
          adj[f][k] = kNone;
          for (Index& x : adj[g]) x = x == f ? kNone : x;
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
  std::sort(cut.begin(), cut.end());  // for is_among()
  r.cut_edges = Index(cut.size());
  return cut;
}

// A vertex whose triangles form several fans (joined only at the vertex) gets one
// copy per extra fan; afterwards every vertex is a disc or half-disc. Fans are not
// joined across `cut` edges (orient()): a vertex on a cut gets a copy for its other
// side, counted apart from the non-manifold ones.
void split_nonmanifold_vertices(TriMesh& m, const std::vector<std::pair<Index, Index>>& cut, CleanReport& r) {
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
    bool on_cut = false;
    for (Index i = 0; i < n; ++i) {
      const Index f = corner[b + i] / 3, k = corner[b + i] % 3;
      for (Index x : {m.faces[f][(k + 1) % 3], m.faces[f][(k + 2) % 3]}) {
        if (is_among(cut, v, x)) {
          on_cut = true;
          continue;
        }
        spokes.push_back({x, i});
      }
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
        ++(on_cut ? r.cut_vertices : r.split_nonmanifold_vertices);
      }
      const Index f = corner[b + i] / 3, k = corner[b + i] % 3;
      m.faces[f][k] = copy_of_root[root];
    }
  }
}


// Lengths are squared and raised to the fourth power in double precision, and fitmaps
// (per length) are kept in single precision: bunny.ply gives the same quads, scaled, from
// 2^-100 to 2^120 times its size (2e-31 to 3e35 across; bench/RESULTS.md, "Units of
// length"). Past that the results degrade (2^150: 39 quads at automatic halting instead of
// 657; 2^1000: no quad at all), so meshes beyond these sizes, with a margin, are refused,
// before any tolerance relative to the size is taken.
constexpr double kSmallestDiagonal = 1e-30, kLargestDiagonal = 1e30;

// Returns the diagonal.
double check_size(const TriMesh& m, const std::string& src) {
  const auto [lo, hi] = used_bbox(m);
  const double d = (hi - lo).stableNorm();  // norm() overflows past 1e154
  if (d >= kSmallestDiagonal && d <= kLargestDiagonal) return d;
  char size[32];
  std::snprintf(size, sizeof size, "%.3g", d);
  throw InvalidInput(src + ": the mesh is " + size + " units across (its bounding box's diagonal); quadsimp takes "
                     "meshes from 1e-30 to 1e30 units across: scale it first (MeshLab: \"Transform: Scale, "
                     "Normalize\")");
}

std::string percent_of(double share) {
  char percent[32];
  std::snprintf(percent, sizeof percent, "%.2g%%", 100 * share);
  return percent;
}

std::string unfolded_note(const CleanReport& r, double diagonal) {
  return std::to_string(r.unfolded_patches) + " patches of triangles folded back onto the surface laid flat (" +
         std::to_string(r.moved_vertices) + " vertices moved, each to the mean of its neighbours, by up to " +
         percent_of(r.farthest_move / diagonal) + " of the bounding box's diagonal)";
}

std::string kept_note(const CleanReport& r, double diagonal) {
  return std::to_string(r.kept_far_folds) + " patches of triangles that look folded back onto the surface left as "
         "they are: laying them flat would move vertices by at least " + percent_of(r.least_kept_move / diagonal) +
         " of the bounding box's diagonal (a scan's folds needed at most 2.8%), so they are most likely a coarse "
         "mesh's sharp thin parts (see Limits in quadsimp's README)";
}

}  // namespace

CleanReport clean(TriMesh& m, const std::string& src, const LogFn& log, const CleanOptions& options) {
  if (!(options.longest_fold_move >= 0))
    throw std::invalid_argument("clean: longest_fold_move must be a share of the diagonal, at least 0");
  CleanReport r;
  if (m.positions.empty()) throw InvalidInput(src + ": the mesh is empty (no vertices)");
  if (m.faces.empty())
    throw InvalidInput(src + ": the mesh has no faces (" + std::to_string(m.n_vertices()) +
                       " vertices: a point cloud, or lines only?); quadsimp needs a triangle surface");
  for (Index v = 0; v < m.n_vertices(); ++v)
    if (!m.positions[v].allFinite())
      throw InvalidInput(src + ": vertex " + std::to_string(v) + " has a NaN or infinite coordinate");
  for (Index f = 0; f < m.n_faces(); ++f)
    for (Index v : m.faces[f])
      if (v >= m.n_vertices())
        throw InvalidInput(src + ": face " + std::to_string(f) + " refers to vertex " +
                           std::to_string(v) + ", out of range (" + std::to_string(m.n_vertices()) +
                           " vertices)");
  const double diagonal = check_size(m, src);

  merge_duplicate_vertices(m, r);
  remove_degenerate_and_duplicate_faces(m, r);
  if (m.faces.empty()) throw InvalidInput(src + ": every face is degenerate (zero area)");
  std::vector<std::array<Index, 3>> adj;
  std::vector<std::pair<Index, Index>> cut;
  std::string cut_at;
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
      if (m.faces.empty())
        throw InvalidInput(src + ": every face is degenerate once border vertices closer than 1e-6 of the "
                           "bounding-box diagonal are merged (a strip thinner than that)");
      adj = manifold_adjacency();
    }
    if ((r.zipped_t_junctions = zip_cracks(m, adj))) adj = manifold_adjacency();
    cut = orient(m, adj, r);
  }
  if (!cut.empty()) {
    // Where: a user can select round that point in MeshLab and delete or mend it.
    const Vec3 at = 0.5 * (m.positions[cut.front().first] + m.positions[cut.front().second]);
    char where[96];
    std::snprintf(where, sizeof where, "%.6g, %.6g, %.6g", at.x(), at.y(), at.z());
    cut_at = where;
  }
  split_nonmanifold_vertices(m, cut, r);  // faces keep their neighbours
  std::vector<Vec3> normals = unit_normals(m);  // for both mends
  r.flipped_edges = mend_by_edge_flips(m, adj, normals);
  unfold_patches(m, adj, normals, options, diagonal, r);
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
    if (r.cut_edges)
      log(src + ": the surface is not orientable (a Moebius-like strip): cut open along " +
          std::to_string(r.cut_edges) + " edges, where its two sides meet (one with its middle at " + cut_at +
          "); the cut stays open, a border, in the quads");
    note(r.flipped_edges,
         "edges flipped to mend caps (triangles whose height is under 1e-3 of their longest edge) and "
         "single triangles folded back onto their neighbours");
    if (r.unfolded_patches) log(src + ": " + unfolded_note(r, diagonal));
    if (r.kept_far_folds) log(src + ": " + kept_note(r, diagonal));
  }
  return r;
}

}  // namespace qs
