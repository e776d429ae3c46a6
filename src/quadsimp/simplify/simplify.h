// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <vector>

#include "quadsimp/mesh/quad_mesh.h"
#include "quadsimp/reference/creases.h"
#include "quadsimp/reference/reference_surface.h"
#include "quadsimp/util/progress.h"

namespace qs {

//! Per-vertex fitmaps on the reference surface (see fitmap/fitmap.h).
struct Fitmaps {
  std::vector<float> s;  //!< F_S: growth of the plane-fit error with radius
  std::vector<float> m;  //!< F_M: largest radius a face may have around a point
};

struct SimplifyOptions {
  //! Stop when the mesh has at most this many faces (0: no count limit). A mesh of several
  //! pieces (connected components) shares the target among them by area (a piece with
  //! fewer faces than its share keeps them, and the others share the rest): each piece
  //! stops at its share, so that pieces which cannot shrink to theirs (scan debris) do not
  //! take quads from the others; the run then ends above the target (SimplifyReport::pieces).
  //! Automatic halting (0 here, adaptive) shares the count it halted at too, by area in
  //! faces of the S-fitmap's sizes with no surplus handed on, and takes the pieces above
  //! their share down towards it, chords included (one quad wide scan debris kept its
  //! quads otherwise).
  Index target_faces = 0;
  //! Adaptive mode: collapse priority |d| * F_S, collapses limited by F_M; needs fitmaps.
  bool adaptive = false;
  const Fitmaps* fitmaps = nullptr;
  //! In adaptive mode, a face radius must stay at most F_M / m_factor (but see m_slack).
  double m_factor = 1.0;
  //! Adaptive mode: a collapse may grow a face smaller than the reach (its diameter under
  //! it; none when the reach is 0) up to m_slack times the M-fitmap's bound;
  //! automatic halting still measures where faces reach the bound itself (1: the paper).
  //! Ours. The bound holds the faces of thin parts small (the armadillo's halting mesh had
  //! 23% of its faces on the tenth of the surface with the smallest F_M, the uniform one
  //! 6%), and the rest of the surface paid for them. A slack of 1.1 on every face raised
  //! the armadillo's gain over uniform (twelve fixed counts 21.9% -> 26.4%) but took one of
  //! 24 draws of the moai to 99.28% projectable (at the thirty-sixth stop a bunny draw to
  //! 99.498%), so the pipeline's 1.1 (SimplifyParams) is for faces under the reach, the
  //! small faces of thin parts: fixed counts 28.1% -> 29.4% (armadillo 26.0%), the moai's
  //! 24 draws unchanged (bench/RESULTS.md, "The slack for faces under the reach").
  double m_slack = 1.0;
  //! In adaptive mode F_S is clamped to its [q, 1-q] quantiles in the priority and in the
  //! smoothing's target sizes, which bounds the size ratio between the finest and the
  //! coarsest parts (0: no clamp). Unclamped, thin parts (the bunny's ears) took most of
  //! the budget and the rest grew huge faces: RMS distance 3x the uniform one at the
  //! same count. 0.2 (20-80%): with refuse_folds, its RMS gain over uniform was 2 to 7
  //! points higher than 0.3's on the seven-count windows around both settings' halting
  //! counts on the bunny and the gargoyle (armadillo 1 to 2 lower), and 1.3 points
  //! higher over twelve fixed counts; before refuse_folds it took the moai under
  //! 70% regular vertices, with it 74.5% (80.3% since mu is recounted often enough on
  //! small meshes; bench/RESULTS.md). The clamp also keeps F_S within [1/2, 2] of its
  //! median, the bound of the sizes: on the scans the quantiles are within it and it
  //! never binds; on a CAD cube of flat sides they were thousands of times apart, and the
  //! priority left the edges' quads small while the sides grew (at 300 quads 1.5 times the
  //! uniform RMS; bounded, 0.65 times).
  double s_percentiles = 0.2;
  //! Automatic halting (adaptive mode without a face target): stop once the faces whose
  //! every diagonal collapse the other checks allow is refused by the M-fitmap (or the
  //! reach, below) cover this share of the surface more than before the first collapse
  //! (measured over all faces, at steps of the face count that shrink to 1% near it). 1
  //! runs on until no feasible collapse remains (the paper's rule). Ours: with the paper's
  //! rule the blocked parts stay put while the rest keeps coarsening, far past what the
  //! fitmap's error balance asks (bunny: 248 quads, RMS 2.2x the uniform result at that
  //! count). With 0.15 and square quads (max_aspect 1, no reach) the bunny, gargoyle and
  //! armadillo halted within 10% of the paper's counts, the moai 15-35% below; with the
  //! pipeline's stretched quads and reach the bunny halts 12-37% above (766 to 933 quads
  //! over eight draws, against 681; its base's holes hold the faces beside them), the moai from 2% below to 23% above
  //! (92 to 116, against 94; bench/RESULTS.md).
  double halt_share = 0.15;
  //! Adaptive mode: quads may be up to this many times longer along the surface's flatter
  //! direction than across its most curved one (fitmap/anisotropy.h; 1: as square as the
  //! smoothing makes them, the paper's). Ours. The springs' rest lengths and the collapse
  //! priority measure lengths in that metric, computed at twice the side a quad would have
  //! if the target (or the predicted halting count; without either, none) were spread
  //! evenly. The pipeline's 3: over the twelve fixed counts of bench/fixed_counts.py the
  //! RMS gain over uniform went from 20.8% to 25.8% (a prototype gave 24.4% at 2, 24.6% at
  //! 3, 24.7% at 4); with the metric turned a quarter (stretched across the curvature) it
  //! fell to 7.1% (bench/RESULTS.md, "Stretched quads"). The loop's M-fitmap bound then
  //! takes a face's radius under the metric over its stretch s (the paper's radius across
  //! the most curved direction, s times as far along the flatter one); automatic halting
  //! keeps the paper's radius (bench/RESULTS.md, "The M-fitmap's bound along the stretch").
  double max_aspect = 1.0;
  //! Adaptive mode: refuse a collapse when a face it grows to a radius of at least half
  //! the reach (this share of the bounding-box diagonal; 0: no check) would lose the input
  //! along its normal: from its centre and its edges' midpoints, a ray either way along
  //! the quad's normal must meet a triangle of the input facing its way within the reach.
  //! Ours. The M-fitmap bounds a face by how far the input around it stays on one side,
  //! which a smooth shape hardly limits: automatic halting left faces of the moai more than
  //! 5% of the diagonal off it (97.27% of the result projectable within 5% at the lowest of
  //! eight draws). The pipeline's 0.045, a tenth short of that 5%, because the check sees
  //! five points before smoothing moves them: at 0.05 the lowest draw was 99.03%, at 0.045
  //! 99.76% (bench/RESULTS.md, "Within reach"). Smaller faces lie within the reach of
  //! their corners, which are on the input. A border edge's midpoint is not checked, as
  //! it lies at the input's border; the rest of a face beside a hole is (bench/RESULTS.md,
  //! "Faces beside holes").
  double reach = 0;
  //! Gauss-Seidel sweeps of the spring relaxation after each collapse.
  int smoothing_sweeps = 3;
  //! Refuse collapses whose merged vertex would exceed this valence, and rotations that
  //! would raise a vertex above it (0: no limit). A refused collapse comes back when
  //! its neighbourhood changes, as with any refusal.
  int max_valence = 6;
  //! Keep the border exactly: no collapse touches a border vertex and smoothing does
  //! not move them (border vertices otherwise slide along the border).
  bool preserve_boundary = false;
  //! Remove border vertices whose border edges are short next to the mean edge (border
  //! ear collapses, ours): without it holes keep all their input edges.
  bool coarsen_border = true;
  //! At the end, move border vertices inwards on M0 where their border edges miss the
  //! input along the faces' normals (a scan's jagged outline; ours, border.cpp).
  bool inset_border = true;
  //! Hold a vertex at each tip of the input (find_tips(), at the scale of the target's or
  //! the predicted count's quads, the steepest 5% of that count at most): the smoothing
  //! leaves it where it is and a collapse merging it stays there. Ours, off by default.
  //! The smoothing otherwise slides the vertices near a tip narrower than its springs
  //! back along it: the armadillo in uniform mode at 2,000 quads keeps its claws with
  //! RMS 1.83e-3 instead of 2.40e-3 (folds refused), pyvista's airplane at automatic halting its nose
  //! with RMS 3.5e-3 instead of 19.8e-3. The quads capping a tip narrower than
  //! themselves fold unless refuse_folds is on (the pipeline turns it on with this); a
  //! coarse input with many small tips (the cow's hooves and teats at 500 quads) can come
  //! out further (bench/RESULTS.md, "Tips kept").
  bool keep_tips = false;
  //! Keep these creases of the reference surface (reference/creases.h; null or empty:
  //! none), ours: the paper keeps no feature, and its smoothing rounds sharp edges off.
  //! The mesh must be converted with the same angle (ConvertOptions::crease_angle_deg),
  //! so that every crease is a chain of its edges. Crease vertices then slide along their
  //! curve only and corners stay put; a collapse merging a crease vertex with another
  //! vertex keeps it where it is, and none merges two (but a doublet collapse, which takes
  //! two segments out of a crease where a vertex is left with one face on either side,
  //! and a chord collapse across a crease edge, which merges its ends on the curve); no
  //! rotation turns an edge between two of them, or makes one; no doublet on a crease is
  //! removed alone.
  const Creases* creases = nullptr;
  //! Rotation + smoothing passes after each collapse. The paper does one; a second
  //! one over the smoothed zone gives 3-6 points more regular vertices. It runs only
  //! outside the fine phase (below), so it costs about a fifth more time overall
  //! (bunny.obj to 5K: 0.87 s against 0.74 s with one).
  int passes = 2;
  //! While the mesh has more than this many times the target faces, each collapse gets
  //! one pass with one sweep (0: full passes throughout). Automatic halting has no
  //! target: there it is 3 times the count predicted from the fitmaps
  //! (SimplifyReport::predicted_faces), or the count at which the blocked share first
  //! passes half the halting share, if that comes first (a height field's prediction is a
  //! few faces). Ours: those vertices are smoothed again by the
  //! many collapses still to come. On Table 1 the mean share of regular vertices moved
  //! from 83.5% to 82.9% (no row below 81%) and bunny.obj to 5K took about 40% less
  //! time (bench/RESULTS.md).
  double fine_phase = 2.0;
  //! Spring-smoothing sweeps over the whole mesh before the first collapse. Ours: where
  //! the input is coarser than elsewhere, no collapse may reach a region before the
  //! target, and it kept the converter's quads (pensatore at 15K: one edge at 0.39 mu).
  int initial_sweeps = 3;
  //! Edge rotations after each collapse (the paper's step 2).
  bool rotations = true;
  //! Refuse collapses, rotations and smoothing moves that bend a quad by more than 90
  //! degrees whichever diagonal splits it, or further if it already is (quad_folds()).
  //! Ours. Such quads wrap thin parts (fingers, ear rims) too narrow for their size;
  //! convexity and orientation checks do not see them. The pipeline turns this on in
  //! adaptive mode, whose small faces gather on thin parts (automatic halting on the
  //! armadillo: 34 folded quads, 13 in the uniform mesh of the same count; with the
  //! check none on five models, and the RMS gain over uniform within 1.5 points of
  //! what it was). In uniform mode it moved two Table 1 rows out of the homeometry bounds
  //! and cut ears off coarse inputs (bench/RESULTS.md), so the pipeline turns it on there
  //! only with keep_tips.
  bool refuse_folds = false;
  //! Without refuse_folds: once the target is reached, rotate an edge of each folded
  //! quad where that leaves neither of the two new quads folded, or else move one of its
  //! corners along M0 so that it bends less, then smooth around it with folds refused.
  //! Ours. Over 41 uniform runs of the six models (600 to 13,000 quads) folded quads went
  //! from 87 to 8 (24 with rotations alone), with the same runs within [0.5, 2] mu, the
  //! same mean RMS and 0.1 points fewer regular vertices (bench/RESULTS.md).
  bool unfold = true;
  //! Once no diagonal collapse is left above the face target, take out whole chords of
  //! quads (rings around tubes, one quad's length of a strip; ops/chord_collapse.h),
  //! shortest crossed edges first, then go back to diagonal collapses. Ours: the paper's
  //! operators cannot thin a part a few quads round, and such parts stopped the run
  //! above the target (a thin tube at 426 quads for a target of 50).
  bool chord_collapses = true;
  //! For tests: after every change the loop makes, and after unfolding, validate() the
  //! mesh, check that no two quads share a diagonal, that every border vertex lies on
  //! M0's border (until the inset moves some inwards), and the loop's own bookkeeping
  //! (every border vertex is a candidate of border coarsening); throws std::logic_error
  //! naming what broke. Linear in the mesh per change: small meshes only.
  bool check_invariants = false;
  //! Called with the fraction done; returning false stops early with a valid mesh.
  ProgressFn progress;
};

struct SimplifyReport {
  Index target_faces = 0;  //!< the run's face target (SimplifyOptions::target_faces; 0: none)
  Index given_faces = 0;    //!< the quads given, before the first cleaning merged their doublets
  Index initial_faces = 0;  //!< the quads after that cleaning, where the loop starts
  Index faces = 0;
  Index collapses = 0;
  Index border_collapses = 0;  //!< border ear collapses (coarsen_border)
  Index border_insets = 0;     //!< border vertices moved inwards (inset_border)
  Index tips = 0;              //!< vertices still held at tips of the input at the end (keep_tips)
  Index chord_collapses = 0;   //!< poly-chord collapses (chord_collapses)
  Index crease_collapses = 0;  //!< doublet collapses on creases (creases)
  Index crease_vertices = 0;   //!< vertices on creases at the end, corners included (creases)
  Index rotations = 0;
  Index unfolds = 0;  //!< rotations and corner moves that unfolded a quad (or bent it less) at the end
  Index doublets = 0;
  Index singlets = 0;
  Index relaxations = 0;  //!< vertices the spring smoothing visited (moved or found at rest)
  //! Popped candidates refused: by topology (link condition, border pinch, kept border),
  //! by the valence cap, by geometry (a fold or a convex face turned non-convex), by
  //! the M-fitmap, by the reach (adaptive mode).
  Index refused_topology = 0, refused_valence = 0, refused_geometry = 0, refused_fitmap = 0, refused_reach = 0;
  //! Adaptive mode with a reach: the ids, in order, of the result's faces that fail its
  //! check (it is made where collapses grow faces; rotations and smoothing after them can
  //! take a face out of reach). The log counts them; the MeshLab filters select them with
  //! the flawed quads (quad_quality()'s).
  std::vector<Index> beyond_reach_faces;
  //! Adaptive mode: share of the surface the M-fitmap (or the reach) blocked when the run ended.
  double blocked_share = 0;
  //! Automatic halting by share: the run ended because every remaining collapse was
  //! refused, before the M-fitmap blocked halt_share of the surface more than it did at
  //! the start (a noisy input, an input already as coarse as it can go).
  bool ran_out = false;
  //! Automatic halting: the halting count predicted from the fitmaps before the run
  //! (0 otherwise, or with nothing to go by).
  double predicted_faces = 0;
  //! With several pieces (see SimplifyOptions::target_faces): the pieces, those left
  //! above their share of the target (or of automatic halting's count), and their faces.
  Index pieces = 0, pieces_above_share = 0, faces_above_share = 0;
  Index refused() const {
    return refused_topology + refused_valence + refused_geometry + refused_fitmap + refused_reach;
  }
  bool cancelled = false;
  double seconds = 0;
};

//! Simplifies `mesh` in place by the loop of [Bozzo et al. 2010, 3.2]: one diagonal
//! collapse per cycle (shortest diagonal first, or |d| * F_S in adaptive mode), then
//! profitable edge rotations and doublet/singlet cleaning around it, then spring
//! smoothing of the affected zone with every moved vertex re-projected onto `ref`.
//! The mesh is compacted at the end. Deterministic for a given input.
//! \pre mesh is valid and lies on (or near) ref.
SimplifyReport simplify(QuadMesh& mesh, const ReferenceSurface& ref, const SimplifyOptions& options = {});

//! The face count at which automatic halting is predicted to stop, from the fitmaps alone
//! (what simplify() reports as SimplifyReport::predicted_faces, and where it takes the
//! stretch of max_aspect and the tips of keep_tips): for adaptive `options` with fitmaps
//! computed on `reference`, the input's triangles; 0 otherwise, or with nothing to go by.
double predicted_halting_faces(const TriMesh& reference, const SimplifyOptions& options);

//! Mean edge length of a quad mesh (each edge once).
double mean_edge_length(const QuadMesh& mesh);

}  // namespace qs
