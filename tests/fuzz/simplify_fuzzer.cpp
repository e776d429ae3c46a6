// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: a small mesh file is loaded (cleaned, converted) and simplified with
// options its first two bytes choose, and the result must pass validate(). Refusing the
// file (InvalidInput) is fine; any other exception, a TopologyError above all, a crash, a
// sanitizer report or a hang is a bug. The meshes are small (odd geometry, not size, is
// what breaks operators), so each input takes milliseconds.
#include "fuzz_input.h"
#include "quadsimp/io/load_input.h"
#include "quadsimp/reference/reference_surface.h"
#include "quadsimp/simplify/pipeline.h"
#include "quadsimp/util/errors.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 3) return 0;
  // Byte 0: the format (fuzz_input.h), the mode, and the target in sixteenths of the quads.
  // Byte 1: one bit per option, and the M-fitmap's tolerance.
  const std::uint8_t mode = data[0], flags = data[1];
  qs::SimplifyParams params;
  params.adaptive = mode & 4;
  params.auto_halt = params.adaptive && (mode & 8);
  params.preserve_boundary = flags & 1;
  params.keep_tips = flags & 2;
  params.crease_angle = (flags & 4) ? 30 : 0;
  params.fast = flags & 8;
  params.fit_to_input = flags & 16;
  params.max_aspect = (flags & 32) ? 1 : params.max_aspect;
  params.tau = (flags & 64) ? 0.2 : (flags & 128) ? 0.01 : params.tau;
  qs::Input in;
  try {
    in = qs::load_input(qs::fuzz::write_input(data, size, 2), qs::convert_options(params));
  } catch (const qs::InvalidInput&) {
    return 0;
  }
  if (in.quads.n_faces() > 2000) return 0;
  if (!params.auto_halt) params.target_faces = 1 + (mode >> 4) * in.quads.n_faces() / 16;
  const qs::ReferenceSurface ref(std::move(in.reference));
  qs::simplify_input(in, ref, params);
  qs::validate(in.quads);
  return 0;
}
