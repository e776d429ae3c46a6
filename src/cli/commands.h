// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <string>

#include "quadsimp/simplify/pipeline.h"

namespace qs::cli {

//! Exit codes shared by every subcommand.
enum Exit : int { kOk = 0, kBadInput = 1, kBadArguments = 2 };

struct ConvertArgs {
  std::string input, output;
  bool quiet = false;
};
int run_convert(const ConvertArgs& args);

struct SimplifyArgs {
  std::string input, output;
  unsigned faces = 0;
  bool adaptive = false, auto_halt = false, preserve_boundary = false, fast = false, fit_to_input = false, stats = false, json = false,
       quiet = false;
  double tau = SimplifyParams().tau, m_factor = SimplifyParams().m_factor, m_slack = SimplifyParams().m_slack,
         halt_share = SimplifyParams().halt_share, max_aspect = SimplifyParams().max_aspect,
         reach = SimplifyParams().reach;
  unsigned samples = 1000000;
};
int run_simplify(const SimplifyArgs& args);

struct FitmapArgs {
  std::string input, output;
  double tau = FitmapOptions().tau;
  bool quiet = false;
};
int run_fitmap(const FitmapArgs& args);

struct StatsArgs {
  std::string reference, quads;
  bool json = false;
  unsigned samples = 1000000;
};
int run_stats(const StatsArgs& args);

//! Refuses to write over the input; returns an error message or "".
std::string check_output_path(const std::string& input, const std::string& output);

}  // namespace qs::cli
