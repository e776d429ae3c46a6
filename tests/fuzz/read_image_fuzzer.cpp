// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: any file is read as an image (a texture named by an OBJ's material or
// a PLY's TextureFile) or refused with InvalidInput, and what is read holds four bytes
// per texel, kMaxImageTexels at most. Anything else (a crash, a sanitizer report, a hang,
// a huge allocation) is a bug. scripts/fuzz.sh runs it.

#include "fuzz_input.h"
#include "quadsimp/io/images.h"
#include "quadsimp/util/errors.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const qs::Image im = qs::read_image(qs::fuzz::write_file(data, size, 0, "image"));
    qs::fuzz::require(im.width > 0 && im.height > 0 && im.rgba.size() == std::size_t(im.width) * im.height * 4,
                      "an image's texels not four bytes each");
    qs::fuzz::require(im.rgba.size() <= 4 * qs::kMaxImageTexels, "an image over kMaxImageTexels");
  } catch (const qs::InvalidInput&) {
  }
  return 0;
}
