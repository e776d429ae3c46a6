// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// Reading a 1.1-million-triangle mesh (the glmark2 bunny with every triangle split into
// four, twice) from binary PLY, OBJ and OFF, all three by our readers, warm file cache;
// and writing its 555,610 quads in each format.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include "quadsimp/io/load_input.h"
#include "quadsimp/io/mesh_io.h"

namespace {

const char* kBunny = "/usr/share/glmark2/models/bunny.obj";

// The three files, written on first use into the temporary folder, removed at exit.
class BenchFiles {
 public:
  BenchFiles() {
    const qs::TriMesh t = qs::split_in_four(qs::split_in_four(qs::load_input(kBunny).reference));
    qs::write_tri_mesh_ply(path("ply"), t);
    std::ofstream obj(path("obj")), off(path("off"));
    off << "OFF\n" << t.n_vertices() << ' ' << t.n_faces() << " 0\n";
    char line[128];
    for (const qs::Vec3& p : t.positions) {
      std::snprintf(line, sizeof line, "%.9g %.9g %.9g\n", p.x(), p.y(), p.z());
      obj << "v " << line;
      off << line;
    }
    for (const auto& f : t.faces) {
      obj << "f " << f[0] + 1 << ' ' << f[1] + 1 << ' ' << f[2] + 1 << '\n';
      off << "3 " << f[0] << ' ' << f[1] << ' ' << f[2] << '\n';
    }
  }
  ~BenchFiles() {
    std::error_code ec;
    for (const char* ext : {"ply", "obj", "off"}) std::filesystem::remove(path(ext), ec);
  }
  std::string path(const std::string& ext) const { return stem_ + "." + ext; }

 private:
  std::string stem_ = (std::filesystem::temp_directory_path() / "qs_read_bench").string();
};

void BM_Read(benchmark::State& state, const std::string& ext) {
  if (!std::ifstream(kBunny)) return state.SkipWithError("glmark2-data's bunny.obj is not installed");
  static const BenchFiles files;
  const std::string path = files.path(ext);
  std::size_t triangles = 0;
  for (auto _ : state) triangles = qs::read_mesh(path).triangles.size();
  state.counters["triangles"] = double(triangles);
  state.counters["MB"] = double(std::filesystem::file_size(path)) / 1e6;
}

void BM_Write(benchmark::State& state, const std::string& ext) {
  if (!std::ifstream(kBunny)) return state.SkipWithError("glmark2-data's bunny.obj is not installed");
  static const BenchFiles files;
  static const qs::QuadMesh quads = qs::load_input(files.path("ply")).quads;
  const std::string path = files.path("out." + ext);
  for (auto _ : state) qs::write_quad_mesh(path, quads);
  state.counters["quads"] = double(quads.n_faces());
  state.counters["MB"] = double(std::filesystem::file_size(path)) / 1e6;
  std::error_code ec;
  std::filesystem::remove(path, ec);
}

BENCHMARK_CAPTURE(BM_Read, ply_binary, std::string("ply"))->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_Read, obj, std::string("obj"))->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_Read, off, std::string("off"))->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_Write, ply_binary, std::string("ply"))->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_Write, obj, std::string("obj"))->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_Write, off, std::string("off"))->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
