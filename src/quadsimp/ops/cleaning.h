// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <vector>

#include "quadsimp/mesh/quad_mesh.h"

namespace qs {

struct CleanCounts {
  Index doublets = 0;
  Index singlets = 0;
};

//! Removes doublets and singlets starting from the vertices in `work`, following
//! the chain each removal starts (the neighbours it lowers go back on the list).
//! Ends because every removal deletes a vertex. Faces that changed are appended
//! to `changed_faces` when given. `work` is consumed. A vertex marked in `keep` (when
//! given) is never removed as a doublet: a crease vertex's two faces lie on either side
//! of the crease, and merged they would fold across it (see doublet_collapse.h).
void clean_from(QuadMesh& mesh, std::vector<Index>& work, CleanCounts& counts,
                std::vector<Index>* changed_faces = nullptr, const std::vector<char>* keep = nullptr);

//! clean_from() on every vertex: the whole-mesh cleaning run before simplification.
CleanCounts clean_all(QuadMesh& mesh, const std::vector<char>* keep = nullptr);

}  // namespace qs
