// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstddef>
#include <vector>

#include "quadsimp/mesh/tri_mesh.h"

namespace qs {

//! Where the input ends in a point at the scale of the result's quads (ours): a claw, a
//! toe, an aircraft's nose. The springs of the smoothing, longer there than the tip is
//! wide, slide the vertices near such a tip back along it, cutting it off (the armadillo's
//! claws, pyvista's airplane: bench/RESULTS.md, "Tips kept").
struct TipOptions {
  double radius = 0;        //!< the scale: about one edge of the result
  //! Every vertex from 0.7 radius from the tip to the first ones past the radius lies
  //! below it along its normal by at least this share of its distance (0.5: a cone of
  //! half-angle 60 degrees or sharper; a sphere is a tip only if its radius is under
  //! `radius`).
  double min_slope = 0.5;
  std::size_t max_tips = 0;  //!< the steepest ones kept (0: all)
};

//! The options `--keep-tips` takes for a result of about `quads` quads on `mesh`: the
//! radius is the side of `quads` squares covering it, and at most 5% of `quads` tips (and
//! one): tips are few, and every held vertex stiffens the quads.
TipOptions tip_options_for(const TriMesh& mesh, double quads);

//! The tips of a clean triangle mesh: interior vertices whose neighbourhood (the part of
//! the ball of `radius` connected to them through edges inside it) lies entirely below
//! them along their angle-weighted normal, within a tenth of the radius, and falls away at
//! `min_slope` all round at its rim (its vertices from 0.7 radius out, and the first ones
//! past it); of tips nearer each other than the radius, the steepest only. Sorted by vertex
//! index. Ridges (a wing's edge) and flat or saddle-shaped places are not tips: along a
//! ridge the surface does not fall away. A solid's corner is one where its sides fall away
//! steeply enough (a cube's at 0.58). In parallel (TBB); deterministic.
std::vector<Index> find_tips(const TriMesh& mesh, const TipOptions& options);

}  // namespace qs
