// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// What the fuzzers share: the fuzzed bytes written to a file. The readers take a path
// (vcglib's STL importer only reads files), so each input goes through a file in a folder
// of /dev/shm named per process, so that fuzzers running side by side do not collide.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include "quadsimp/io/images.h"

namespace qs::fuzz {

//! This process's folder for the files it fuzzes, made on first use, with a 2 x 2 image
//! t.png in it for the files to name (a material's map_Kd, a PLY's TextureFile), and
//! removed when the process exits (not when it crashes: that is a finding).
inline const std::string& folder() {
  static const std::string path = [] {
    const std::string p = "/dev/shm/qs_fuzz_" + std::to_string(getpid());
    std::filesystem::create_directories(p);
    write_png(p + "/t.png", Image{2, 2, {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255}});
    return p;
  }();
  // Registered once `path` is made, so that it runs before `path` is destroyed.
  static const bool removed_at_exit = std::atexit([] {
    std::error_code ec;
    std::filesystem::remove_all(folder(), ec);
  }) == 0;
  (void)removed_at_exit;
  return path;
}

//! Writes `data` after its first `header` bytes to `name` in folder() and returns its path.
inline std::string write_file(const std::uint8_t* data, std::size_t size, std::size_t header, const std::string& name) {
  const std::string path = folder() + "/" + name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (size > header) out.write(reinterpret_cast<const char*>(data + header), std::streamsize(size - header));
  return path;
}

//! Writes a mesh file, its format chosen by the low two bits of the first byte (PLY, OBJ,
//! OFF or STL), and returns its path. An OBJ's bytes go to m.mtl beside it too, so that
//! its "mtllib m.mtl" reads its own material statements (which the OBJ reader skips) and
//! the textures' code runs; no other format reads a material file.
inline std::string write_mesh(const std::uint8_t* data, std::size_t size, std::size_t header) {
  static const char* const extensions[] = {"ply", "obj", "off", "stl"};
  const int format = size == 0 ? 0 : data[0] % 4;
  if (format == 1) write_file(data, size, header, "m.mtl");
  return write_file(data, size, header, std::string("in.") + extensions[format]);
}

//! A finding when `ok` is false: a promise of the code under test (`what`) was broken.
inline void require(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "broken promise: %s\n", what);
  std::abort();
}

}  // namespace qs::fuzz
