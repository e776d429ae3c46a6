// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// End-to-end speed of the uniform simplifier on the Stanford bunny of glmark2-data
// (69,666 triangles) down to 5,000 quads, single thread: load + clean + convert +
// BVH + simplify, with the default two passes per collapse and with --fast (one).
// Reports collapses per second and the process's peak memory.
#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <tbb/global_control.h>

#include <fstream>

#include "quadsimp/io/load_input.h"
#include "quadsimp/reference/reference_surface.h"
#include "quadsimp/simplify/simplify.h"

namespace {

const char* kBunny = "/usr/share/glmark2/models/bunny.obj";

double peak_rss_mib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

void BM_BunnyTo5000(benchmark::State& state) {
  if (!std::ifstream(kBunny)) {
    state.SkipWithError("glmark2-data's bunny.obj is not installed");
    return;
  }
  tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  qs::SimplifyReport last;
  for (auto _ : state) {
    qs::Input in = qs::load_input(kBunny);
    const qs::ReferenceSurface ref(std::move(in.reference));
    qs::SimplifyOptions opt;
    opt.target_faces = qs::Index(state.range(0));
    opt.passes = int(state.range(1));
    last = qs::simplify(in.quads, ref, opt);
    benchmark::DoNotOptimize(in.quads.n_faces());
  }
  state.counters["collapses_per_s"] = last.collapses / last.seconds;
  state.counters["simplify_s"] = last.seconds;
  state.counters["faces"] = last.faces;
  state.counters["peak_MiB"] = peak_rss_mib();
}

// Arguments: target faces, rotation/smoothing passes per collapse (2: default, 1: --fast).
BENCHMARK(BM_BunnyTo5000)->Args({5000, 2})->Args({5000, 1})->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
