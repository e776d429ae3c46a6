// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// Reading a 1.1-million-triangle mesh (the glmark2 bunny with every triangle split into
// four, twice) from binary PLY, OBJ and OFF, all three by our readers, warm file cache;
// and writing its 555,610 quads in each format; and baking a texture onto quads.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include "quadsimp/io/load_input.h"
#include "quadsimp/io/mesh_io.h"
#include "quadsimp/reference/reference_surface.h"
#include "quadsimp/simplify/pipeline.h"
#include "quadsimp/texture/texture_bake.h"

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

// Baking a texture onto quads: the glmark2 bunny (69,666 triangles) mapped by a planar
// projection into a 2,048 x 2,048 image, onto its simplification to `range(0)` quads.
void BM_BakeTexture(benchmark::State& state) {
  if (!std::ifstream(kBunny)) return state.SkipWithError("glmark2-data's bunny.obj is not installed");
  qs::Input in = qs::load_input(kBunny);
  const qs::TriMesh input = in.reference;
  const qs::ReferenceSurface reference(std::move(in.reference));
  qs::SimplifyParams params;
  params.target_faces = qs::Index(state.range(0));
  qs::simplify_input(in, reference, params);
  qs::Vec3 lo = input.positions[0], hi = lo;
  for (const qs::Vec3& p : input.positions) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  qs::FileTexture texture;
  texture.images = {"planar"};
  for (const auto& f : input.faces) {
    std::array<qs::TexCoord, 3> uv;
    for (int k = 0; k < 3; ++k) {
      const qs::Vec3 t = (input.positions[f[k]] - lo).cwiseQuotient(hi - lo);
      uv[k] = {float(t.x()), float(t.y())};
    }
    texture.triangles.push_back(f);
    texture.coords.push_back(uv);
    texture.image.push_back(0);
  }
  qs::Image image;
  image.width = image.height = 2048;
  for (int y = 0; y < 2048; ++y)
    for (int x = 0; x < 2048; ++x)
      image.rgba.insert(image.rgba.end(), {std::uint8_t(x), std::uint8_t(y), std::uint8_t(x ^ y), 255});
  qs::QuadTexture baked;
  for (auto _ : state) baked = qs::bake_texture(input.positions, texture, {image}, in.quads);
  state.counters["quads"] = double(in.quads.n_faces());
  state.counters["texels"] = double(baked.image.width) * baked.image.height;
}
BENCHMARK(BM_BakeTexture)->Arg(1000)->Arg(5000)->Unit(benchmark::kMillisecond)->Iterations(3);

BENCHMARK_CAPTURE(BM_Read, ply_binary, std::string("ply"))->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_Read, obj, std::string("obj"))->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_Read, off, std::string("off"))->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_Write, ply_binary, std::string("ply"))->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_Write, obj, std::string("obj"))->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_Write, off, std::string("off"))->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
