// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>

#include "quadsimp/mesh/quad_mesh.h"

namespace qs {

//! Edge rotation [Bozzo et al. 2010, Fig. 1 right]. The interior edge h = u->w with
//! faces f1 = (u, w, x1, x2) and f2 = (w, u, y1, y2) spans the hexagon
//! (w, x1, x2, u, y1, y2). The edge is replaced by one of the hexagon's other long
//! diagonals:
//!
//!     x2 --- x1            x2 --- x1            x2 --- x1
//!     |  f1  |             |    / |             | \    |
//!     u ---- w     A:      u   /  w     B:      u  \   w
//!     |  f2  |             |  /   |             |   \  |
//!     y1 --- y2            y1 --- y2            y1 --- y2
//!
//!   A (Rotation::Ccw): new edge x1-y1, faces (x1, x2, u, y1) and (y1, y2, w, x1).
//!   B (Rotation::Cw):  new edge x2-y2, faces (x2, u, y1, y2) and (y2, w, x1, x2).
//! u and w lose one edge each; the two new endpoints gain one.
enum class Rotation { Ccw, Cw };

//! The new edge's endpoints (x1, y1 for Ccw; x2, y2 for Cw): the two vertices that gain
//! an edge. \pre h is interior.
std::array<Index, 2> rotated_edge(const QuadMesh& mesh, Index h, Rotation r);

//! Refused (false) when: h is on the border; the faces are the same; the six hexagon
//! corners are not distinct; the new endpoints already share a face outside the
//! pair (the edge would be doubled); two corners that become opposite in a new face
//! already share a face outside the pair (see shared_diagonals); u or w would
//! drop below valence 3 inside or 2 on the border (rotations never make doublets), but
//! `doublet` may drop to 2, and its faces' opposite corners may share its other face:
//! crease coarsening makes a doublet there, which it collapses next
//! (ops/doublet_collapse.h).
bool can_rotate_edge(const QuadMesh& mesh, Index h, Rotation r, Index doublet = kNone);

//! The two faces after the rotation (in the slots of f1 and f2), without changing
//! the mesh: for energy and geometric checks.
std::array<std::array<Index, 4>, 2> rotated_faces(const QuadMesh& mesh, Index h, Rotation r);

//! True when a rotated face would be folded or degenerate relative to the old pair, or
//! non-convex; with `bends`, also when it would bend by more than 90 degrees whichever
//! diagonal splits it (quad_folds()) and more than the more bent of the two faces now.
//! A rotated face with corner `except` is not checked (kNone: both are): the border
//! ear removal rotates an edge to make an ear that it collapses right away.
bool rotation_folds(const QuadMesh& mesh, Index h, Rotation r, Index except = kNone, bool bends = false);

//! The two faces rotating edge h rewrites, as they are, and their outer twins: what
//! undo_rotation() puts back (border and crease coarsening rotate, then undo if the
//! collapse that was to follow is refused).
struct RotationUndo {
  Index faces[2];
  std::array<std::array<Index, 4>, 2> before;
  std::array<Index, 6> outer;
};
RotationUndo rotation_undo(const QuadMesh& mesh, Index h);
//! Restores the faces as `undo` saved them. \pre no change since but rotations of them.
void undo_rotation(QuadMesh& mesh, const RotationUndo& undo);

//! Performs the rotation in place (faces keep their ids). \pre can_rotate_edge (with the
//! same `doublet`).
void rotate_edge(QuadMesh& mesh, Index h, Rotation r, Index doublet = kNone);

}  // namespace qs
