// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// The simplifier's state and steps, shared by the files of this folder: the loop and the
// collapse checks (simplify.cpp), face shape checks (shape_checks.cpp), spring smoothing
// (smoothing.cpp), edge rotations (rotations.cpp), border coarsening (border.cpp),
// poly-chord collapses (chords.cpp) and unfolding (unfolding.cpp). Internal: the API is
// simplify.h.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <utility>
#include <vector>

#include "quadsimp/fitmap/anisotropy.h"
#include "quadsimp/ops/chord_collapse.h"
#include "quadsimp/ops/edge_rotation.h"
#include "quadsimp/simplify/simplify.h"

namespace qs::detail {

// The least F_S the sizing divides by: a flat part's F_S is 0. Float's smallest normal
// number, not a length-like constant, so that it holds at every unit of length (F_S is
// per length, and kept in float).
inline constexpr double kLeastS = double(std::numeric_limits<float>::min());

// held_'s marks: a tip (SimplifyOptions::keep_tips) and a crease corner (::creases).
inline constexpr char kHeldTip = 1, kHeldCorner = 2;

// One candidate collapse: diagonal k (corners k, k+2) of a face, valid while the face's
// version is the one it was keyed at (lazy invalidation). The face and k share one word
// (2 face + k), which orders entries by face, then k, as two fields would: 12 bytes
// instead of 16, for the heap that takes a tenth of a large run's time.
struct Entry {
  float key;
  std::uint32_t slot;
  std::uint32_t version;
  Index face() const { return slot >> 1; }
  Index k() const { return slot & 1; }
};
// The heap is rebuilt (its stale entries dropped, every live face keyed again) once it
// holds more than kHeapPerFace entries a face and kHeapExtra (Simplifier::upkeep()).
inline constexpr std::size_t kHeapPerFace = 16, kHeapExtra = 1024;

struct LaterFirst {  // makes std::*_heap a min-heap, ties broken by ids
  bool operator()(const Entry& a, const Entry& b) const {
    if (a.key != b.key) return a.key > b.key;
    return a.slot > b.slot;
  }
};

class Simplifier {
 public:
  Simplifier(QuadMesh& m, const ReferenceSurface& ref, const SimplifyOptions& opt)
      : m_(m), ref_(ref), opt_(opt), refuse_folds_(opt.refuse_folds) {}

  SimplifyReport run();

 private:
  // run()'s three parts (simplify.cpp).
  void set_up();
  bool collapse_all();
  void finish(bool halted);
  // Automatic halting's schedule in collapse_all(): the blocked share is measured when the
  // faces come down to next_scan (or, above the predicted range, to next_early).
  struct HaltingSchedule {
    bool on = false;
    Index next_scan = 0, next_early = 0;
    double base_share = 0;  // blocked before any collapse: not counted towards the halt
  };
  bool collapse_until(HaltingSchedule& halting, Index& next_mu);
  bool halting_due(HaltingSchedule& h);
  void upkeep(Index& next_mu);

  // The loop: the heap and its keys, the collapse checks, automatic halting, and what
  // follows each change (simplify.cpp).
  void rebuild_heap();
  void push_face(Index f);
  void append_entries(Index f);
  double s_weight(Index f);
  double sample_fitmap(const std::vector<float>& field, const Vec3& p, const Vec3& n, Index& hint) const;
  // Where a walk to f's centre starts: the triangle under it at its last key, else a corner's.
  Index centre_hint(Index f) const { return centre_foot_[f] != kNone ? centre_foot_[f] : foot_face_[m_.vertex(f, 0)]; }
  // F_S as the priority and the sizing use it: clamped to [s_lo, s_hi].
  double clamped_s(double s) const { return std::clamp(s, s_lo_, s_hi_); }
  // Spring size relative to the rest from a clamped F_S: s_mid / F_S, within [1/2, 2].
  // The quantiles alone did not bound it where F_S is rounding noise (exactly flat parts):
  // ratios of noise left the bump test with 71% regular vertices and 2.3x the RMS of a
  // single mu. clamped_s() keeps F_S within the same bound; this one holds without the
  // clamp (s_percentiles 0).
  double target_size(double s) const { return std::clamp(s_mid_ / std::max(s, kLeastS), 0.5, 2.0); }
  enum class Verdict { Topology, Valence, Geometry, Fitmap, Reach, Ok };
  // Whose M-fitmap bound a check applies: the loop's, with SimplifyOptions::m_slack and,
  // with anisotropy, the radius along the stretch (bound_radius()), or the paper's bound
  // itself, where automatic halting measures the blocked share.
  enum class Bound { Loop, Halting };
  // The first check a diagonal collapse fails, in order, or Ok; pos and foot are set
  // once it passes the topology and valence checks. The loop and blocked_share() both
  // ask here, so that the halting measure sees the collapses the loop would do, but held
  // at the M-fitmap's bound itself.
  Verdict check_collapse(Index f, Index k, Vec3& pos, SurfacePoint& foot, Bound bound) const;
  bool touches_kept_border(Index f, Index k) const {
    return opt_.preserve_boundary && (m_.is_border_vertex(m_.vertex(f, k)) || m_.is_border_vertex(m_.vertex(f, k + 2)));
  }
  bool exceeds_valence(Index f, Index k) const {
    return opt_.max_valence > 0 &&
           m_.valence(m_.vertex(f, k)) + m_.valence(m_.vertex(f, k + 2)) - 2 > opt_.max_valence;
  }
  // A merge of u and w (a collapse's diagonal ends, a chord's pair) keeps a tip's vertex
  // where it is: `tip` is that vertex, or kNone. False when the other is pinned to a
  // place of its own too (a tip, or M0's border): the merge is refused.
  // Held tips and crease corners, and crease vertices, keep their places the same way
  // (SimplifyOptions::creases).
  bool merge_keeps_tip(Index u, Index w, Index& tip) const {
    tip = pinned(u) ? u : pinned(w) ? w : kNone;
    const Index other = tip == u ? w : u;
    return tip == kNone || !(pinned(other) || m_.is_border_vertex(other));
  }
  bool pinned(Index v) const { return held_[v] || (!crease_.empty() && crease_[v] != kNone); }
  bool place(Index f, Index k, Vec3& pos, SurfacePoint& foot) const;
  // Adaptive mode's checks on the faces a collapse grows: the M-fitmap, then the reach.
  Verdict check_grown_faces(Index f, Index k, const Vec3& pos, Bound bound) const;
  Verdict check_grown_face(Index g, const Vec3* q, Bound bound) const;
  // A quad's centre (corner mean), normal and radius (largest centre-to-corner distance).
  struct QuadShape {
    Vec3 centre, normal;
    double radius;
  };
  static QuadShape shape_of(const Vec3* q);
  double bound_radius(Index g, const Vec3* q, const QuadShape& s, Bound bound) const;
  bool beyond_reach(Index g, const Vec3* q, const QuadShape& s) const;
  // Smaller than the reach (none without one): within the reach of its corners, which lie
  // on M0, so beyond_reach() need not cast rays; the M-fitmap's slack applies there only.
  bool under_reach(const QuadShape& s) const { return 2 * s.radius < reach_; }
  std::vector<Index> faces_beyond_reach() const;
  void count_refusal(Verdict v);  // the report's count for a verdict other than Ok
  void cycle(Index f, Index k, const Vec3& pos, const SurfacePoint& foot);
  void hold_tips();
  void after_change(std::initializer_list<Index> touched) { after_change(touched.begin(), touched.end()); }
  void after_change(const Index* first, const Index* last);
  // SimplifyOptions::check_invariants; border vertices on M0's border too unless told not.
  void check_invariants(bool border_on_m0 = true);
  void check_shared_diagonals();
  void check_border_on_m0() const;
  void add_faces_around(Index v, std::vector<Index>& faces);
  void requeue_region();
  double blocked_share();
  void record_foot(Index v, const SurfacePoint& s) {
    foot_normal_[v] = ref_.normal_at(s);
    foot_face_[v] = s.face;
    if (!opt_.adaptive) return;
    s_foot_[v] = clamped_s(ref_.interpolate(opt_.fitmaps->s, s));
    size_[v] = target_size(s_foot_[v]);
    if (anisotropy_.empty()) return;
    const auto g = ref_.interpolate(anisotropy_.g, s);
    for (int k = 0; k < 6; ++k) metric_[v][k] = float(g[k]);
  }
  using Metric = std::array<double, 6>;  // symmetric: xx, xy, xz, yy, yz, zz
  // The mean of the metrics under the given vertices (with anisotropy).
  Metric mean_metric(std::initializer_list<Index> vertices) const {
    Metric g{};
    for (Index v : vertices)
      for (int k = 0; k < 6; ++k) g[k] += metric_[v][k];
    const double w = 1.0 / double(vertices.size());  // exact for two and four vertices
    for (double& x : g) x *= w;
    return g;
  }
  // d^T G d: d's squared length under G.
  static double length2_under(const Metric& g, const Vec3& d) {
    return g[0] * d.x() * d.x() + g[3] * d.y() * d.y() + g[5] * d.z() * d.z() +
           2 * (g[1] * d.x() * d.y() + g[2] * d.x() * d.z() + g[4] * d.y() * d.z());
  }
  // d's squared length under the mean of u's and v's metrics, which springs are measured by.
  double metric_length2(Index u, Index v, const Vec3& d) const { return length2_under(mean_metric({u, v}), d); }
  void update_mu();
  // The mean edge of v's connected component: what its springs and the thresholds
  // scaled by the edge length use. With one mu for all, a part too small to hold quads
  // of the mesh's size (a sphere a tenth the size of another, beside it) had springs
  // longer than itself: its quads crumpled (edges from 0.02 to 8 mu), every collapse
  // there was refused at 75 quads, and the target was reached by taking the large
  // sphere down to 8. No operator joins or splits components, so the labels hold.
  double mu_at(Index v) const { return component_mu_[component_[v]]; }
  // Spring rest length between u and v, for an edge (diagonals: times sqrt(2)).
  double rest_length(Index u, Index v) const {
    const double mu = mu_at(u);
    return opt_.adaptive ? mu * 0.5 * (size_[u] + size_[v]) / size_mean_ : mu;
  }

  // Whether faces may take new corner positions (shape_checks.cpp).
  bool shape_ok(Index f, const Vec3* q, const Vec3& extra_normal) const;
  bool follows_reference(const Vec3& n, const std::array<Index, 4>& corners, const Vec3* q,
                         const Vec3& extra_normal) const;
  // Whether two corners or more have their feet on or next to a folded-over patch of M0.
  // With one (the faces around a fold) the other three still say where M0 faces. "Any
  // corner" changed the armadillo's runs (17 single-triangle flaps): at 1,806 quads its
  // longest diagonal went from 2.43 to 3.03 mu, 1.3 mu from a flap; "two" changes none
  // of 66 dataset runs and still clears the 1.1M bunny's fold.
  bool over_flap(const std::array<Index, 4>& c) const {
    int n = 0;
    for (Index v : c) n += foot_face_[v] != kNone && ref_.is_flap(foot_face_[v]);
    return n >= 2;
  }
  bool moved_faces_ok(Index v, const Vec3& p) const;

  // Spring smoothing (smoothing.cpp).
  void smooth_region(int sweeps);
  void prefetch_feet() const;
  void smooth_vertex(Index v);

  // Edge rotations (rotations.cpp).
  void rotate_in_region();
  bool try_rotate(Index h);
  int target_valence(Index v) const {
    if (m_.is_border_vertex(v)) return target_valence_of_border(v);
    return (held_[v] & kHeldCorner) ? target_valence_of_corner(v) : 4;
  }
  bool rotation_passes_cap(Index h, Rotation r) const;
  bool rotation_follows_reference(Index h, Rotation r, Index except = kNone) const;

  // Border vertices and border coarsening (border.cpp).
  int target_valence_of_border(Index v) const;
  std::pair<Vec3, Vec3> border_directions(Index v) const;
  double border_turn(Index v) const;
  bool is_border_corner(Index v) const;
  void coarsen_border();
  bool remove_border_vertex(Index b);
  void inset_border();
  int border_misses(Index v, const Vec3& p) const;
  bool keeps_lengths(Index v, const Vec3& p) const;
  // The border ear f with b at corner k merges its neighbours a and c into one vertex of
  // val(a) + val(c) - 3 edges (border_ear.h).
  bool ear_exceeds_valence(Index f, Index k) const {
    return opt_.max_valence > 0 &&
           m_.valence(m_.vertex(f, k + 3)) + m_.valence(m_.vertex(f, k + 1)) - 3 > opt_.max_valence;
  }
  bool border_merge_corner(Index a, Index c, Index& corner) const;
  SurfacePoint border_point_between(Index a, Index b, const Vec3& p) const;

  // Poly-chord collapses (chords.cpp).
  bool collapse_chords();
  bool try_collapse_chord(const Chord& chord);

  // Creases (creases.cpp; SimplifyOptions::creases).
  void mark_creases();
  void note_crease(Index v) {
    if (!crease_.empty() && crease_[v] != kNone) crease_verts_.push_back(v);
  }
  // `survivor` takes the crease state (curve, place, corner) of `from`.
  void inherit(Index survivor, Index from);
  bool joins_pinned(Index keep, Index gone) const;
  bool creates_pinned_edge(Index h, Rotation r) const;
  // Whether the edge u-w may run along a crease: both ends on one curve, or at a corner and
  // on a curve or corner. Two ends on different curves are joined across a part's corner.
  bool may_be_crease_edge(Index u, Index w) const {
    if (!pinned(u) || !pinned(w)) return false;
    return (crease_[u] != kNone && crease_[u] == crease_[w]) || (held_[u] & kHeldCorner) || (held_[w] & kHeldCorner);
  }
  int target_valence_of_corner(Index v) const;
  void slide_on_crease(Index v, const Vec3& target);
  // How far crease vertex v may slide along its curve before it meets a neighbour on it.
  void crease_arc(Index v, double& back, double& ahead) const;
  bool coarsen_creases();
  bool remove_crease_vertex(Index b);
  bool remove_crease_doublet(Index b);
  bool absorb_far_corners(Index b);
  bool place_between_on_crease(Index l, Index r, const Vec3& mid, SurfacePoint& foot, double& s) const;
  void check_creases() const;

  // Unfolding (unfolding.cpp).
  void unfold();
  bool unfold_face(Index f);
  bool relocate_corner(Index f);

  QuadMesh& m_;
  const ReferenceSurface& ref_;
  const SimplifyOptions& opt_;
  SimplifyReport rep_;
  double mu_ = 0;  // the mean edge of the whole mesh: search radii
  std::vector<Index> component_;     // per vertex
  std::vector<double> component_mu_;  // per component
  // Per component, its faces, counted by after_change(), and with a target and several
  // components its share of the target (share_target(); empty otherwise).
  std::vector<Index> piece_faces_;
  std::vector<double> share_;
  Index counted_faces_ = 0;  // m_.n_faces() at the last count: what an operation removed
  // The faces the piece of v may still lose before it is down to its share, or with one
  // share (a single piece) before the mesh is down to the target; unbounded without a
  // target. The loop, border coarsening and chords each stop a piece there: one pass of
  // border coarsening can take many ears (asked for 900 of a decimated bunny's 999 quads,
  // the run stopped at 882 when a single piece had no bound here).
  double piece_room(Index v) const {
    if (!share_.empty()) return double(piece_faces_[component_[v]]) - share_[component_[v]];
    return opt_.target_faces > 0 ? double(m_.n_faces()) - double(opt_.target_faces)
                                 : std::numeric_limits<double>::infinity();
  }
  std::vector<double> count_pieces(bool by_size, double& total);
  void share_target(const std::vector<double>& piece_area);
  bool share_halting_count();
  std::vector<std::uint32_t> version_, face_mark_, vertex_mark_;
  // Reference normal under each vertex (at its last projection): faces are checked
  // against these, so that no sequence of small turns can flip a face.
  std::vector<Vec3> foot_normal_;
  // SimplifyOptions::keep_tips: the vertices held where they are, at tips of M0. A
  // collapse's survivor inherits the mark (both ends held: refused).
  std::vector<char> held_;
  // With creases: each vertex's curve (kNone off creases and at corners) and parameter on
  // it, the vertices to look at for crease doublets (coarsen_creases(); some may have left
  // the creases), and which vertices are on a curve (clean_from() keeps their doublets).
  std::vector<Index> crease_;
  std::vector<double> crease_s_;
  std::vector<Index> crease_verts_, crease_scan_;
  std::vector<char> on_crease_;
  std::vector<Index> foot_face_;  // the triangle under each vertex: where project_near() starts
  std::vector<Index> centre_foot_;  // adaptive: the triangle under each face's centre at its last key
  // Adaptive mode: the F_S range the priority is clamped to, and the target size of each
  // vertex relative to the rest (s_mid / F_S under it, clamped alike) and its mean.
  double s_lo_ = 0, s_hi_ = std::numeric_limits<double>::infinity(), s_mid_ = 1;
  double reach_ = 0;  // SimplifyOptions::reach times M0's bounding-box diagonal
  std::vector<double> s_foot_;  // clamped F_S under each vertex
  // target_size(s_foot_[v]), written only by record_foot(): rest_length() reads it for
  // every spring, and computing it there instead (two divisions a spring) measured 2-3%
  // slower on the adaptive armadillo and bunny (five of seven alternated runs).
  std::vector<double> size_;
  double size_mean_ = 1;
  // Adaptive mode with max_aspect > 1: the metric on M0, and under each vertex (record_foot()).
  Anisotropy anisotropy_;
  std::vector<std::array<float, 6>> metric_;
  std::vector<double> blocked_area_;  // blocked_share()'s per face, kept for its next measure
  double fine_above_ = std::numeric_limits<double>::infinity();  // the fine phase runs above this face count
  std::uint32_t stamp_ = 0;
  std::vector<Entry> heap_;
  std::vector<Index> region_faces_, region_verts_, work_, cand_, border_verts_, requeued_;
  // Every live border vertex is among these (in no order, once each: border_noted_): those
  // on the border at the start or at the last coarsen_border(), and those of the zone an
  // operation smoothed since, which holds every vertex it touched (note_border()). A scan
  // of every vertex every 64 collapses found the same ones and took half the time of
  // bunny.ply split to 1.1M triangles.
  std::vector<Index> border_candidates_;
  std::vector<char> border_noted_;
  // check_invariants: the shared diagonals (shared_diagonals()) at the last check. The
  // input may have some (the pairing of low-poly meshes; the crease conversion's flat
  // quads); the operators must add none (check_shared_diagonals()).
  std::vector<std::pair<Index, Index>> shared_;
  void note_border(Index v) {
    if (!border_noted_[v] && m_.is_vertex_live(v) && m_.is_border_vertex(v))
      border_noted_[v] = 1, border_candidates_.push_back(v);
  }
  Chord chord_;
  std::vector<Index> beside_;
  std::vector<Vec3> chord_pos_;
  std::vector<SurfacePoint> chord_feet_;
  std::vector<double> chord_crease_s_;  // with creases: a crease edge's merged place on its curve, else -1
  std::vector<std::size_t> edge_count_;  // per component, for update_mu()
  bool has_border_ = false;  // no operator makes a border where there was none
  double area_ = 0;  // of the mesh at the start
  bool refuse_folds_;  // opt_.refuse_folds, and on during unfold() and inset_border(): what every fold check reads
};

}  // namespace qs::detail
