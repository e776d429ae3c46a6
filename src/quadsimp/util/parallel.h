// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

namespace qs {

//! tbb::parallel_for over `range`, whose tasks compute with the calling thread's
//! floating-point settings (flush-to-zero, denormals-are-zero) whichever thread runs them.
//! Otherwise they take those of the context TBB made first, which depend on what used
//! TBB before: Embree's BVH build turns both on. A loop whose parallel verdicts must match
//! its serial ones needs this: a ray cast from a quad lying in M0's plane hit on one
//! thread and missed on another, and a CAD cylinder with creases halted at 774 or 66
//! quads by the history of the process (bench/RESULTS.md, "Floating-point settings").
template <class Range, class Body>
void parallel_for_as_here(const Range& range, const Body& body) {
  tbb::task_group_context context;
  context.capture_fp_settings();
  tbb::parallel_for(range, body, context);
}

}  // namespace qs
