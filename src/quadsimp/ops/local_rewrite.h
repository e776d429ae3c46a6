// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// Shared step of the operators that reshape faces in place (rotation, doublet).
#pragma once

#include <array>

#include "quadsimp/mesh/quad_mesh.h"

namespace qs::detail {

//! Gives faces[i] the corners quads[i] (i < n) and reconnects every new half-edge
//! a->b with its partner b->a: another new half-edge, or one of the `outer`
//! half-edges (the twins of the region's old border, kNone entries allowed); with
//! no partner it becomes a border half-edge. Resets out() of every corner.
void rewrite_faces(QuadMesh& m, const Index* faces, const std::array<Index, 4>* quads, int n,
                   const Index* outer, int n_outer);

//! Vertices that share a face with v (v excluded), sorted, into `out`.
void face_neighbours(const QuadMesh& m, Index v, std::vector<Index>& out);

//! Quad link condition for merging a and c: the vertices sharing a face with a and
//! those sharing a face with c are exactly {b, d} in common, and e too when given (a
//! vertex whose faces go before the merge: a doublet's, for doublet_collapse.h).
bool link_condition(const QuadMesh& m, Index a, Index c, Index b, Index d, Index e = kNone);

}  // namespace qs::detail
