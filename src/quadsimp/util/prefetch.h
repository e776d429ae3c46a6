// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

namespace qs {

//! Asks the CPU to bring the cache line holding `p` (a hint: nothing else happens, and
//! compilers without a way to say it ignore it). For reads whose addresses are known a
//! while before the reads, so that misses on scattered data overlap instead of following
//! one another.
inline void prefetch(const void* p) {
#if defined(__GNUC__) && defined(__x86_64__)
  // Not __builtin_prefetch: GCC 12 at -O3 dropped some of those, whole loops of them once
  // inlined (the corners' loop of Simplifier::prefetch_feet()), with no warning. A
  // volatile asm stays; its operand only names the address, nothing is read.
  asm volatile("prefetcht0 %0" : : "m"(*static_cast<const char*>(p)));
#elif defined(__GNUC__)
  __builtin_prefetch(p);
#else
  (void)p;
#endif
}

}  // namespace qs
