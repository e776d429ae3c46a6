// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "quadsimp/convert/prepare_input.h"
#include "quadsimp/fitmap/fitmap.h"
#include "quadsimp/metrics/metrics.h"
#include "quadsimp/simplify/simplify.h"

namespace qs {

//! What a user chooses, in the CLI or in a MeshLab filter (the same names and defaults:
//! both take theirs from here, and the options' defaults come from the core's).
struct SimplifyParams {
  Index target_faces = 0;        //!< uniform: required (or target_share); adaptive: optional
  //! Above 0: the target is this share of the quads the input converts to, in place of
  //! target_faces (one setting for a batch of meshes of different sizes).
  double target_share = 0;
  //! Above 0: the target is the number of quads of about this edge length (in the input's
  //! units) that cover the reference surface (the input, or its remeshing),
  //! faces_for_edge_length(), in place of target_faces (one setting for meshes of one
  //! scale, as Instant Meshes' --scale).
  double target_edge = 0;
  bool adaptive = false;
  bool auto_halt = false;        //!< adaptive: stop once the M-fitmap blocks halt_share of the surface
  double tau = FitmapOptions().tau;                //!< M-fitmap tolerance
  double m_factor = SimplifyOptions().m_factor;      //!< adaptive: the M-fitmap's bound, F_M / m_factor
  double m_slack = 1.1;          //!< adaptive: see SimplifyOptions::m_slack (1: the paper's bound)
  double halt_share = SimplifyOptions().halt_share;  //!< auto_halt: see SimplifyOptions::halt_share
  double max_aspect = 3.0;       //!< adaptive: see SimplifyOptions::max_aspect (1: square quads)
  double reach = 0.045;          //!< adaptive: see SimplifyOptions::reach (0: no check)
  bool preserve_boundary = false;
  bool keep_tips = false;        //!< see SimplifyOptions::keep_tips; refuses folds too (simplify_options())
  //! Keep the input's edges sharper than this (degrees; 0: none) as chains of the quads'
  //! edges: the conversion pairs no triangles across them (convert_options()) and the
  //! simplifier keeps them (SimplifyOptions::creases).
  double crease_angle = 0;
  bool fast = false;             //!< one optimisation pass per collapse (the paper's loop)
  bool fit_to_input = false;     //!< afterwards, fit_to_surface(): vertices leave the input
};

//! Checks a parameter combination; returns "" or the reason it is refused.
std::string check_params(const SimplifyParams& params);

//! The conversion's options for `params` (the crease angle): what prepare_input() and
//! load_input() must be given for simplify_input() to keep creases.
ConvertOptions convert_options(const SimplifyParams& params);

//! How many quads of mean edge `edge` cover a surface of `area`: area / edge^2, at least 1.
//! Homeometric quads are close to squares, so the result's mean edge comes out near `edge`:
//! 0.94 to 1.01 of sqrt(area / quads) over the six datasets at 300 to 2,000 quads (uniform
//! mode), shorter at low counts, where the quads span detail whose area they do not have.
Index faces_for_edge_length(double area, double edge);

//! The face target `params` set for an input that converts to `quads` quads, on a reference
//! surface of `area`: target_faces, target_share of `quads` (at least 1) or
//! faces_for_edge_length(area, target_edge); 0 for none (automatic halting).
Index target_faces_of(const SimplifyParams& params, Index quads, double area);

//! The core's options for `params` (no progress callback), with `fitmaps` (computed on
//! the reference surface with params.tau) in adaptive mode: what simplify_input() runs
//! with (once it has turned a target share into a count, target_faces_of()), and what
//! predicted_halting_faces() must be given to predict its halting count.
SimplifyOptions simplify_options(const SimplifyParams& params, const Fitmaps* fitmaps);

//! The fitmaps simplify_input() runs with in adaptive mode (none in uniform mode): computed
//! on `in.reference` with params.tau. Computed before `in.reference` is moved into its
//! ReferenceSurface, their working memory (about 0.3 kB a triangle) and the surface's are
//! not held at once: the CLI's adaptive run of 1.1 million triangles peaked at 630 MB with
//! the fitmaps computed inside simplify_input(), at 485 MB with them computed first
//! (bench/RESULTS.md, "Peak memory of large runs"). \throw std::invalid_argument
//! for parameters check_params() refuses; Cancelled when `progress` says stop.
Fitmaps input_fitmaps(const Input& in, const SimplifyParams& params, const ProgressFn& progress = {});

//! The whole job on prepared input: fitmaps on `ref` in adaptive mode (unless `fitmaps`
//! gives them: input_fitmaps()), then simplify() (to target_faces_of() the input's quads),
//! then fit_to_surface() if asked. `ref` is the reference surface of `in.reference` (the
//! caller keeps it for measuring the result). `in.quads` is simplified in place.
//! \throw std::invalid_argument for parameters check_params() refuses or fitmaps not of
//! `ref`'s vertices; Cancelled when `progress` says stop.
SimplifyReport simplify_input(Input& in, const ReferenceSurface& ref, const SimplifyParams& params,
                              const ProgressFn& progress = {}, const Fitmaps* fitmaps = nullptr);

//! Called after each level of simplify_levels() with its index and report, while in.quads
//! holds its result.
using LevelFn = std::function<void(std::size_t level, const SimplifyReport& report)>;

//! simplify_input() to several face targets in one run, for a chain of levels of detail:
//! each level goes on from the quads of the one before (the fitmaps and creases are found
//! once), so the run takes about as long as the coarsest level alone. `targets` must
//! decrease (0, automatic halting, only alone); the params' own target is not used. With
//! params.fit_to_input each level's quads are fitted for `level_done` only: the next level
//! goes on from them as they were, on the input. The levels are not separate runs' quads,
//! but as close to the input: over the six datasets, levels of 2,000, 1,000 and 500 quads
//! after 5,000 had an RMS distance 1.4% above separate runs' (median; -24 to +29%) in
//! uniform mode, and levels of 1,000 and 500 after 2,000 3.0% below (-12 to +0.6%) in
//! adaptive mode (bench/levels.py; bench/RESULTS.md, "Levels of detail in one run").
//! \throw std::invalid_argument for parameters check_params() refuses, targets that do
//! not decrease, or fitmaps not of `ref`'s vertices; Cancelled when `progress` says stop.
void simplify_levels(Input& in, const ReferenceSurface& ref, const SimplifyParams& params,
                     const std::vector<Index>& targets, const LevelFn& level_done, const ProgressFn& progress = {},
                     const Fitmaps* fitmaps = nullptr);

//! "" when the run reached its face target (or was cancelled, or halted automatically by
//! its rule); otherwise one sentence for the log saying where it stopped and what refused
//! the remaining collapses, or that the target is above the quads the input converts to.
//! Holes, a kept border and the valence cap can leave a mesh above any target, and a user
//! asking for 50 quads must not take 568 for a bug; nor one asking for automatic halting
//! take a noisy scan left at 18,761 of 19,911 quads for the fitmaps' verdict. A mesh of
//! several pieces that some could not shrink to their share of the target says so, and
//! how many quads they hold.
std::string target_shortfall(const SimplifyReport& report, Index target_faces);

//! "" when every quad of a result is convex, unfolded and, with a reference surface
//! measured, faces the way it does; otherwise one sentence for the log counting those that
//! are not. Uniform runs unfold what they can at the end and adaptive runs refuse folds,
//! but knife-edged parts and CAD solids of long triangles can leave some (README, Limits),
//! and a user running a batch should hear of them without asking for statistics. So
//! should one whose adaptive result has faces beyond the reach (SimplifyReport::beyond_reach_faces).
std::string defects_note(const QuadQuality& quality, Index beyond_reach = 0);

//! "" unless the result's holes crowd it: two or more border loops, a fifth or more of its
//! vertices on them, and under 70% of its vertices regular; then one sentence for the log
//! saying so and that closing a scan's holes first helps. Holes stay open, and quads
//! between holes a few quads apart cannot be regular: bunny.ply with 0.1% of its triangles
//! taken out at random halts with 28% of its vertices on 78 holes, 64% regular (its file:
//! 4% on 5 holes, 78%). A patch's outline alone is one loop, and a tube's two ends leave
//! its vertices regular: neither gets the note.
std::string holes_note(const QuadQuality& quality);

//! "" unless the run stopped short (above its target, or automatic halting out of
//! collapses) with half or more of the result's vertices on creases (SimplifyParams::
//! crease_angle); then one sentence for the log saying so, and that a larger angle keeps
//! fewer. The CAD parts measured reach their targets
//! with 9 to 45% there at 300 to 1,000 quads; pymeshlab's cow at 30 degrees stops at seven
//! times its target with 77% there and 210 non-convex quads: a crease angle meant for a
//! machined part, given to a coarse organic mesh, pins most of it.
std::string creases_note(const SimplifyReport& report, const QuadQuality& quality, Index target_faces);

//! The log's notes on a finished run, in order: target_shortfall(), defects_note(),
//! holes_note() and creases_note(), those that have something to say. The CLI and the
//! filters both log these.
std::vector<std::string> result_notes(const SimplifyReport& report, const QuadQuality& quality, Index target_faces);

//! The faces defects_note() counts, by id, each once and in order: `flawed` (as
//! quad_quality() lists them) with the report's faces beyond the reach. The filters select
//! them in their result; the CLI's JSON lists them.
std::vector<Index> noted_faces(const std::vector<Index>& flawed, const SimplifyReport& report);

//! The operations a run did, for a summary line: "N collapses, M rotations", with the
//! chord and crease collapses between them when there were any.
std::string operations_done(const SimplifyReport& report);

}  // namespace qs
