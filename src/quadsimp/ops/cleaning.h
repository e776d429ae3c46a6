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
//! to `changed_faces` when given. `work` is consumed.
void clean_from(QuadMesh& mesh, std::vector<Index>& work, CleanCounts& counts,
                std::vector<Index>* changed_faces = nullptr);

//! clean_from() on every vertex: the whole-mesh cleaning run before simplification.
CleanCounts clean_all(QuadMesh& mesh);

}  // namespace qs
