// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// Preparing a noisy scan (cleaning and converting; no reading): the datasets' bunny.ply
// with Gaussian noise added to every vertex, 0.1% and 0.2% of its bounding-box diagonal
// (fixed seed). Its many small folds are laid flat on loading, which dominates: at 0.2%,
// 1,101 patches.
#include <benchmark/benchmark.h>

#include <fstream>
#include <random>
#include <string>

#include "quadsimp/convert/prepare_input.h"
#include "quadsimp/io/mesh_io.h"

namespace {

const char* kBunnyPly = QS_SHARED_DATASETS "/bunny.ply";

// Argument: the noise's standard deviation in millionths of the diagonal.
void BM_PrepareNoisyBunny(benchmark::State& state) {
  if (!std::ifstream(kBunnyPly)) return state.SkipWithError("the shared datasets' bunny.ply is not there");
  qs::MeshFile noisy = qs::read_mesh(kBunnyPly);
  std::mt19937 random(1);
  std::normal_distribution<double> gauss(0.0, 1e-6 * double(state.range(0)) * qs::bbox_diagonal(noisy.positions));
  for (qs::Vec3& p : noisy.positions) p += qs::Vec3(gauss(random), gauss(random), gauss(random));
  qs::Input in;
  for (auto _ : state) {
    in = qs::prepare_input(noisy, "noisy bunny");
    benchmark::DoNotOptimize(in.quads.n_faces());
  }
  state.counters["patches_laid_flat"] = double(in.clean.unfolded_patches);
  state.counters["quads"] = double(in.quads.n_faces());
}

BENCHMARK(BM_PrepareNoisyBunny)->Arg(1000)->Arg(2000)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
