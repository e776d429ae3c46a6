// The core alone (quadsimp::core, no file formats): a wavy grid made in memory, simplified.
// Usage: simplify_grid N
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <quadsimp/convert/prepare_input.h>
#include <quadsimp/simplify/pipeline.h>

int main(int argc, char** argv) {
  const int n = 40;
  qs::MeshFile grid;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      grid.positions.emplace_back(double(i) / n, double(j) / n, 0.05 * std::sin(6.0 * i / n) * std::cos(4.0 * j / n));
  const auto id = [n](int i, int j) { return qs::Index(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      grid.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      grid.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  qs::Input in = qs::prepare_input(grid, "grid");
  const qs::ReferenceSurface reference(std::move(in.reference));
  qs::SimplifyParams params;
  params.target_faces = qs::Index(argc > 1 ? std::atoi(argv[1]) : 100);
  qs::simplify_input(in, reference, params);
  std::printf("%u quads\n", in.quads.n_faces());
  return 0;
}
