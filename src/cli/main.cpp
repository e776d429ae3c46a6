// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>

#include "cli/commands.h"

int main(int argc, char** argv) {
  using namespace qs::cli;
  CLI::App app{"quadsimp: adaptive quad mesh simplification (Bozzo et al. 2010)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "quadsimp 0.1.0");

  ConvertArgs convert;
  auto* c = app.add_subcommand("convert", "Convert a triangle mesh (PLY, OBJ, OFF, STL) into a pure quad mesh");
  c->add_option("IN", convert.input, "input mesh")->required()->check(CLI::ExistingFile);
  c->add_option("OUT", convert.output, "output quad mesh (.ply, .obj or .off)")->required();
  c->add_flag("-q,--quiet", convert.quiet, "no notes on stderr");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kOk : kBadArguments;
  }
  try {
    if (*c) return run_convert(convert);
  } catch (const std::exception& e) {
    std::cerr << "quadsimp: internal error: " << e.what() << "\n";
    return 3;
  }
  return kBadArguments;
}
