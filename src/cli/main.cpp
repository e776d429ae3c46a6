// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <exception>
#include <iostream>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cli/commands.h"
#include "quadsimp/util/parse_number.h"

namespace {

// CLI11's PositiveNumber answers 0 with "Value 0 not in range 0.000000 to" and the
// largest double in 309 digits; these say what is wanted.
std::string not_a_whole_number(const std::string& s, unsigned least, unsigned most) {
  unsigned long long x = 0;
  if (!qs::parse_number(s, x) || x < least || x > most)
    return "'" + s + "' is not a whole number from " + std::to_string(least) + " to " + std::to_string(most);
  return {};
}

std::string not_a_whole_number_from_one(const std::string& s) {
  return not_a_whole_number(s, 1, std::numeric_limits<unsigned>::max());
}

// A bound against typos (-j 10000): threads beyond the cores only take turns on them.
constexpr unsigned kMostThreads = 1024;

CLI::Validator whole_number_from_one() {
  return CLI::Validator([](std::string& s) { return not_a_whole_number_from_one(s); }, "N>=1");
}

// --crease-angle DEG: the sharp edges kept (0: none, the default).
void add_crease_angle(CLI::App* command, double& angle, const std::string& what) {
  command->add_option("--crease-angle", angle, what + " (degrees between their faces' normals; 0: none)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 179.0));
}

void add_texture_size(CLI::App* command, int& size) {
  command->add_option("--texture-size", size,
                      "the largest width and height of the quads' texture, baked from the input's (OBJ, PLY output)")
      ->capture_default_str()
      ->check(CLI::Range(qs::TextureBakeOptions::kSmallestSide, qs::TextureBakeOptions::kLargestSide));
}

// --remesh, and --remesh-edge PCT with it.
void add_remesh(CLI::App* command, qs::cli::RemeshArgs& remesh) {
  auto* on = command->add_flag("--remesh", remesh.on,
                               "remesh the input isotropically before converting it, as MeshLab's \"Isotropic Explicit "
                               "Remeshing\" does (for CAD tessellations' long, thin triangles: the quads are fitted to "
                               "the remeshing, and distances measured from the input)");
  command->add_option("--remesh-edge", remesh.edge_percent,
                      "with --remesh: the edges' length in % of the bounding box's diagonal (default 1, shorter "
                      "where --faces or --edge-length asks for more than about a fifth of the quads that would "
                      "give, longer where it would give over 200,000 triangles)")
      ->needs(on)
      ->check(CLI::Range(0.01, 100.0));
}

CLI::Validator face_count_or_auto() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        if (s == "auto" || not_a_whole_number_from_one(s).empty()) return {};
        return "'" + s + "' is neither a whole number from 1 nor 'auto'";
      },
      "");
}

// One value of --faces: "N", or "P%" of the quads the input converts to. Returns "" or why
// `s` is neither; adds the target to `targets` when given one (the validator checks, the
// callback sets).
std::string parse_face_target(const std::string& s, std::vector<qs::cli::Target>* targets) {
  qs::cli::Target t;
  if (!s.empty() && s.back() == '%') {
    double percent = 0;
    if (!qs::parse_number(std::string_view(s).substr(0, s.size() - 1), percent) || !(percent > 0 && percent <= 100))
      return "'" + s + "' is not a share above 0% and at most 100%";
    t.share = percent / 100;
  } else if (std::string why = not_a_whole_number_from_one(s); !why.empty()) {
    return why;
  } else {
    qs::parse_number(s, t.faces);
  }
  if (targets) targets->push_back(t);
  return {};
}

CLI::Validator number_above_zero() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        double x = 0;
        if (!qs::parse_number(s, x) || !(x > 0) || !std::isfinite(x)) return "'" + s + "' is not a number above 0";
        return {};
      },
      "X>0");
}

}  // namespace

int main(int argc, char** argv) {
  using namespace qs::cli;
  CLI::App app{"quadsimp: adaptive quad mesh simplification (Bozzo et al. 2010)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "quadsimp 0.1.0");
  // Before the subcommands, so that they inherit it: --threads goes before or after the
  // subcommand's name.
  app.fallthrough();
  unsigned threads = 0;
  app.add_option("-j,--threads", threads,
                 "run the parallel parts (fitmaps, distance sampling, BVH builds) on at most this many threads "
                 "(0: as many as the machine has); the output is the same whatever the number")
      ->capture_default_str()
      ->type_name("N")
      ->check(CLI::Validator([](std::string& s) { return not_a_whole_number(s, 0, kMostThreads); }, ""));

  ConvertArgs convert;
  auto* c = app.add_subcommand("convert", "Convert a triangle mesh (PLY, OBJ, OFF, STL) into a pure quad mesh");
  c->add_option("IN", convert.input, "input mesh")->required()->check(CLI::ExistingFile);
  c->add_option("OUT", convert.output, "output quad mesh (.ply, .obj or .off)")->required();
  add_crease_angle(c, convert.crease_angle, "pair no triangles across edges sharper than this");
  add_remesh(c, convert.remesh);
  add_texture_size(c, convert.texture_size);
  c->add_flag("-q,--quiet", convert.quiet, "no notes on stderr");

  SimplifyArgs simp;
  auto* s = app.add_subcommand("simplify", "Simplify a triangle or quad mesh into a coarser pure quad mesh");
  s->add_option("IN", simp.input, "input mesh (PLY, OBJ, OFF, STL; triangles or quads)")
      ->required()
      ->check(CLI::ExistingFile);
  s->add_option("OUT", simp.output, "output quad mesh (.ply, .obj or .off)")->required();
  // The two targets' values: one word each time the option is given, split at its commas (a
  // list option would take IN and OUT after it too).
  auto* faces = s->add_option_function<std::vector<std::string>>(
                     "-f,--faces",
                     [&simp](const std::vector<std::string>& values) {
                       for (const std::string& v : values) parse_face_target(v, &simp.targets);
                     },
                     "target number of quads, or a share of the input's quads (10%); several, comma-separated, "
                     "for levels of detail in one run, each going on from the one before (OUT_N.ext for N quads)")
                    ->type_name("N|P%[,...]")
                    ->allow_extra_args(false)
                    ->delimiter(',')
                    ->check(CLI::Validator([](std::string& v) { return parse_face_target(v, nullptr); }, ""));
  s->add_option_function<std::vector<double>>(
       "--edge-length",
       [&simp](const std::vector<double>& edges) {
         for (double edge : edges) simp.targets.push_back({0, 0, edge});
       },
       "target: as many quads as quads of this edge length (in the input's units) take to cover the input's "
       "surface, in place of --faces; several, comma-separated, for levels of detail as with --faces")
      ->type_name("L[,...]")
      ->allow_extra_args(false)
      ->delimiter(',')
      ->check(number_above_zero())
      ->excludes(faces);
  s->add_flag("--adaptive", simp.params.adaptive, "adaptive mode driven by fitmaps");
  s->add_flag(
      "--auto-halt", simp.params.auto_halt,
      "adaptive: stop once the faces whose collapses the M-fitmap (or --reach) refuses cover --halt-share of the "
      "surface");
  s->add_option("--tau", simp.params.tau, "adaptive: M-fitmap tolerance (share of inconsistent area)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  s->add_option("--m-factor", simp.params.m_factor,
                "adaptive: the M-fitmap's bound on a face radius is F_M / this (see --m-slack)")
      ->capture_default_str()
      ->check(number_above_zero());
  s->add_option("--m-slack", simp.params.m_slack,
                "adaptive: collapses may grow a face smaller than --reach up to this times the M-fitmap's bound; "
                "--auto-halt still measures where faces reach the bound itself (1: the paper's)")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 100.0));
  s->add_option("--halt-share", simp.params.halt_share,
                "auto-halt: share of the surface the M-fitmap may block before stopping (1: until no feasible collapse "
                "remains, the paper's rule)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  s->add_option("--max-aspect", simp.params.max_aspect,
                "adaptive: how much longer than wide quads may grow along the flatter direction, and as much "
                "further past the M-fitmap's bound there (1: square quads and the paper's bound)")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 100.0));
  s->add_option("--reach", simp.params.reach,
                "adaptive: refuse collapses that leave a large quad's centre or edge midpoints without the input "
                "along its normal within this share of the bounding-box diagonal (0: no check)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  s->add_flag("--preserve-boundary", simp.params.preserve_boundary,
              "keep the border exactly as it is (else border vertices slide along it, and move inwards by about "
              "one input edge at most where a ragged outline leaves a border edge over nothing)");
  s->add_flag("--keep-tips", simp.params.keep_tips,
              "hold a vertex at each tip of the input (claws, a nose) that the smoothing would otherwise cut back, "
              "and refuse to fold quads round thin parts in uniform mode too (ours)");
  add_crease_angle(s, simp.params.crease_angle, "keep the input's edges sharper than this as edges of the quads");
  add_remesh(s, simp.remesh);
  s->add_flag("--fast", simp.params.fast,
              "one rotation/smoothing pass per collapse (the paper's loop): about 20% faster, less regular");
  s->add_flag(
      "--fit-to-input", simp.params.fit_to_input,
      "afterwards, move the vertices along their normals, off the input, to lower the distance both ways (ours)");
  add_texture_size(s, simp.texture_size);
  s->add_flag("--stats", simp.stats, "print quality and distance metrics of the result");
  s->add_flag("--json", simp.json, "print the result's metrics (and the time) as one JSON object");
  s->add_option("--samples", simp.samples, "distance samples per surface for --stats")
      ->capture_default_str()
      ->check(whole_number_from_one());
  s->add_flag("-q,--quiet", simp.quiet, "no progress bar and no notes");

  FitmapArgs fit;
  auto* fm =
      app.add_subcommand("fitmap", "Compute the S and M fitmaps of a mesh and write them as per-vertex PLY properties");
  fm->add_option("IN", fit.input, "input mesh")->required()->check(CLI::ExistingFile);
  fm->add_option("OUT", fit.output, "output .ply (fitmap_s, fitmap_m per vertex; S as colour)")->required();
  fm->add_option("--tau", fit.tau, "M-fitmap tolerance (share of inconsistent area)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  fm->add_option("--tips", fit.tips_at,
                 "also mark the tips that simplify's --keep-tips holds at N quads, or with auto where simplify "
                 "--adaptive --auto-halt is predicted to stop (per-vertex tip: 1 at each)")
      ->type_name("N|auto")
      ->check(face_count_or_auto());
  fm->add_option("--metric", fit.metric_at,
                 "also write how much longer than wide simplify --adaptive lets quads grow at N quads (or auto, as "
                 "--tips), and along which direction (per-vertex aspect, and long_x, long_y, long_z: a unit vector, "
                 "0 where square)")
      ->type_name("N|auto")
      ->check(face_count_or_auto());
  fm->add_option("--max-aspect", fit.max_aspect, "with --metric: simplify's --max-aspect")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 100.0));
  fm->add_option("--m-factor", fit.m_factor, "with auto: simplify's --m-factor, which the predicted count depends on")
      ->capture_default_str()
      ->check(number_above_zero());
  fm->add_flag("-q,--quiet", fit.quiet, "no progress bar and no notes");

  StatsArgs stats;
  auto* st = app.add_subcommand("stats", "Quality of a quad mesh and its distance to a reference surface");
  st->add_option("REF", stats.reference, "reference (input) mesh")->required()->check(CLI::ExistingFile);
  st->add_option("QUAD", stats.quads, "quad mesh to measure")->required()->check(CLI::ExistingFile);
  st->add_flag("--json", stats.json, "one JSON object on stdout");
  st->add_option("--samples", stats.samples, "distance samples per surface")
      ->capture_default_str()
      ->check(whole_number_from_one());

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kOk : kBadArguments;
  }
  // Every parallel loop of the core and Embree's builds run in TBB's arena, which this caps.
  std::optional<tbb::global_control> thread_limit;
  if (threads > 0) thread_limit.emplace(tbb::global_control::max_allowed_parallelism, threads);
  try {
    if (*c) return run_convert(convert);
    if (*s) return run_simplify(simp);
    if (*st) return run_stats(stats);
    if (*fm) return run_fitmap(fit);
  } catch (const std::exception& e) {
    std::cerr << "quadsimp: internal error: " << e.what() << "\n";
    return 3;
  }
  return kBadArguments;
}
