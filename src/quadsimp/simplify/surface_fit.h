// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include "quadsimp/mesh/quad_mesh.h"
#include "quadsimp/reference/reference_surface.h"

namespace qs {

struct SurfaceFitOptions {
  //! Gauss-Newton steps; each rebuilds the BVH of the quads and measures both sides.
  int iterations = 5;
  //! Share of each vertex's own least-squares step taken: all vertices move at once,
  //! and neighbours that each take their full step overshoot together.
  double damping = 0.7;
  //! Largest move per step, as a share of the vertex's mean edge length.
  double max_step = 0.25;
};

struct SurfaceFitReport {
  double moved_max = 0;   //!< largest total move of a vertex, x the reference's bbox diagonal
  Index shortened = 0;    //!< vertex steps shortened or dropped because a face would fold
                          //!< or turn non-convex
};

//! Moves each vertex along its normal to lower the squared distance between the quads
//! (split along their shorter diagonal) and the reference, both ways: from the
//! reference's vertices (area-weighted) to the quads, and from regular samples of the
//! quads to the reference. Ours, not the paper's, whose vertices stay on the input:
//! faces that join points of a curved surface lie inside its bend, and moving their
//! corners off it by part of the bend halves that (bench/RESULTS.md). A step that
//! would fold a face or turn it non-convex is tried at half and a quarter, then
//! dropped. The connectivity is not changed. Deterministic.
SurfaceFitReport fit_to_surface(QuadMesh& mesh, const ReferenceSurface& ref, const SurfaceFitOptions& options = {});

}  // namespace qs
