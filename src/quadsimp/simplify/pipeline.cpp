// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/simplify/pipeline.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "quadsimp/fitmap/fitmap.h"
#include "quadsimp/reference/reference_surface.h"
#include "quadsimp/simplify/surface_fit.h"

namespace qs {

std::string check_params(const SimplifyParams& p) {
  if (!(p.target_share >= 0 && p.target_share <= 1)) return "the target share must be in [0, 1]";
  if (!(p.target_edge >= 0 && std::isfinite(p.target_edge))) return "the target edge length must be a number from 0";
  if ((p.target_faces != 0 || p.target_share > 0) && p.target_edge > 0)
    return "give either a target number of faces or a target edge length, not both";
  const bool target = p.target_faces != 0 || p.target_share > 0 || p.target_edge > 0;
  if (!p.adaptive && p.auto_halt) return "automatic halting needs the adaptive mode";
  if (!p.adaptive && !target) return "the uniform mode needs a target number of faces";
  if (p.adaptive && p.auto_halt && target) return "give either a target number of faces or automatic halting, not both";
  if (p.adaptive && !p.auto_halt && !target)
    return "the adaptive mode needs a target number of faces or automatic halting";
  if (!(p.tau > 0 && p.tau < 1)) return "tau must be between 0 and 1";
  if (!(p.m_factor > 0)) return "the M-fitmap factor must be positive";
  if (!(p.m_slack >= 1)) return "the M-fitmap slack must be at least 1";
  if (!(p.halt_share > 0 && p.halt_share <= 1)) return "the halting share must be in (0, 1]";
  if (!(p.max_aspect >= 1)) return "the largest aspect must be at least 1";
  if (!(p.reach >= 0 && p.reach <= 1)) return "the reach must be in [0, 1]";
  if (!(p.crease_angle >= 0 && p.crease_angle < 180)) return "the crease angle must be in [0, 180)";
  return {};
}

ConvertOptions convert_options(const SimplifyParams& p) {
  ConvertOptions o;
  o.crease_angle_deg = p.crease_angle;
  return o;
}

Index faces_for_edge_length(double area, double edge) {
  const double n = area / (edge * edge);
  // Past the index range the count is no target anyone can mean; the loop then has nothing
  // to do, as with any target above the input's quads.
  if (!(n < double(std::numeric_limits<std::int32_t>::max()))) return std::numeric_limits<std::int32_t>::max();
  return std::max<Index>(1, Index(std::lround(n)));
}

Index target_faces_of(const SimplifyParams& p, Index quads, double area) {
  if (p.target_edge > 0) return faces_for_edge_length(area, p.target_edge);
  if (!(p.target_share > 0)) return p.target_faces;
  return std::max<Index>(1, Index(std::lround(p.target_share * double(quads))));
}

SimplifyOptions simplify_options(const SimplifyParams& p, const Fitmaps* fitmaps) {
  SimplifyOptions opt;
  opt.target_faces = p.target_faces;
  opt.preserve_boundary = p.preserve_boundary;
  opt.keep_tips = p.keep_tips;
  // Folds refused: adaptive mode's small faces gather on thin parts (SimplifyOptions::
  // refuse_folds), and a kept tip's cap folds where it is narrower than the quads, which
  // the unfolding after the loop cannot flatten round a held vertex: uniform mode at the
  // twelve fixed counts kept 20 folded quads with the tips held, 10 without. Refused
  // throughout, none, and the RMS 1.7% lower still (bench/RESULTS.md, "Tips kept with
  // folds refused").
  opt.refuse_folds = p.adaptive || p.keep_tips;
  opt.passes = p.fast ? 1 : 2;
  if (p.adaptive) {
    opt.adaptive = true;
    opt.fitmaps = fitmaps;
    opt.m_factor = p.m_factor;
    opt.m_slack = p.m_slack;
    opt.halt_share = p.halt_share;
    opt.max_aspect = p.max_aspect;
    opt.reach = p.reach;
  }
  return opt;
}

namespace {

Fitmaps fitmaps_on(const TriMesh& reference, const SimplifyParams& p, const ProgressFn& progress) {
  FitmapOptions fo;
  fo.tau = p.tau;
  fo.progress = progress;
  return compute_fitmaps(reference, fo);
}

}  // namespace

Fitmaps input_fitmaps(const Input& in, const SimplifyParams& p, const ProgressFn& progress) {
  if (const std::string why = check_params(p); !why.empty()) throw std::invalid_argument(why);
  return p.adaptive ? fitmaps_on(in.reference, p, progress) : Fitmaps{};
}

SimplifyReport simplify_input(Input& in, const ReferenceSurface& ref, const SimplifyParams& p,
                              const ProgressFn& progress, const Fitmaps* fitmaps) {
  if (const std::string why = check_params(p); !why.empty()) throw std::invalid_argument(why);
  SimplifyReport report;
  simplify_levels(in, ref, p, {target_faces_of(p, in.quads.n_faces(), ref.area())},
                  [&report](std::size_t, const SimplifyReport& r) { report = r; }, progress, fitmaps);
  return report;
}

void simplify_levels(Input& in, const ReferenceSurface& ref, const SimplifyParams& p,
                     const std::vector<Index>& targets, const LevelFn& level_done, const ProgressFn& progress,
                     const Fitmaps* fitmaps) {
  if (targets.empty()) throw std::invalid_argument("no target to simplify to");
  SimplifyParams first = p;  // checked with the first level's target in place of its own
  first.target_faces = targets.front(), first.target_share = 0, first.target_edge = 0;
  if (const std::string why = check_params(first); !why.empty()) throw std::invalid_argument(why);
  for (std::size_t i = 1; i < targets.size(); ++i)
    if (!(targets[i] < targets[i - 1]) || targets[i] == 0)
      throw std::invalid_argument("each level must ask for fewer quads than the one before");
  Fitmaps own;
  if (p.adaptive && !fitmaps) {
    own = fitmaps_on(ref.mesh(), p, progress);
    fitmaps = &own;
  }
  SimplifyOptions opt = simplify_options(p, fitmaps);
  const Creases creases(ref.mesh(), ref.adjacency(), p.crease_angle);
  opt.creases = &creases;
  opt.progress = progress;
  SurfaceFitOptions fit_options;
  fit_options.keep_border = p.preserve_boundary;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    opt.target_faces = targets[i];
    const SimplifyReport r = simplify(in.quads, ref, opt);
    const bool fit = p.fit_to_input && !r.cancelled;
    // The loop takes its vertices to lie on the input, so a next level goes on from the quads
    // as they were before the fit.
    const bool keep = fit && i + 1 < targets.size();
    QuadMesh on_input;
    if (keep) on_input = in.quads;
    if (fit) fit_to_surface(in.quads, ref, fit_options);
    if (level_done) level_done(i, r);
    if (r.cancelled) return;
    if (keep) in.quads = std::move(on_input);
  }
}

std::string target_shortfall(const SimplifyReport& r, Index target_faces) {
  const auto n = [](Index x) { return std::to_string(x); };
  if (target_faces > r.initial_faces) {
    const std::string above = "the target of " + n(target_faces) + " quads is above the " + n(r.initial_faces);
    if (r.given_faces > r.initial_faces)
      return above + " left of the " + n(r.given_faces) +
             " the input converts to once their doublets (two quads sharing two edges) are merged: nothing else was "
             "simplified";
    return above + " the input converts to: nothing was simplified (the result is the conversion)";
  }
  const auto refusals = [&] {
    return "every remaining collapse was refused (refusals over the run: " + n(r.refused_topology) +
           " topology, e.g. holes and kept borders; " + n(r.refused_valence) + " valence cap; " +
           n(r.refused_geometry) + " shape; " + n(r.refused_fitmap) + " M-fitmap; " + n(r.refused_reach) + " reach)";
  };
  if (target_faces == 0 && r.ran_out)
    return "automatic halting stopped at " + n(r.faces) + " quads (the input converts to " + n(r.given_faces) +
           ") before the M-fitmap blocked its share of the surface: " + refusals();
  if (target_faces == 0 || r.faces <= target_faces || r.cancelled) return {};
  const std::string above = "stopped at " + n(r.faces) + " quads, above the target of " + n(target_faces) + ": ";
  if (r.pieces_above_share == 0) return above + refusals();
  return above + "the mesh has " + n(r.pieces) + " pieces, each stopping at its share of the target by area, and " +
         n(r.pieces_above_share) + " of them could not shrink to theirs (they hold " + n(r.faces_above_share) +
         " quads; if they are scan debris, remove small isolated pieces first, MeshLab: \"Remove Isolated "
         "pieces\"): there, " + refusals();
}

std::string holes_note(const QuadQuality& q) {
  if (q.border_loops < 2 || 5 * q.border_vertices < q.vertices || q.regular_percent >= 70) return {};
  char regular[32];
  std::snprintf(regular, sizeof regular, "%.0f%%", q.regular_percent);
  return std::to_string(q.border_vertices) + " of the result's " + std::to_string(q.vertices) +
         " vertices lie on its border, round " + std::to_string(q.border_loops) + " holes or outlines, and " +
         regular + " are regular: holes stay open, and the quads between them cannot be regular. If these are "
         "holes in a scan, close them first (MeshLab: \"Close Holes\"; pymeshlab: meshing_close_holes)";
}

std::vector<std::string> result_notes(const SimplifyReport& r, const QuadQuality& q, Index target_faces) {
  std::vector<std::string> notes;
  for (std::string note : {target_shortfall(r, target_faces), defects_note(q, Index(r.beyond_reach_faces.size())),
                           holes_note(q), creases_note(r, q, target_faces)})
    if (!note.empty()) notes.push_back(std::move(note));
  return notes;
}

std::string creases_note(const SimplifyReport& r, const QuadQuality& q, Index target_faces) {
  const bool short_of_it = target_faces > 0 ? r.faces > target_faces : r.ran_out;
  if (!short_of_it || q.vertices == 0 || 2 * r.crease_vertices < q.vertices) return {};
  return std::to_string(r.crease_vertices) + " of the result's " + std::to_string(q.vertices) +
         " vertices lie on creases, where they stay, and hold it there; a larger crease angle keeps fewer (a coarse "
         "or noisy mesh has edges that sharp all over)";
}

std::string defects_note(const QuadQuality& q, Index beyond_reach) {
  std::string parts;
  const auto add = [&](Index n, const char* what) {
    if (n == 0) return;
    parts += (parts.empty() ? "" : ", ") + std::to_string(n) + " " + what;
  };
  add(q.folded_faces, "folded (bent by more than 90 degrees)");
  add(q.flipped_faces, "flipped (facing against the input)");
  add(q.nonconvex_faces, "non-convex");
  add(beyond_reach, "beyond the reach (missing the input along their normals)");
  if (parts.empty()) return {};
  std::string pieces;
  if (q.two_quad_pieces > 0)
    pieces = "; " + std::to_string(q.two_quad_pieces) +
             (q.two_quad_pieces == 1 ? " closed piece is" : " closed pieces are") +
             " two quads on the same four corners, all a tiny closed part (a scan's debris) can become: remove small "
             "isolated pieces first";
  return "of the result's " + std::to_string(q.faces) + " quads, " + parts + pieces +
         "; see Limits in quadsimp's README";
}

std::vector<Index> noted_faces(const std::vector<Index>& flawed, const SimplifyReport& r) {
  std::vector<Index> out;
  std::set_union(flawed.begin(), flawed.end(), r.beyond_reach_faces.begin(), r.beyond_reach_faces.end(),
                 std::back_inserter(out));
  return out;
}

std::string operations_done(const SimplifyReport& r) {
  const auto n = [](Index x) { return std::to_string(x); };
  return n(r.collapses) + " collapses, " + (r.chord_collapses ? n(r.chord_collapses) + " chord collapses, " : "") +
         (r.crease_collapses ? n(r.crease_collapses) + " crease collapses, " : "") + n(r.rotations) + " rotations";
}

}  // namespace qs
