// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

// Internal to the mesh folder: the triangle connectivity that tri_mesh.cpp, clean.cpp and
// mend_folds.cpp each build on.

#include <algorithm>
#include <array>
#include <numeric>
#include <vector>

#include "quadsimp/mesh/tri_mesh.h"

namespace qs::detail {

// The corners (3 * face + k) at each vertex, as compressed rows: those of vertex v are
// corner[start[v]] to corner[start[v + 1] - 1].
struct CornersAround {
  std::vector<Index> start, corner;
};
CornersAround corners_around(const TriMesh& m);

// Whether u and w are corners of one face (an edge, in a manifold mesh).
inline bool share_a_face(const TriMesh& m, const CornersAround& around, Index u, Index w) {
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
                                                 bool* nonmanifold = nullptr);

// Disjoint sets of indices; each set's root is its lowest index, so that what is built on
// them does not depend on the order of the unions.
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

}  // namespace qs::detail
