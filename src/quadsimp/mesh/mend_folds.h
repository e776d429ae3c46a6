// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

// Internal to clean(): the repairs of caps and of triangles folded back onto the surface.

#include <array>
#include <vector>

#include "quadsimp/mesh/clean.h"
#include "quadsimp/mesh/tri_mesh.h"

namespace qs::detail {

//! Flips an edge of each cap and of each single triangle folded back against all its
//! neighbours, where that mends it; returns the flips. `adj` (as adjacency_from() gives
//! it) and `normals` (the faces' unit normals) are kept up to date.
Index mend_by_edge_flips(TriMesh& m, std::vector<std::array<Index, 3>>& adj, std::vector<Vec3>& normals);

//! Lays flat the small patches folded back onto the surface (folded_patches() with
//! kLaidFlatShare and kLaidFlatCos) that are discs and that `options` asks for, by moving
//! their vertices and if need be the rings around them; counts them, and those left for
//! CleanOptions::longest_fold_move, in `report`. `diagonal`: the mesh's bounding box's,
//! which CleanOptions' shares are of.
void unfold_patches(TriMesh& m, const std::vector<std::array<Index, 3>>& adj, const std::vector<Vec3>& normals,
                    const CleanOptions& options, double diagonal, CleanReport& report);

}  // namespace qs::detail
