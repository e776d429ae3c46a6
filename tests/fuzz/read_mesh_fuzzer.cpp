// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: any file is read or refused with InvalidInput. Anything else (a
// crash, a sanitizer report, another exception, a hang or a huge allocation, which
// libFuzzer's -timeout and -malloc_limit_mb catch) is a bug. scripts/fuzz.sh runs it.
#include "fuzz_input.h"
#include "quadsimp/io/mesh_io.h"
#include "quadsimp/util/errors.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    qs::read_mesh(qs::fuzz::write_input(data, size, 1));
  } catch (const qs::InvalidInput&) {
  }
  return 0;
}
