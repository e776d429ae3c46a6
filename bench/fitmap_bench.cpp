// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// Fitmaps on all cores: the Stanford bunny of glmark2-data (69,666 triangles), and a
// 1.1-million-triangle mesh made by splitting every bunny triangle into four, twice.
// The bunny run also reports the median and 90th percentile of the relative difference
// to the brute-force reference at every 97th vertex. The tips (`--keep-tips`) of the 1.1M
// mesh at the scales of 500, 5,000 and 50,000 quads. Each reports its peak memory
// (peak_rss.h), the meshes they read included.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "peak_rss.h"
#include "quadsimp/fitmap/fitmap.h"
#include "quadsimp/fitmap/tips.h"
#include "quadsimp/io/load_input.h"

namespace {

const char* kBunny = "/usr/share/glmark2/models/bunny.obj";

// The 1.1M mesh, loaded and split once for all the benchmarks that read it.
const qs::TriMesh& bunny_1m() {
  static const qs::TriMesh t = qs::split_in_four(qs::split_in_four(qs::load_input(kBunny).reference));
  return t;
}

// The q-quantile of v (0.5: the median, the upper one of an even count).
double quantile(std::vector<double> v, double q) {
  const auto at = v.begin() + std::ptrdiff_t(std::min(q * double(v.size()), double(v.size() - 1)));
  std::nth_element(v.begin(), at, v.end());
  return *at;
}

void BM_FitmapsBunny(benchmark::State& state) {
  if (!std::ifstream(kBunny)) return state.SkipWithError("glmark2-data's bunny.obj is not installed");
  const qs::TriMesh t = qs::load_input(kBunny).reference;
  const bool reset = qs_bench::reset_peak_rss();
  qs::Fitmaps fast;
  for (auto _ : state) fast = qs::compute_fitmaps_unsmoothed(t);
  qs_bench::report_peak(state, reset);  // before the brute force's own
  std::vector<qs::Index> sample;
  for (qs::Index v = 0; v < t.n_vertices(); v += 97) sample.push_back(v);
  const qs::Fitmaps ref = qs::fitmaps_brute_force(t, sample);
  std::vector<double> ds, dm;
  for (std::size_t j = 0; j < sample.size(); ++j) {
    if (ref.s[j] > 0) ds.push_back(std::abs(fast.s[sample[j]] - ref.s[j]) / ref.s[j]);
    dm.push_back(std::abs(fast.m[sample[j]] - ref.m[j]) / ref.m[j]);
  }
  state.counters["triangles"] = t.n_faces();
  state.counters["median_rel_diff_S"] = quantile(ds, 0.5);
  state.counters["median_rel_diff_M"] = quantile(dm, 0.5);
  // The median hides a bias confined to some radii: the tenth of vertices furthest off.
  state.counters["p90_rel_diff_S"] = quantile(ds, 0.9);
  state.counters["p90_rel_diff_M"] = quantile(dm, 0.9);
}

void BM_Fitmaps1M(benchmark::State& state) {
  if (!std::ifstream(kBunny)) return state.SkipWithError("glmark2-data's bunny.obj is not installed");
  const qs::TriMesh& t = bunny_1m();
  const bool reset = qs_bench::reset_peak_rss();
  for (auto _ : state) benchmark::DoNotOptimize(qs::compute_fitmaps(t).s.data());
  state.counters["triangles"] = t.n_faces();
  qs_bench::report_peak(state, reset);
}

void BM_Tips1M(benchmark::State& state) {
  if (!std::ifstream(kBunny)) return state.SkipWithError("glmark2-data's bunny.obj is not installed");
  const qs::TriMesh& t = bunny_1m();
  const qs::TipOptions o = qs::tip_options_for(t, double(state.range(0)));  // as the loop sets them
  const bool reset = qs_bench::reset_peak_rss();
  std::size_t found = 0;
  for (auto _ : state) found = qs::find_tips(t, o).size();
  state.counters["triangles"] = t.n_faces();
  qs_bench::report_peak(state, reset);
  state.counters["tips"] = double(found);
}

BENCHMARK(BM_FitmapsBunny)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_Fitmaps1M)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_Tips1M)->Arg(500)->Arg(5000)->Arg(50000)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
