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

//! What unfold_patches() laid flat.
struct Unfolded {
  Index patches = 0;
  Index vertices = 0;     //!< moved
  double farthest = 0;    //!< the longest move
  Index kept = 0;         //!< patches left because laying them flat moved a vertex past max_move
  double least_kept = 0;  //!< the least of those moves
};

//! Lays flat the small patches folded back onto the surface (folded_patches() with
//! kLaidFlatShare and kLaidFlatCos) that are discs and that `options` asks for, by moving
//! their vertices and if need be the rings around them. `diagonal`: the mesh's bounding
//! box's, which CleanOptions' shares are of.
Unfolded unfold_patches(TriMesh& m, const std::vector<std::array<Index, 3>>& adj, const std::vector<Vec3>& normals,
                        const CleanOptions& options, double diagonal);

}  // namespace qs::detail
