// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "cli/commands.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "quadsimp/io/load_input.h"
#include "quadsimp/io/mesh_io.h"
#include "quadsimp/util/errors.h"

namespace qs::cli {
namespace {

LogFn stderr_log(bool quiet) {
  if (quiet) return {};
  return [](std::string_view m) { std::cerr << "note: " << m << "\n"; };
}

}  // namespace

std::string check_output_path(const std::string& input, const std::string& output) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(output, ec) && fs::equivalent(input, output, ec))
    return "refusing to write the output over the input file " + input;
  const std::string ext = extension_of(output);
  if (ext != "ply" && ext != "obj" && ext != "off")
    return "output " + output + " must end in .ply, .obj or .off";
  const fs::path dir = fs::absolute(output).parent_path();
  if (!fs::is_directory(dir, ec)) return "output folder " + dir.string() + " does not exist";
  return {};
}

int run_convert(const ConvertArgs& a) {
  if (auto err = check_output_path(a.input, a.output); !err.empty()) {
    std::cerr << "quadsimp convert: " << err << "\n";
    return kBadArguments;
  }
  try {
    const auto t0 = std::chrono::steady_clock::now();
    Input in = load_input(a.input, {}, stderr_log(a.quiet));
    write_quad_mesh(a.output, in.quads);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (in.was_pure_quad) {
      std::printf("%s: already pure quad, %u quads written to %s (%.2f s)\n", a.input.c_str(),
                  in.quads.n_faces(), a.output.c_str(), s);
    } else {
      const auto& r = in.convert;
      std::printf("%s: %u triangles -> %u quads (paired %.2f%%: greedy %u, re-paired %u; border splits: %u parity, %u unmatchable%s), written to %s (%.2f s)\n",
                  a.input.c_str(), r.input_triangles, r.quads, 100.0 * r.pairing_rate(), r.paired_greedy,
                  r.paired_augmented, r.parity_splits, r.border_splits,
                  r.refined ? "; refined once" : "", a.output.c_str(), s);
    }
    return kOk;
  } catch (const InvalidInput& e) {
    std::cerr << "quadsimp convert: " << e.what() << "\n";
    return kBadInput;
  }
}

}  // namespace qs::cli
