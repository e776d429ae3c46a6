// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: any file is read or refused with InvalidInput, and what is read keeps
// read_mesh()'s word (every corner names a vertex, colours and texture come one per
// element or not at all), since the cleaning trusts it. Anything else (a crash, a
// sanitizer report, another exception, a hang or a huge allocation, which libFuzzer's
// -timeout and -malloc_limit_mb catch) is a bug. The file lies beside an image (and an
// OBJ beside its own bytes as m.mtl: fuzz_input.h), so that textures' code runs.
// scripts/fuzz.sh runs it.

#include "fuzz_input.h"
#include "quadsimp/io/mesh_io.h"
#include "quadsimp/util/errors.h"

namespace {

using qs::fuzz::require;

template <class Faces>
bool corners_name_vertices(const Faces& faces, std::size_t n) {
  for (const auto& f : faces)
    for (const qs::Index v : f)
      if (v >= n) return false;
  return true;
}

void check(const qs::MeshFile& file) {
  const std::size_t n = file.positions.size();
  require(n > 0, "no vertices");
  require(corners_name_vertices(file.triangles, n) && corners_name_vertices(file.quads, n),
          "a face corner names no vertex");
  require(file.colours.empty() || file.colours.size() == n, "vertex colours not one per vertex");
  require(!file.has_face_colours() ||
              (file.triangle_colours.size() == file.triangles.size() && file.quad_colours.size() == file.quads.size()),
          "face colours not one per face");
  const qs::FileTexture& t = file.texture;
  require(t.coords.size() == t.triangles.size() && t.image.size() == t.triangles.size(),
          "texture coordinates or images not one per texture triangle");
  require(t.colours.empty() || t.colours.size() == t.triangles.size(), "texture colours not one per triangle");
  require(corners_name_vertices(t.triangles, n), "a texture triangle's corner names no vertex");
  for (const int i : t.image) require(i >= -1 && i < int(t.images.size()), "a texture triangle names no image");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    check(qs::read_mesh(qs::fuzz::write_mesh(data, size, 1)));
  } catch (const qs::InvalidInput&) {
  }
  return 0;
}
