// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// Peak resident memory of one benchmark at a time. getrusage()'s ru_maxrss never goes
// down, so in one process every benchmark would report the largest peak of those run
// before it; Linux resets the high-water mark (VmHWM) to the current size when "5" is
// written to /proc/self/clear_refs.
#pragma once

#include <benchmark/benchmark.h>
#include <malloc.h>
#include <sys/resource.h>

#include <fstream>
#include <string>

namespace qs_bench {

//! Hands memory freed by earlier benchmarks back to the system (so that it does not
//! count as this one's), then resets the high-water mark. False where it cannot.
inline bool reset_peak_rss() {
  malloc_trim(0);
  std::ofstream clear("/proc/self/clear_refs");
  return clear && (clear << "5").flush();
}

//! The high-water mark since the last reset, in MiB; 0 where /proc says nothing.
inline double peak_rss_mib() {
  std::ifstream status("/proc/self/status");
  for (std::string key; status >> key;) {
    if (key == "VmHWM:") {
      double kib = 0;
      status >> kib;
      return kib / 1024.0;
    }
  }
  return 0;
}

//! Records this benchmark's peak as `peak_MiB` when the reset before it worked, else the
//! process's peak so far as `process_peak_MiB`, which is not this benchmark's own.
inline void report_peak(benchmark::State& state, bool was_reset) {
  if (was_reset) {
    state.counters["peak_MiB"] = peak_rss_mib();
    return;
  }
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  state.counters["process_peak_MiB"] = double(u.ru_maxrss) / 1024.0;  // KiB on Linux
}

}  // namespace qs_bench
