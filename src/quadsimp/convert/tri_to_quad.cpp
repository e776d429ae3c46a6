// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/convert/tri_to_quad.h"

#include <boost/graph/compressed_sparse_row_graph.hpp>
#include <boost/graph/max_cardinality_matching.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <tuple>
#include <utility>

#include "quadsimp/reference/creases.h"
#include "quadsimp/util/errors.h"

namespace qs {
namespace {

// The quad made by triangle f and its neighbour across edge k, counter-clockwise.
std::array<Index, 4> merged_quad(const TriMesh& t, Index f, Index k, Index g) {
  const Index a = t.faces[f][k], b = t.faces[f][(k + 1) % 3], c = t.faces[f][(k + 2) % 3];
  Index d = kNone;
  for (Index v : t.faces[g])
    if (v != a && v != b) d = v;
  return {a, d, b, c};
}

// The side k of triangle f (corner k to k + 1) whose neighbour in `adj` is g.
Index side_towards(const std::vector<std::array<Index, 3>>& adj, Index f, Index g) {
  Index k = 0;
  while (adj[f][k] != g) ++k;
  return k;
}

// Mean over the corners of 1-|cos(angle)|: 1 for a rectangle. Negative (refused)
// when the quad is not convex in its own plane.
double quad_quality(const std::vector<Vec3>& p, const std::array<Index, 4>& q) {
  const Vec3 n = (p[q[2]] - p[q[0]]).cross(p[q[3]] - p[q[1]]);
  double s = 0;
  for (int k = 0; k < 4; ++k) {
    const Vec3 e1 = p[q[(k + 1) % 4]] - p[q[k]], e0 = p[q[(k + 3) % 4]] - p[q[k]];
    const double l = e0.norm() * e1.norm();
    if (l == 0 || e1.cross(e0).dot(n) <= 0) return -1;
    s += 1 - std::abs(e0.dot(e1)) / l;
  }
  return s / 4;
}

// Splits triangle x at its edge j (corner j to j + 1) with vertex m on that edge: x keeps
// the half from the edge's start, a new triangle (returned) takes the other. With `adj`,
// the neighbours are kept up to date, the split edge's halves getting none (a border, or a
// crease: `crease`, when given, marks them `split_crease` and keeps the others' marks).
Index split_triangle(TriMesh& t, Index x, Index j, Index m, std::vector<std::array<Index, 3>>* adj = nullptr,
                     std::vector<char>* crease = nullptr, char split_crease = 0) {
  const Index a = t.faces[x][j], b = t.faces[x][(j + 1) % 3], c = t.faces[x][(j + 2) % 3];
  const Index z = t.n_faces();
  t.faces[x] = {a, m, c};
  t.faces.push_back({m, b, c});
  if (adj) {
    const Index next = (*adj)[x][(j + 1) % 3], prev = (*adj)[x][(j + 2) % 3];
    (*adj)[x] = {kNone, z, prev};
    adj->push_back({kNone, next, x});
    if (next != kNone)
      for (Index& y : (*adj)[next])
        if (y == x) y = z;
  }
  if (crease && !crease->empty()) {
    const char next = (*crease)[3 * x + (j + 1) % 3], prev = (*crease)[3 * x + (j + 2) % 3];
    (*crease)[3 * x] = split_crease, (*crease)[3 * x + 1] = 0, (*crease)[3 * x + 2] = prev;
    crease->insert(crease->end(), {split_crease, next, 0});
  }
  return z;
}

// Per component (`comp`, with `count` triangles each), its longest border edge (3 * face +
// corner) when its triangle count is odd, else kNone: where fix_parity() splits it.
std::vector<Index> longest_odd_border(const TriMesh& t, const std::vector<std::array<Index, 3>>& adj,
                                      const std::vector<Index>& comp, const std::vector<Index>& count) {
  std::vector<std::pair<double, Index>> best(count.size(), {-1.0, kNone});  // (length, 3*face+k)
  for (Index f = 0; f < t.n_faces(); ++f)
    for (Index k = 0; k < 3; ++k) {
      if (adj[f][k] != kNone || count[comp[f]] % 2 == 0) continue;
      const double len = (t.positions[t.faces[f][k]] - t.positions[t.faces[f][(k + 1) % 3]]).norm();
      if (len > best[comp[f]].first) best[comp[f]] = {len, 3 * f + k};
    }
  std::vector<Index> edge(count.size());
  for (std::size_t c = 0; c < count.size(); ++c) edge[c] = best[c].second;
  return edge;
}

// Triangles per component.
std::vector<Index> component_sizes(const std::vector<Index>& comp, Index nc) {
  std::vector<Index> count(nc, 0);
  for (Index c : comp) ++count[c];
  return count;
}

// Splits the longest border edge of every component with an odd triangle count;
// `adj` (t's triangle adjacency) is brought up to date when it does.
Index fix_parity(TriMesh& t, std::vector<std::array<Index, 3>>& adj) {
  std::vector<Index> comp;
  const std::vector<Index> count = component_sizes(comp, face_components(adj, comp));
  if (std::all_of(count.begin(), count.end(), [](Index n) { return n % 2 == 0; })) return 0;
  const std::vector<Index> longest = longest_odd_border(t, adj, comp, count);
  Index splits = 0;
  for (std::size_t c = 0; c < count.size(); ++c) {
    if (count[c] % 2 == 0) continue;
    // An odd closed component cannot exist (3F = 2E); clean() guarantees manifoldness.
    if (longest[c] == kNone) throw TopologyError("tri_to_quad: odd closed component");
    const Index f = longest[c] / 3, k = longest[c] % 3;
    t.positions.push_back(0.5 * (t.positions[t.faces[f][k]] + t.positions[t.faces[f][(k + 1) % 3]]));
    split_triangle(t, f, k, t.n_vertices() - 1);
    ++splits;
  }
  adj = triangle_adjacency(t);
  return splits;
}

// Bipyramids of five or more rim vertices (a CAD cone: a fan round its tip, another round
// its base's centre) are paired by construction: greedy pairing and the searches may
// leave doublets (interior vertices of two quad edges) at rim vertices, and the
// simplifier's first cleaning merges them, each merge making the next, down to two quads
// on four corners whatever the target. A pairing removes one edge per quad, n in all, and
// a rim vertex (four edges) keeps three only if it loses one: a rim edge costs two rim
// vertices, so only spokes may go, one per rim vertex, alternately from the tip's fan and
// the base's round the rim. An odd rim cannot alternate: its longest rim edge is split at
// its midpoint first. The choices (which centre is the tip, where the rim starts, which
// edge is split) go by position, not by the file's order. Sizes `mate` to t's triangles
// and pairs the bipyramids' in it; `crease` (3 per triangle, or empty) is kept up to date
// through the splits. Returns the rim edges split. One with a crease edge is left to the
// pairing across no crease (a cone's rim: fix_crease_parity() has made each fan even).
Index pair_bipyramids(TriMesh& t, std::vector<std::array<Index, 3>>& adj, std::vector<char>& crease,
                      std::vector<Index>& mate) {
  const auto before = [&](Index u, Index v) {  // position order, ids for exact copies
    const Vec3 &a = t.positions[u], &b = t.positions[v];
    return std::tie(a.x(), a.y(), a.z(), u) < std::tie(b.x(), b.y(), b.z(), v);
  };
  const auto corner = [&](Index e, Index i) -> const Vec3& {  // of side e = 3 * f + k
    return t.positions[t.faces[e / 3][(e % 3 + i) % 3]];
  };
  std::vector<Index> comp;
  const std::vector<Index> count = component_sizes(comp, face_components(adj, comp));
  std::vector<Index> degree(t.n_vertices(), 0);
  for (const auto& f : t.faces)
    for (Index v : f) ++degree[v];
  // Per component, its two vertices of degree n (the fans' centres; the "tip" below is the
  // one first by position, whichever end of the cone it is), both kNone where it has
  // another number of them; then whether every triangle holds exactly one, and the
  // component is closed, with no crease.
  std::vector<std::array<Index, 2>> centre(count.size(), {kNone, kNone});
  std::vector<char> other(count.size(), 0);
  for (Index f = 0; f < t.n_faces(); ++f) {
    const Index n = count[comp[f]] / 2;
    auto& c = centre[comp[f]];
    for (Index v : t.faces[f]) {
      if (n < 5 || degree[v] != n || c[0] == v || c[1] == v) continue;
      if (c[0] == kNone)
        c[0] = v;
      else if (c[1] == kNone)
        c[1] = v;
      else
        other[comp[f]] = 1;
    }
  }
  for (Index f = 0; f < t.n_faces(); ++f) {
    const auto& c = centre[comp[f]];
    int held = 0;
    for (Index k = 0; k < 3; ++k) {
      other[comp[f]] |= adj[f][k] == kNone || (!crease.empty() && crease[3 * f + k]);
      held += t.faces[f][k] == c[0] || t.faces[f][k] == c[1];
    }
    other[comp[f]] |= c[1] == kNone || held != 1;
  }
  // The tip's triangles, each with its rim edge (the one opposite the tip) as 3 * f + k.
  std::vector<std::vector<Index>> fan(count.size());
  for (std::size_t c = 0; c < count.size(); ++c)
    if (!other[c] && before(centre[c][1], centre[c][0])) std::swap(centre[c][0], centre[c][1]);
  for (Index f = 0; f < t.n_faces(); ++f)
    for (Index k = 0; k < 3 && !other[comp[f]]; ++k)
      if (t.faces[f][k] == centre[comp[f]][0]) fan[comp[f]].push_back(3 * f + (k + 1) % 3);
  Index splits = 0;
  for (auto& edges : fan) {
    if (edges.size() % 2 == 0) continue;
    const auto key = [&](Index e) {  // longest first, then the midpoint first by position
      const Vec3 m = corner(e, 0) + corner(e, 1);
      return std::make_tuple((corner(e, 0) - corner(e, 1)).norm(), -m.x(), -m.y(), -m.z());
    };
    const Index e = *std::max_element(edges.begin(), edges.end(), [&](Index x, Index y) { return key(x) < key(y); });
    const Index f = e / 3, k = e % 3, g = adj[f][k], j = side_towards(adj, g, f);
    t.positions.push_back(0.5 * (corner(e, 0) + corner(e, 1)));
    const Index m = t.n_vertices() - 1;
    split_triangle(t, f, k, m, nullptr, &crease);  // f becomes {u, m, tip}, the new triangle {m, w, tip}
    split_triangle(t, g, j, m, nullptr, &crease);
    *std::find(edges.begin(), edges.end(), e) = 3 * f;
    edges.push_back(3 * (t.n_faces() - 2));
    ++splits;
  }
  if (splits) adj = triangle_adjacency(t);
  mate.assign(t.n_faces(), kNone);
  for (const auto& edges : fan) {
    if (edges.empty()) continue;
    // The tip's triangles in rim order from the rim vertex first by position: each rim
    // edge starts where the one before it ends.
    std::vector<std::pair<Index, Index>> by_start;  // (rim edge's start, triangle)
    for (Index e : edges) by_start.push_back({t.faces[e / 3][e % 3], e});
    std::sort(by_start.begin(), by_start.end());
    Index start = by_start[0].first;
    for (const auto& s : by_start)
      if (before(s.first, start)) start = s.first;
    std::vector<Index> ring;  // rim edges, as 3 * f + k
    for (Index v = start; ring.size() < edges.size();) {
      const Index e = std::lower_bound(by_start.begin(), by_start.end(), std::pair<Index, Index>{v, 0})->second;
      ring.push_back(e);
      v = t.faces[e / 3][(e % 3 + 1) % 3];
    }
    // With offset o, the tip's fan pairs across the spokes at rim vertices o + 1, o + 3,
    // ...; the base's, each triangle across a rim edge from the tip's, across those at
    // o + 2, o + 4, .... Of the two offsets, the one whose quads greedy pairing would score
    // better (fewer non-convex, then a higher sum). On an odd rim this decides which fan
    // holds the quad with a straight angle at the split's midpoint; a fixed offset left a
    // folded quad where this leaves a non-convex one (bench/RESULTS.md, "CAD cones paired
    // by construction").
    const std::size_t n = ring.size();
    const auto tip_of = [&](std::size_t i) { return ring[i % n] / 3; };
    const auto base_of = [&](std::size_t i) { return adj[tip_of(i)][ring[i % n] % 3]; };
    const auto for_each_pair = [&](std::size_t o, const auto& visit) {
      for (std::size_t i = o; i < n + o; i += 2) visit(tip_of(i), tip_of(i + 1)), visit(base_of(i + 1), base_of(i + 2));
    };
    std::pair<int, double> score[2] = {};  // (- non-convex quads, sum of scores) per offset
    for (std::size_t o = 0; o < 2; ++o)
      for_each_pair(o, [&](Index f, Index g) {
        const double q = quad_quality(t.positions, merged_quad(t, f, side_towards(adj, f, g), g));
        if (q < 0)
          --score[o].first;
        else
          score[o].second += q;
      });
    for_each_pair(score[1] > score[0] ? 1 : 0, [&](Index f, Index g) { mate[f] = g, mate[g] = f; });
  }
  return splits;
}

// With creases, the parts between them must each pair up on their own: every part but
// the one fix_parity() splits a border edge of is made even. Splitting a crease edge at
// its midpoint adds a triangle on both sides, so the oddness of a part is handed across a
// crease to its neighbour: along a tree of the parts of each component, from the leaves
// to the root, which is the part holding the border edge fix_parity() will split (any
// part, where the component is closed and so even). Returns the crease edges split.
Index fix_crease_parity(TriMesh& t, std::vector<std::array<Index, 3>>& adj, double crease_angle_deg) {
  const std::vector<char> crease = crease_edges(t, adj, crease_angle_deg);
  if (std::find(crease.begin(), crease.end(), 1) == crease.end()) return 0;
  auto edge_to = [&](Index f, Index g) { return 3 * f + side_towards(adj, f, g); };
  std::vector<Index> part, comp;
  const Index parts = face_components(adj, part, [&](Index f, Index g) { return !crease[edge_to(f, g)]; });
  const Index nc = face_components(adj, comp);
  const std::vector<Index> longest = longest_odd_border(t, adj, comp, component_sizes(comp, nc));
  std::vector<char> odd(parts, 0);
  for (Index p : part) odd[p] ^= 1;
  // Each part's neighbours across creases, with a crease edge between them.
  std::vector<std::vector<std::pair<Index, Index>>> next(parts);
  for (Index f = 0; f < t.n_faces(); ++f)
    for (Index k = 0; k < 3; ++k) {
      const Index g = adj[f][k];
      if (g == kNone || g < f || !crease[3 * f + k] || part[f] == part[g]) continue;
      next[part[f]].push_back({part[g], 3 * f + k});
      next[part[g]].push_back({part[f], 3 * f + k});
    }
  std::vector<Index> root(nc, kNone);
  for (Index c = 0; c < nc; ++c)
    if (longest[c] != kNone) root[c] = part[longest[c] / 3];
  // Breadth first from each component's root (its first face's part where it has none).
  std::vector<Index> order, parent(parts, kNone), parent_edge(parts, kNone);
  std::vector<char> seen(parts, 0);
  for (Index f = 0; f < t.n_faces(); ++f) {
    Index& r = root[comp[f]];
    if (r == kNone) r = part[f];
    if (seen[r]) continue;
    seen[r] = 1;
    std::size_t head = order.size();
    order.push_back(r);
    for (; head < order.size(); ++head)
      for (const auto& [q, e] : next[order[head]])
        if (!seen[q]) seen[q] = 1, parent[q] = order[head], parent_edge[q] = e, order.push_back(q);
  }
  // The crease edges to split, as directed vertex pairs of the triangle holding each.
  std::vector<std::pair<Index, Index>> cut;
  for (std::size_t i = order.size(); i-- > 0;) {
    const Index q = order[i];
    if (!odd[q] || parent[q] == kNone) continue;
    const Index e = parent_edge[q];
    cut.push_back({t.faces[e / 3][e % 3], t.faces[e / 3][(e % 3 + 1) % 3]});
    odd[q] = 0, odd[parent[q]] ^= 1;
  }
  if (cut.empty()) return 0;
  // An earlier split may have moved a later one's edge to a new triangle: the triangle
  // holding each directed edge to split is looked up, and kept up to date.
  std::map<std::pair<Index, Index>, Index> holder;
  for (const auto& [u, w] : cut) holder[{u, w}] = holder[{w, u}] = kNone;
  for (Index f = 0; f < t.n_faces(); ++f)
    for (Index k = 0; k < 3; ++k)
      if (auto it = holder.find({t.faces[f][k], t.faces[f][(k + 1) % 3]}); it != holder.end()) it->second = f;
  for (const auto& [u, w] : cut) {
    const Index m = t.n_vertices();
    t.positions.push_back(0.5 * (t.positions[u] + t.positions[w]));
    for (const auto& [a, b] : {std::pair<Index, Index>{u, w}, std::pair<Index, Index>{w, u}}) {
      const Index f = holder.at({a, b});
      Index k = 0;
      while (t.faces[f][k] != a) ++k;
      const Index c = t.faces[f][(k + 2) % 3];
      const Index z = split_triangle(t, f, k, m);
      if (auto it = holder.find({b, c}); it != holder.end()) it->second = z;
    }
  }
  adj = triangle_adjacency(t);
  return Index(cut.size());
}

// Re-pairs along the shortest alternating path from the free triangle u to another
// free triangle (an augmenting path of the dual graph's matching).
// With `to_border`, the search instead ends at the first triangle y with a border
// edge: the path is re-paired so that y is the one left free, and y is returned
// (kNone when nothing was found; u itself when the plain search succeeded).
// `adj` has no neighbour across a crease; `crease` (empty without creases) tells those
// edges from the border.
// The first of triangle y's edges on the border, 3 if none.
Index border_edge(const std::vector<std::array<Index, 3>>& adj, const std::vector<char>& crease, Index y) {
  Index k = 0;
  while (k < 3 && (adj[y][k] != kNone || (!crease.empty() && crease[3 * y + k]))) ++k;
  return k;
}

struct Search {
  std::vector<Index> seen, via, from, queue;
  Index stamp = 0;
  void resize(std::size_t n) {
    seen.resize(n, 0);
    via.resize(n, kNone);
    from.resize(n, kNone);
  }
};

void flip_path(Index u, Index x, Index partner, std::vector<Index>& mate, const Search& s) {
  for (;;) {
    mate[x] = partner;
    if (partner != kNone) mate[partner] = x;
    if (x == u) return;
    partner = s.via[x];
    x = s.from[partner];
  }
}

// Any pair of neighbours may be made.
struct AnyPair {
  bool operator()(Index, Index) const { return true; }
};

// `allowed(y, k)` says whether the path may pair triangle y with its neighbour across side k.
template <class Allowed = AnyPair>
Index augment(Index u, const std::vector<std::array<Index, 3>>& adj, std::vector<Index>& mate, Search& s,
              Index max_search, bool to_border, const std::vector<char>& crease, const Allowed& allowed = {}) {
  const Index stamp = ++s.stamp;
  s.queue.clear();
  s.queue.push_back(u);
  s.seen[u] = stamp;
  for (std::size_t head = 0; head < s.queue.size() && s.queue.size() < max_search; ++head) {
    const Index y = s.queue[head];
    if (to_border && border_edge(adj, crease, y) < 3) {
      if (y != u) {
        const Index t = s.via[y];
        mate[y] = kNone;
        flip_path(u, s.from[t], t, mate, s);
      }
      return y;
    }
    for (Index k = 0; k < 3; ++k) {
      const Index t = adj[y][k];
      if (t == kNone || s.seen[t] == stamp || !allowed(y, k)) continue;
      if (mate[t] == kNone && !to_border) {
        flip_path(u, y, t, mate, s);
        return u;
      }
      const Index p = mate[t];
      if (p == kNone || s.seen[p] == stamp) continue;
      s.seen[t] = s.seen[p] = stamp;
      s.from[t] = y;
      s.via[p] = t;
      s.queue.push_back(p);
    }
  }
  return kNone;
}

// Pairs what the breadth-first searches left, wherever the graph of triangles allows:
// Edmonds' blossom algorithm (Boost.Graph) finds the paths through odd cycles that they
// miss. It starts from the pairs found so far and returns the triangles it paired. On
// noisy scans the searches, moves and all, left a few triangles of a closed surface
// (whose pairing always exists) unpaired in about one copy in ten, and the refinement
// that followed made four times the quads. It runs only when something is left, so the
// conversions of clean inputs keep the pairs they had (bench/RESULTS.md, "Noisy scans").
// The graph is Boost's compressed rows with 32-bit ids, its out-edges per triangle in the
// order an adjacency_list built by add_edge() for each triangle and each later neighbour
// gives them (from its earlier neighbours, then to its later ones), so the search makes the
// same steps and pairs: an adjacency_list (a vector of edges a vertex, a list of all edges)
// and the finder's arrays of 64-bit ids took 1.1 GB of a run's 1.68 GB peak on 4.5 million
// triangles (bench/RESULTS.md, "Peak memory of large runs").
Index pair_through_blossoms(const std::vector<std::array<Index, 3>>& adj, std::vector<Index>& mate) {
  using Graph = boost::compressed_sparse_row_graph<boost::directedS, boost::no_property, boost::no_property,
                                                   boost::no_property, std::uint32_t, std::uint32_t>;
  using Vertex = boost::graph_traits<Graph>::vertex_descriptor;
  const Index n = Index(adj.size());
  const Graph g = [&] {
    std::vector<std::uint32_t> at(n + 1, 0);  // then each source's next slot
    for (Index f = 0; f < n; ++f)
      for (Index h : adj[f])
        if (h != kNone && f < h) ++at[f + 1], ++at[h + 1];
    std::partial_sum(at.begin(), at.end(), at.begin());
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges(at[n]);
    for (Index f = 0; f < n; ++f)
      for (Index h : adj[f])
        if (h != kNone && f < h) edges[at[f]++] = {f, h}, edges[at[h]++] = {h, f};
    return Graph(boost::edges_are_sorted, edges.begin(), edges.end(), n);
  }();
  const Vertex none = boost::graph_traits<Graph>::null_vertex();
  std::vector<Vertex> partner(n);
  for (Index f = 0; f < n; ++f) partner[f] = mate[f] == kNone ? none : Vertex(mate[f]);
  const auto index = boost::get(boost::vertex_index, g);
  auto partner_of = boost::make_iterator_property_map(partner.begin(), index);
  boost::edmonds_augmenting_path_finder<Graph, decltype(partner_of), decltype(index)> finder(g, partner_of, index);
  Index paired = 0;
  while (finder.augment_matching()) paired += 2;
  finder.get_current_matching(partner_of);
  for (Index f = 0; f < n; ++f) mate[f] = partner[f] == none ? kNone : Index(partner[f]);
  return paired;
}

// Splits the border edge of triangle y at its midpoint; the two halves pair up.
void split_border_and_pair(TriMesh& t, std::vector<std::array<Index, 3>>& adj, std::vector<char>& crease,
                           std::vector<Index>& mate, Index y) {
  const Index k = border_edge(adj, crease, y);
  t.positions.push_back(0.5 * (t.positions[t.faces[y][k]] + t.positions[t.faces[y][(k + 1) % 3]]));
  const Index z = split_triangle(t, y, k, t.n_vertices() - 1, &adj, &crease);
  mate[y] = z;
  mate.push_back(y);
}

// One refinement step of a mixed mesh: each quad -> 4 quads, each triangle -> 3.
QuadMesh refine_mixed(const TriMesh& t, const std::vector<std::array<Index, 3>>& adj, const std::vector<Index>& mate) {
  std::vector<Vec3> pos = t.positions;
  std::map<std::pair<Index, Index>, Index> mid;
  auto midpoint = [&](Index a, Index b) {
    auto key = std::minmax(a, b);
    auto [it, fresh] = mid.emplace(std::pair<Index, Index>(key.first, key.second), Index(pos.size()));
    if (fresh) pos.push_back(0.5 * (t.positions[a] + t.positions[b]));
    return it->second;
  };
  std::vector<std::array<Index, 4>> quads;
  auto fan = [&](const Index* poly, int n, Index centre) {
    for (int k = 0; k < n; ++k)
      quads.push_back({poly[k], midpoint(poly[k], poly[(k + 1) % n]), centre,
                       midpoint(poly[(k + n - 1) % n], poly[k])});
  };
  for (Index f = 0; f < t.n_faces(); ++f) {
    const Index g = mate[f];
    if (g == kNone) {
      const auto& v = t.faces[f];
      const Index c = Index(pos.size());
      pos.push_back((t.positions[v[0]] + t.positions[v[1]] + t.positions[v[2]]) / 3.0);
      fan(v.data(), 3, c);
    } else if (f < g) {
      const auto q = merged_quad(t, f, side_towards(adj, f, g), g);
      // The diagonal a-b is shared by both triangles: its midpoint lies on the surface.
      const Index c = midpoint(q[0], q[2]);
      fan(q.data(), 4, c);
    }
  }
  return QuadMesh::from_faces(std::move(pos), quads);
}

// Each pair of triangles across a crease edge u-w, (u, w, a) and (w, u, b), becomes two
// quads with a new vertex m at the edge's midpoint, (u, m, w, a) and (w, m, u, b): flat,
// with a straight angle at m, but neither crosses the crease. The simplifier takes m out
// again with its crease neighbours (ops/doublet_collapse.h). `adj` has no neighbours
// across creases, `full` does; both and `crease` are kept up to date. Returns the pairs
// split.
Index split_pairs_at_creases(TriMesh& t, const std::vector<std::array<Index, 3>>& full,
                             std::vector<std::array<Index, 3>>& adj, std::vector<char>& crease,
                             std::vector<Index>& mate) {
  Index splits = 0;
  const Index n = t.n_faces();
  for (Index f = 0; f < n; ++f) {
    const Index g = mate[f];
    if (g == kNone || g < f || std::find(adj[f].begin(), adj[f].end(), g) != adj[f].end()) continue;
    const Index m = t.n_vertices();
    const Index k = side_towards(full, f, g);
    t.positions.push_back(0.5 * (t.positions[t.faces[f][k]] + t.positions[t.faces[f][(k + 1) % 3]]));
    // Each of f and g keeps the half from its edge's start, and a new triangle takes the
    // other half and pairs with it.
    for (const Index x : {f, g}) {
      const Index z = split_triangle(t, x, side_towards(full, x, x == f ? g : f), m, &adj, &crease, 1);
      mate[x] = z;
      mate.push_back(x);
    }
    ++splits;
  }
  return splits;
}

// The pairs pair_greedily() makes: convex, bent by at most max_dihedral_deg. score() is
// the quad's quad_quality(), -1 for a pair bent further.
struct GreedyPair {
  GreedyPair(const TriMesh& t, const std::vector<std::array<Index, 3>>& adj, double max_dihedral_deg)
      : t(t), adj(adj), cos_max(std::cos(max_dihedral_deg * M_PI / 180.0)), normal(unit_normals(t)) {}
  const TriMesh& t;
  const std::vector<std::array<Index, 3>>& adj;
  double cos_max;
  std::vector<Vec3> normal;
  double score(Index f, Index k) const {
    const Index g = adj[f][k];
    return normal[f].dot(normal[g]) < cos_max ? -1 : quad_quality(t.positions, merged_quad(t, f, k, g));
  }
  bool operator()(Index f, Index k) const { return score(f, k) > 0; }
};

// Greedy matching of the triangles still unpaired, best candidate first (quad_quality();
// non-convex pairs and pairs bent by more than max_dihedral_deg are not candidates); ties
// broken by ids for determinism. Returns the triangles it paired. Its candidates and
// normals are freed on return, before the searches' and the blossom algorithm's memory is
// taken (the latter's graph sets the peak of a run).
Index pair_greedily(const TriMesh& t, const std::vector<std::array<Index, 3>>& adj, double max_dihedral_deg,
                    std::vector<Index>& mate) {
  struct Cand {
    double score;
    Index f, k;
  };
  std::vector<Cand> cand;
  cand.reserve(3 * t.faces.size() / 2);
  const GreedyPair pair(t, adj, max_dihedral_deg);
  for (Index f = 0; f < t.n_faces(); ++f)
    for (Index k = 0; k < 3; ++k) {
      if (adj[f][k] == kNone || adj[f][k] < f) continue;
      const double s = pair.score(f, k);
      if (s > 0) cand.push_back({s, f, k});
    }
  std::sort(cand.begin(), cand.end(), [](const Cand& a, const Cand& b) {
    return a.score > b.score || (a.score == b.score && (a.f < b.f || (a.f == b.f && a.k < b.k)));
  });
  Index paired = 0;
  for (const Cand& c : cand) {
    const Index g = adj[c.f][c.k];
    if (mate[c.f] != kNone || mate[g] != kNone) continue;
    mate[c.f] = g;
    mate[g] = c.f;
    paired += 2;
  }
  return paired;
}

// ConvertOptions::convex_pairs, before the plain searches: each leftover is paired along an
// alternating path of pairs greedy pairing would make, where one is found within
// ConvertOptions::convex_search triangles.
void pair_leftovers_convex(const TriMesh& t, const std::vector<std::array<Index, 3>>& adj,
                           const std::vector<char>& crease, const ConvertOptions& opt, std::vector<Index>& mate,
                           Search& search, ConvertReport& r) {
  const GreedyPair good(t, adj, opt.max_dihedral_deg);
  for (Index f = 0; f < t.n_faces(); ++f) {
    if (mate[f] != kNone) continue;
    if (augment(f, adj, mate, search, opt.convex_search, false, crease, good) != kNone) r.paired_augmented += 2;
    r.searched += search.queue.size();
  }
}

// ConvertOptions::convex_pairs, once every triangle is paired: each pair greedy pairing
// would not make is taken apart and its two triangles joined again along an alternating
// path of pairs it would make, where one is found; the pair stays where none is. Every
// pair made is one greedy pairing would make, so each re-pairing leaves at least one such
// pair fewer.
void mend_pairs(const TriMesh& t, const std::vector<std::array<Index, 3>>& adj, const ConvertOptions& opt,
                std::vector<Index>& mate, Search& search, ConvertReport& r) {
  const GreedyPair good(t, adj, opt.max_dihedral_deg);
  for (Index f = 0; f < t.n_faces(); ++f) {
    const Index g = mate[f];
    if (g == kNone || g < f) continue;
    const Index k = Index(std::find(adj[f].begin(), adj[f].end(), g) - adj[f].begin());
    if (k == 3 || good(f, k)) continue;  // k == 3: across a crease (split_pairs_at_creases() left none)
    mate[f] = mate[g] = kNone;
    if (augment(f, adj, mate, search, opt.convex_search, false, {}, good) != kNone)
      ++r.mended;
    else
      mate[f] = g, mate[g] = f, ++r.not_mended;
    r.searched += search.queue.size();
  }
}

}  // namespace

QuadMesh tri_to_quad(const TriMesh& input, const ConvertOptions& opt, ConvertReport* report) {
  TriMesh t = input;
  ConvertReport r;
  auto adj = triangle_adjacency(t);
  r.crease_splits = fix_crease_parity(t, adj, opt.crease_angle_deg);
  r.parity_splits = fix_parity(t, adj);
  std::vector<char> crease;
  if (opt.crease_angle_deg > 0) crease = crease_edges(t, adj, opt.crease_angle_deg);
  std::vector<Index> mate;
  r.rim_splits = pair_bipyramids(t, adj, crease, mate);
  r.input_triangles = t.n_faces();
  // From here on no triangle is a neighbour across a crease, so none is paired there;
  // `full` keeps the neighbours across creases.
  std::vector<std::array<Index, 3>> full;
  if (opt.crease_angle_deg > 0) {
    if (std::find(crease.begin(), crease.end(), 1) == crease.end()) crease.clear();
    if (!crease.empty()) full = adj;
    for (Index f = 0; f < t.n_faces() && !crease.empty(); ++f)
      for (Index k = 0; k < 3; ++k)
        if (crease[3 * f + k]) adj[f][k] = kNone;
  }

  r.paired_greedy = Index(std::count_if(mate.begin(), mate.end(), [](Index g) { return g != kNone; }));
  r.paired_greedy += pair_greedily(t, adj, opt.max_dihedral_deg, mate);

  Search search;
  search.resize(t.n_faces());
  const auto leftover = [&] { return std::find(mate.begin(), mate.end(), kNone) != mate.end(); };
  const auto pair_leftovers = [&](const std::vector<std::array<Index, 3>>& a) {
    for (Index f = 0; f < t.n_faces(); ++f) {
      // Breadth-first alternating search misses paths through odd cycles (it does not
      // shrink blossoms); moving the free triangle one step and searching again gets
      // around them in practice. The moves share one breadth: where no path exists (a part
      // between creases with no pairing of its own), each search covers the whole part,
      // and Edmonds' algorithm below settles it in the time of a few such searches.
      Index free = f;
      Index breadth = opt.max_search;
      for (Index attempt = 0; mate[free] == kNone && attempt < opt.max_moves && breadth > 0; ++attempt) {
        const bool paired = augment(free, a, mate, search, breadth, false, crease) != kNone;
        r.searched += search.queue.size();
        if (paired) {
          r.paired_augmented += 2;
          break;
        }
        breadth -= std::min(breadth, Index(search.queue.size()));
        const Index t2 = a[free][attempt % 3];
        if (t2 == kNone || mate[t2] == kNone) continue;
        const Index freed = mate[t2];
        mate[t2] = free;
        mate[free] = t2;
        mate[freed] = kNone;
        free = freed;
      }
    }
    if (leftover()) {
      const Index paired = pair_through_blossoms(a, mate);
      r.paired_blossoms += paired;
      r.paired_augmented += paired;
    }
  };
  if (opt.convex_pairs) pair_leftovers_convex(t, adj, crease, opt, mate, search, r);
  pair_leftovers(adj);
  if (!crease.empty() && leftover()) {
    // Even in number, a part between creases may still have no pairing of its own (the
    // cells of a grid, split in two one way, with a triangle added at two places). Its
    // leftovers pair across creases, and each such pair is split at the crease into two
    // quads (crease_midpoints()).
    // Not at crease edges that end where creases meet or end, if it can be helped: the
    // simplifier keeps such a vertex where it is, and the flat quads beside it do not
    // always go then (the faces around the other end would have to reach that vertex).
    std::vector<char> corner(t.n_vertices(), 0);
    for (Index f = 0; f < t.n_faces(); ++f)
      for (Index k = 0; k < 3; ++k)
        if (crease[3 * f + k] && full[f][k] > f) ++corner[t.faces[f][k]], ++corner[t.faces[f][(k + 1) % 3]];
    std::vector<std::array<Index, 3>> away = full;
    for (Index f = 0; f < t.n_faces(); ++f)
      for (Index k = 0; k < 3; ++k)
        if (crease[3 * f + k] && (corner[t.faces[f][k]] != 2 || corner[t.faces[f][(k + 1) % 3]] != 2))
          away[f][k] = kNone;
    pair_leftovers(away);
    if (leftover()) pair_leftovers(full);
    r.crease_midpoints = split_pairs_at_creases(t, full, adj, crease, mate);
    r.input_triangles += 2 * r.crease_midpoints;
    r.paired_augmented += 2 * r.crease_midpoints;
    search.resize(t.n_faces());
  }
  // Some meshes have no perfect matching at all (two "ears" hanging off one
  // triangle at a border). Carry each leftover to the border and split a border
  // edge there: one midpoint vertex, and the two halves make a quad.
  const Index n_before = t.n_faces();
  for (Index f = 0; f < n_before; ++f) {
    if (mate[f] != kNone) continue;
    const Index y = augment(f, adj, mate, search, opt.max_search, true, crease);
    r.searched += search.queue.size();
    if (y == kNone) continue;
    split_border_and_pair(t, adj, crease, mate, y);
    search.resize(t.n_faces());
    ++r.border_splits;
    r.paired_augmented += 1;
  }

  QuadMesh q;
  if (r.paired_greedy + r.paired_augmented == r.input_triangles) {
    if (opt.convex_pairs) mend_pairs(t, adj, opt, mate, search, r);
    std::vector<std::array<Index, 4>> quads;
    quads.reserve(t.n_faces() / 2);
    for (Index f = 0; f < t.n_faces(); ++f) {
      const Index g = mate[f];
      if (f > g) continue;
      quads.push_back(merged_quad(t, f, side_towards(adj, f, g), g));
    }
    q = QuadMesh::from_faces(t.positions, quads);
  } else {
    r.refined = true;
    q = refine_mixed(t, adj, mate);
  }
  r.quads = q.n_faces();
  if (report) *report = r;
  return q;
}

}  // namespace qs
