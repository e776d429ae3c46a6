// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/convert/tri_to_quad.h"

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/max_cardinality_matching.hpp>

#include <algorithm>
#include <cmath>
#include <map>

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

// Splits the longest border edge of every component with an odd triangle count;
// `adj` (t's triangle adjacency) is brought up to date when it does.
Index fix_parity(TriMesh& t, std::vector<std::array<Index, 3>>& adj) {
  std::vector<Index> comp;
  const Index nc = face_components(adj, comp);
  std::vector<Index> count(nc, 0);
  for (Index c : comp) ++count[c];
  if (std::all_of(count.begin(), count.end(), [](Index n) { return n % 2 == 0; })) return 0;
  std::vector<std::pair<double, Index>> best(nc, {-1.0, kNone});  // (length, 3*face+k)
  for (Index f = 0; f < t.n_faces(); ++f)
    for (Index k = 0; k < 3; ++k) {
      if (adj[f][k] != kNone || count[comp[f]] % 2 == 0) continue;
      const double len = (t.positions[t.faces[f][k]] - t.positions[t.faces[f][(k + 1) % 3]]).norm();
      if (len > best[comp[f]].first) best[comp[f]] = {len, 3 * f + k};
    }
  Index splits = 0;
  for (Index c = 0; c < nc; ++c) {
    if (count[c] % 2 == 0) continue;
    // An odd closed component cannot exist (3F = 2E); clean() guarantees manifoldness.
    if (best[c].second == kNone) throw TopologyError("tri_to_quad: odd closed component");
    const Index f = best[c].second / 3, k = best[c].second % 3;
    const auto tri = t.faces[f];
    const Index a = tri[k], b = tri[(k + 1) % 3], apex = tri[(k + 2) % 3];
    const Index m = t.n_vertices();
    t.positions.push_back(0.5 * (t.positions[a] + t.positions[b]));
    t.faces[f] = {a, m, apex};
    t.faces.push_back({m, b, apex});
    ++splits;
  }
  adj = triangle_adjacency(t);
  return splits;
}

// Re-pairs along the shortest alternating path from the free triangle u to another
// free triangle (an augmenting path of the dual graph's matching).
// With `to_border`, the search instead ends at the first triangle y with a border
// edge: the path is re-paired so that y is the one left free, and y is returned
// (kNone when nothing was found; u itself when the plain search succeeded).
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

Index augment(Index u, const std::vector<std::array<Index, 3>>& adj, std::vector<Index>& mate,
              Search& s, Index max_search, bool to_border) {
  const Index stamp = ++s.stamp;
  s.queue.clear();
  s.queue.push_back(u);
  s.seen[u] = stamp;
  for (std::size_t head = 0; head < s.queue.size() && s.queue.size() < max_search; ++head) {
    const Index y = s.queue[head];
    if (to_border && (adj[y][0] == kNone || adj[y][1] == kNone || adj[y][2] == kNone)) {
      if (y != u) {
        const Index t = s.via[y];
        mate[y] = kNone;
        flip_path(u, s.from[t], t, mate, s);
      }
      return y;
    }
    for (Index t : adj[y]) {
      if (t == kNone || s.seen[t] == stamp) continue;
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
Index pair_through_blossoms(const std::vector<std::array<Index, 3>>& adj, std::vector<Index>& mate) {
  using Graph = boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS>;
  using Vertex = boost::graph_traits<Graph>::vertex_descriptor;
  const Index n = Index(adj.size());
  Graph g(n);
  for (Index f = 0; f < n; ++f)
    for (Index h : adj[f])
      if (h != kNone && f < h) boost::add_edge(f, h, g);
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
void split_border_and_pair(TriMesh& t, std::vector<std::array<Index, 3>>& adj, std::vector<Index>& mate,
                           Index y) {
  Index k = 0;
  while (adj[y][k] != kNone) ++k;
  const auto tri = t.faces[y];
  const Index a = tri[k], b = tri[(k + 1) % 3], c = tri[(k + 2) % 3];
  const Index n_bc = adj[y][(k + 1) % 3], n_ca = adj[y][(k + 2) % 3];
  const Index m = t.n_vertices(), z = t.n_faces();
  t.positions.push_back(0.5 * (t.positions[a] + t.positions[b]));
  t.faces[y] = {a, m, c};
  t.faces.push_back({m, b, c});
  adj[y] = {kNone, z, n_ca};
  adj.push_back({kNone, n_bc, y});
  if (n_bc != kNone)
    for (Index& x : adj[n_bc])
      if (x == y) x = z;
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
      Index k = 0;
      while (adj[f][k] != g) ++k;
      const auto q = merged_quad(t, f, k, g);
      // The diagonal a-b is shared by both triangles: its midpoint lies on the surface.
      const Index c = midpoint(q[0], q[2]);
      fan(q.data(), 4, c);
    }
  }
  return QuadMesh::from_faces(std::move(pos), quads);
}

}  // namespace

QuadMesh tri_to_quad(const TriMesh& input, const ConvertOptions& opt, ConvertReport* report) {
  TriMesh t = input;
  ConvertReport r;
  auto adj = triangle_adjacency(t);
  r.parity_splits = fix_parity(t, adj);
  r.input_triangles = t.n_faces();

  // Greedy matching, best candidate first; ties broken by ids for determinism. Its
  // candidates and normals go at the end of the block, before the searches' and the
  // blossom algorithm's memory is taken (the latter's graph sets the peak of a run).
  std::vector<Index> mate(t.n_faces(), kNone);
  {
    struct Cand {
      double score;
      Index f, k;
    };
    std::vector<Cand> cand;
    cand.reserve(3 * t.faces.size() / 2);
    const double cos_max = std::cos(opt.max_dihedral_deg * M_PI / 180.0);
    const std::vector<Vec3> normal = unit_normals(t);
    for (Index f = 0; f < t.n_faces(); ++f)
      for (Index k = 0; k < 3; ++k) {
        const Index g = adj[f][k];
        if (g == kNone || g < f || normal[f].dot(normal[g]) < cos_max) continue;
        const double s = quad_quality(t.positions, merged_quad(t, f, k, g));
        if (s > 0) cand.push_back({s, f, k});
      }
    std::sort(cand.begin(), cand.end(), [](const Cand& a, const Cand& b) {
      return a.score > b.score || (a.score == b.score && (a.f < b.f || (a.f == b.f && a.k < b.k)));
    });
    for (const Cand& c : cand) {
      const Index g = adj[c.f][c.k];
      if (mate[c.f] != kNone || mate[g] != kNone) continue;
      mate[c.f] = g;
      mate[g] = c.f;
      r.paired_greedy += 2;
    }
  }

  Search search;
  search.resize(t.n_faces());
  for (Index f = 0; f < t.n_faces(); ++f) {
    // Breadth-first alternating search misses paths through odd cycles (it does not
    // shrink blossoms); moving the free triangle one step and searching again gets
    // around them in practice.
    Index free = f;
    for (Index attempt = 0; mate[free] == kNone && attempt < opt.max_moves; ++attempt) {
      if (augment(free, adj, mate, search, opt.max_search, false) != kNone) {
        r.paired_augmented += 2;
        break;
      }
      const Index t2 = adj[free][attempt % 3];
      if (t2 == kNone || mate[t2] == kNone) continue;
      const Index freed = mate[t2];
      mate[t2] = free;
      mate[free] = t2;
      mate[freed] = kNone;
      free = freed;
    }
  }
  if (std::find(mate.begin(), mate.end(), kNone) != mate.end()) {
    r.paired_blossoms = pair_through_blossoms(adj, mate);
    r.paired_augmented += r.paired_blossoms;
  }
  // Some meshes have no perfect matching at all (two "ears" hanging off one
  // triangle at a border). Carry each leftover to the border and split a border
  // edge there: one midpoint vertex, and the two halves make a quad.
  const Index n_before = t.n_faces();
  for (Index f = 0; f < n_before; ++f) {
    if (mate[f] != kNone) continue;
    const Index y = augment(f, adj, mate, search, opt.max_search, true);
    if (y == kNone) continue;
    split_border_and_pair(t, adj, mate, y);
    search.resize(t.n_faces());
    ++r.border_splits;
    r.paired_augmented += 1;
  }

  QuadMesh q;
  if (r.paired_greedy + r.paired_augmented == r.input_triangles) {
    std::vector<std::array<Index, 4>> quads;
    quads.reserve(t.n_faces() / 2);
    for (Index f = 0; f < t.n_faces(); ++f) {
      const Index g = mate[f];
      if (f > g) continue;
      Index k = 0;
      while (adj[f][k] != g) ++k;
      quads.push_back(merged_quad(t, f, k, g));
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
