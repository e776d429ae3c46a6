// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

namespace qs {

//! Asks the CPU to bring the cache line holding `p` (a hint: nothing else happens, and
//! compilers without the builtin ignore it). For reads whose addresses are known a while
//! before the reads, so that misses on scattered data overlap instead of following one
//! another.
inline void prefetch(const void* p) {
#if defined(__GNUC__)
  __builtin_prefetch(p);
#else
  (void)p;
#endif
}

}  // namespace qs
