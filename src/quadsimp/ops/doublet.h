// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include "quadsimp/mesh/quad_mesh.h"

namespace qs {

//! Doublet [Bozzo et al. 2010, Fig. 1 centre]: an interior vertex s of valence 2.
//! Its faces (s, p, x, r) and (s, r, y, p) share the edges s-p and s-r; removing s
//! merges them into (p, x, r, y). V-1, E-2, F-1; p and r lose one edge each.
//!
//!     p --- x            p --- x
//!     | \ s |     ->     |     |
//!     y --- r            y --- r
//!
//! A border vertex of valence 2 is a corner, not a doublet.
bool is_doublet(const QuadMesh& mesh, Index s);

//! False for the two-face "pillow" (x == y), the only doublet whose merge would
//! repeat a vertex; it is a whole closed component of two faces.
bool can_remove_doublet(const QuadMesh& mesh, Index s);

//! Removes s and merges its two faces into the first one. \pre can_remove_doublet.
//! \return the surviving face.
Index remove_doublet(QuadMesh& mesh, Index s);

}  // namespace qs
