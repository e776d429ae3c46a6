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

}  // namespace qs::detail
