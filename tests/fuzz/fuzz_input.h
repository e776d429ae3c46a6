// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// What the fuzzers share: the fuzzed bytes written to a mesh file. The readers take a
// path (vcglib's STL importer only reads files), so each input goes through a file in
// /dev/shm, named per process so that fuzzers running side by side do not collide.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

namespace qs::fuzz {

//! Writes `data` after its first `header` bytes to a file and returns its path; the low
//! two bits of the first byte choose PLY, OBJ, OFF or STL.
inline std::string write_input(const std::uint8_t* data, std::size_t size, std::size_t header) {
  static const char* const extensions[] = {"ply", "obj", "off", "stl"};
  const std::string path =
      "/dev/shm/qs_fuzz_" + std::to_string(getpid()) + "." + extensions[size == 0 ? 0 : data[0] % 4];
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (size > header) out.write(reinterpret_cast<const char*>(data + header), std::streamsize(size - header));
  return path;
}

//! A finding when `ok` is false: a promise of the code under test (`what`) was broken.
inline void require(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "broken promise: %s\n", what);
  std::abort();
}

}  // namespace qs::fuzz
