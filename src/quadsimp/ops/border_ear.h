// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include "quadsimp/mesh/quad_mesh.h"

namespace qs {

//! Border ear collapse (ours; the paper never coarsens a border). Quad f = (a, b, c, d)
//! whose corner b (= corner k) has only this face, so that a-b and b-c are border
//! edges: f and b are removed and a, c merge into one border vertex. The border loses
//! two edges; a-d and c-d become one interior edge.
//!
//!     x -- a -- b -- c -- y   (border)          x -- v -- y
//!          |  f      |                    ->         |
//!          d --------                                d
//!
//! V-2, E-3, F-1. val(v) = val(a) + val(c) - 3; d loses one edge. Without it, the
//! number of border edges never drops: holes keep their input edges at any face count.
//!
//! Refused (false) when: f is dead; b is not a border vertex whose only face is f; a-d
//! or c-d is a border edge; the face neighbourhoods of a and c share more than b and
//! d; the border loop has fewer than five edges.
bool can_collapse_border_ear(const QuadMesh& mesh, Index f, Index k);

//! Performs it and puts the merged vertex at `p`. \pre can_collapse_border_ear.
//! \return the merged vertex (a).
Index collapse_border_ear(QuadMesh& mesh, Index f, Index k, const Vec3& p);

}  // namespace qs
