// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <string>
#include <vector>

#include "quadsimp/simplify/pipeline.h"
#include "quadsimp/texture/texture_bake.h"

namespace qs::cli {

//! Exit codes shared by every subcommand.
enum Exit : int { kOk = 0, kBadInput = 1, kBadArguments = 2 };

//! --remesh: the input's triangles remeshed isotropically before they are converted.
struct RemeshArgs {
  bool on = false;
  double edge_percent = 0;  // the edges' length in % of the bounding box's diagonal; 0: RemeshOptions' choice
};

struct ConvertArgs {
  std::string input, output;
  double crease_angle = 0;  // SimplifyParams::crease_angle
  RemeshArgs remesh;
  int texture_size = TextureBakeOptions().max_side;  // the quads' texture's largest side
  bool quiet = false;
};
int run_convert(const ConvertArgs& args);

//! One value of --faces or --edge-length: the target of one level (the SimplifyParams fields).
struct Target {
  Index faces = 0;
  double share = 0, edge = 0;
};

struct SimplifyArgs {
  std::string input, output;
  SimplifyParams params;  // the options bind to its fields, so the defaults are the pipeline's
  // The levels' targets, in the order given (none with automatic halting). With more than one
  // each level is written to OUT with its target count before the extension (out_2000.ply).
  std::vector<Target> targets;
  RemeshArgs remesh;
  int texture_size = TextureBakeOptions().max_side;  // the quads' texture's largest side
  bool stats = false, json = false, quiet = false;
  unsigned samples = 1000000;
};
int run_simplify(const SimplifyArgs& args);

struct FitmapArgs {
  std::string input, output;
  double tau = FitmapOptions().tau;
  // Also the tips --keep-tips holds, and adaptive mode's stretch, at a face count: a
  // whole number, "auto" (where automatic halting is predicted to stop) or "" (not asked).
  std::string tips_at, metric_at;
  double max_aspect = SimplifyParams().max_aspect;
  double m_factor = SimplifyParams().m_factor;  // the prediction's, as simplify's
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
