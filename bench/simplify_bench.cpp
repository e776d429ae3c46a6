// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// End-to-end speed of the simplifier on the Stanford bunny (69,666 triangles): uniform
// down to 5,000 quads on one thread (load + clean + convert + BVH + simplify, with the
// default two passes per collapse and with --fast's one), and adaptive with automatic
// halting on both cores, fitmaps included, as `quadsimp simplify --adaptive --auto-halt`
// runs it. Reports collapses per second and each benchmark's peak memory (peak_rss.h).
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <fstream>
#include <string>

#include "peak_rss.h"
#include "quadsimp/io/load_input.h"
#include "quadsimp/reference/reference_surface.h"
#include "quadsimp/simplify/pipeline.h"
#include "quadsimp/simplify/simplify.h"

namespace {

const char* kBunny = "/usr/share/glmark2/models/bunny.obj";
const char* kBunnyPly = QS_SHARED_DATASETS "/bunny.ply";  // the paper's Tables 2 and 3 bunny

void BM_BunnyTo5000(benchmark::State& state) {
  if (!std::ifstream(kBunny)) {
    state.SkipWithError("glmark2-data's bunny.obj is not installed");
    return;
  }
  tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  const bool reset = qs_bench::reset_peak_rss();
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
  qs_bench::report_peak(state, reset);
}

// Arguments: target faces, rotation/smoothing passes per collapse (2: default, 1: --fast).
BENCHMARK(BM_BunnyTo5000)->Args({5000, 2})->Args({5000, 1})->Unit(benchmark::kMillisecond)->Iterations(3);

// The target of bench/RESULTS.md's Tables 2 and 3: under 5 s on 2 cores, everything
// included. Argument 0: glmark2-data's bunny.obj; 1: the shared datasets' bunny.ply.
void BM_BunnyAdaptive(benchmark::State& state) {
  const char* path = state.range(0) == 0 ? kBunny : kBunnyPly;
  if (!std::ifstream(path)) return state.SkipWithError((std::string(path) + " is not there").c_str());
  qs::SimplifyParams params;
  params.adaptive = true;
  params.auto_halt = true;
  const bool reset = qs_bench::reset_peak_rss();
  qs::SimplifyReport last;
  for (auto _ : state) {
    qs::Input in = qs::load_input(path);
    const qs::Fitmaps fitmaps = qs::input_fitmaps(in, params);
    const qs::ReferenceSurface ref(std::move(in.reference));
    last = qs::simplify_input(in, ref, params, {}, &fitmaps);
    benchmark::DoNotOptimize(in.quads.n_faces());
  }
  state.counters["loop_s"] = last.seconds;
  state.counters["faces"] = last.faces;
  qs_bench::report_peak(state, reset);
}

BENCHMARK(BM_BunnyAdaptive)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
