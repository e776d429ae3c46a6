// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include "quadsimp/mesh/quad_mesh.h"

namespace qs {

//! Singlet [Bozzo et al. 2010, Fig. 1 centre]: an interior vertex s of valence 1. Its
//! only face reads (p, s, p, x): two consecutive edges p-s, s-p coincide, and the face
//! has two edges between p and x. Removing it deletes the face and s and glues the
//! two p-x edges, so the faces beyond them become neighbours. V-1, E-2, F-1.
//!
//! validate() rejects such a face (it repeats p); a singlet only exists between two
//! steps of an operation, and these functions clean it up.
bool is_singlet(const QuadMesh& mesh, Index s);

//! Removes the singlet at s. Vertices left with no face are deleted too.
//! \pre is_singlet(mesh, s). \return p (kNone if p was deleted with the face).
Index remove_singlet(QuadMesh& mesh, Index s);

}  // namespace qs
