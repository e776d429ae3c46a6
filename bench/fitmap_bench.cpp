// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// Fitmaps on all cores: the Stanford bunny of glmark2-data (69,666 triangles), and a
// 1.1-million-triangle mesh made by splitting every bunny triangle into four, twice.
// The bunny run also reports the median relative difference to the brute-force
// reference at every 97th vertex.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <fstream>
#include <map>

#include "quadsimp/fitmap/fitmap.h"
#include "quadsimp/io/load_input.h"

namespace {

const char* kBunny = "/usr/share/glmark2/models/bunny.obj";

qs::TriMesh split_in_four(const qs::TriMesh& t) {
  qs::TriMesh out;
  out.positions = t.positions;
  std::map<std::pair<qs::Index, qs::Index>, qs::Index> mid;
  auto midpoint = [&](qs::Index a, qs::Index b) {
    const auto key = std::minmax(a, b);
    auto [it, fresh] = mid.emplace(std::pair<qs::Index, qs::Index>(key.first, key.second), out.n_vertices());
    if (fresh) out.positions.push_back(0.5 * (t.positions[a] + t.positions[b]));
    return it->second;
  };
  for (const auto& f : t.faces) {
    const qs::Index ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
    out.faces.push_back({f[0], ab, ca});
    out.faces.push_back({ab, f[1], bc});
    out.faces.push_back({ca, bc, f[2]});
    out.faces.push_back({ab, bc, ca});
  }
  return out;
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

void BM_FitmapsBunny(benchmark::State& state) {
  if (!std::ifstream(kBunny)) return state.SkipWithError("glmark2-data's bunny.obj is not installed");
  const qs::TriMesh t = qs::load_input(kBunny).reference;
  qs::Fitmaps fast;
  for (auto _ : state) fast = qs::compute_fitmaps_unsmoothed(t);
  std::vector<qs::Index> sample;
  for (qs::Index v = 0; v < t.n_vertices(); v += 97) sample.push_back(v);
  const qs::Fitmaps ref = qs::fitmaps_brute_force(t, sample);
  std::vector<double> ds, dm;
  for (std::size_t j = 0; j < sample.size(); ++j) {
    if (ref.s[j] > 0) ds.push_back(std::abs(fast.s[sample[j]] - ref.s[j]) / ref.s[j]);
    dm.push_back(std::abs(fast.m[sample[j]] - ref.m[j]) / ref.m[j]);
  }
  state.counters["triangles"] = t.n_faces();
  state.counters["median_rel_diff_S"] = median(ds);
  state.counters["median_rel_diff_M"] = median(dm);
}

void BM_Fitmaps1M(benchmark::State& state) {
  if (!std::ifstream(kBunny)) return state.SkipWithError("glmark2-data's bunny.obj is not installed");
  const qs::TriMesh t = split_in_four(split_in_four(qs::load_input(kBunny).reference));
  for (auto _ : state) benchmark::DoNotOptimize(qs::compute_fitmaps(t).s.data());
  state.counters["triangles"] = t.n_faces();
}

BENCHMARK(BM_FitmapsBunny)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_Fitmaps1M)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
