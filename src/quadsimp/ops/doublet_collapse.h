// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include "quadsimp/mesh/quad_mesh.h"

namespace qs {

//! Doublet collapse (ours): a doublet s (an interior vertex of valence 2, ops/doublet.h)
//! goes, and with it the diagonal p-r its faces are left with; p and r merge. It takes
//! two segments out of a crease: the crease runs p - s - r, with one face of s on
//! either side, and removing s alone would leave one quad folded across the crease.
//!
//!     p --- x              x
//!     | \ s |     ->       |
//!     y --- r          y - v        V-2, E-4, F-2
//!
//! The survivor keeps p's id. val(v) = val(p) + val(r) - 4.
//!
//! Refused (false) when s is no doublet, or its faces make a pillow; p and r are both
//! on the border; x or y is an interior vertex of valence <= 2; or the vertices sharing
//! a face with p and with r are not exactly {s, x, y} (the merge would double an edge
//! or repeat a vertex in a face).
bool can_collapse_doublet(const QuadMesh& mesh, Index s);

//! The doublet's neighbours p and r (along its edges) and the far corners x and y of
//! its faces (s, p, x, r) and (s, r, y, p). \pre is_doublet(mesh, s).
struct DoubletCorners {
  Index p, x, r, y;
};
DoubletCorners doublet_corners(const QuadMesh& mesh, Index s);

//! Performs it and puts the survivor at `position`. \pre can_collapse_doublet.
//! \return the surviving vertex, p.
Index collapse_doublet(QuadMesh& mesh, Index s, const Vec3& position);

}  // namespace qs
