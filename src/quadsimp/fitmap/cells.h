// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

// Internal to the fitmap folder: the clustering of M0 into cells that the fitmaps'
// large balls and the anisotropy's balls are searched on.

#include <array>
#include <vector>

#include "quadsimp/mesh/tri_mesh.h"

namespace qs::detail {

// Triangles clustered into cubic cells of one size by their centroids. Cells are numbered
// in the order of their first triangle, and cells touching through a mesh edge are
// neighbours, so that a search over cells follows the surface as one over triangles does
// (two sheets close in space stay apart).
struct CellGrid {
  std::vector<Index> cell_of_triangle;
  std::vector<Index> adj_start, adj;  // compressed rows: the neighbours of each cell
  Index n_cells() const { return Index(adj_start.size()) - 1; }
};
CellGrid cluster_triangles(const std::vector<Vec3>& centroid, const std::vector<std::array<Index, 3>>& tri_adj,
                           double size);

// Grows a ball of cells over the surface, breadth first from the cells already in `cells`:
// each neighbour not stamped `stamp` or `shared` whose centre is nearer p than sqrt(r2)
// is stamped `stamp`, appended and handed to take(x), in the order appended. The fitmaps'
// balls and the anisotropy's are this search with their own sums.
template <class Take>
void grow_ball(const CellGrid& grid, const std::vector<Vec3>& centre, const Vec3& p, double r2,
               std::vector<Index>& cells, std::vector<Index>& mark, Index stamp, Index shared, Take&& take) {
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const Index c = cells[i];
    for (Index j = grid.adj_start[c]; j < grid.adj_start[c + 1]; ++j) {
      const Index x = grid.adj[j];
      if (mark[x] != stamp && mark[x] != shared && (centre[x] - p).squaredNorm() < r2) {
        mark[x] = stamp;
        cells.push_back(x);
        take(x);
      }
    }
  }
}

}  // namespace qs::detail
