// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

namespace qs {

//! tbb::parallel_for over `range`, whose tasks compute with the calling thread's
//! floating-point settings (flush-to-zero, denormals-are-zero) whichever thread runs them.
//! Otherwise they take those of the context TBB made first, which depend on what used
//! TBB before: Embree's BVH build turns both on. Every parallel loop of the library runs
//! through this, so that a result does not depend on the history of the process (a CLI
//! run, a MeshLab plugin's): in the automatic halting measure, a ray cast from a quad lying
//! in M0's plane hit on one thread and missed on another, and a CAD cylinder with creases
//! halted at 774 or 66 quads (bench/RESULTS.md, "Floating-point settings in TBB's tasks").
template <class Range, class Body>
void parallel_for_as_here(const Range& range, const Body& body) {
  tbb::task_group_context context;
  context.capture_fp_settings();
  tbb::parallel_for(range, body, context);
}

//! The same over the indices first to last (excluded), `f` called with each.
template <class Index, class Function>
void parallel_for_as_here(Index first, Index last, const Function& f) {
  parallel_for_as_here(tbb::blocked_range<Index>(first, last), [&](const tbb::blocked_range<Index>& r) {
    for (Index i = r.begin(); i != r.end(); ++i) f(i);
  });
}

}  // namespace qs
