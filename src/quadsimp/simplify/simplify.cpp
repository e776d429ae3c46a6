// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/simplify/simplify.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <utility>

#include "quadsimp/mesh/quad_geometry.h"
#include "quadsimp/ops/border_ear.h"
#include "quadsimp/ops/chord_collapse.h"
#include "quadsimp/ops/cleaning.h"
#include "quadsimp/ops/diagonal_collapse.h"
#include "quadsimp/ops/edge_rotation.h"
#include "quadsimp/ops/local_rewrite.h"
#include "quadsimp/util/errors.h"

namespace qs {
namespace {

constexpr double kSqrt2 = 1.4142135623730951;
// A border vertex is removed when its two border edges add up to less than this many
// mu. Measured on bunny.ply at 3K/5K/11K quads: 1.0 left homeometry minima of
// 0.46/0.30/0.44, 1.3 gives 0.53/0.52/0.44 with the same RMS, 1.6 starts to stretch
// border faces (maximum 3.09 at 5K).
constexpr double kBorderShort = 1.3;

// One candidate collapse: diagonal k (corners k, k+2) of `face`, valid while the
// face's version is unchanged (lazy invalidation).
struct Entry {
  float key;
  Index face;
  std::uint32_t version;
  std::uint32_t k;
};
struct LaterFirst {  // makes std::*_heap a min-heap, ties broken by ids
  bool operator()(const Entry& a, const Entry& b) const {
    if (a.key != b.key) return a.key > b.key;
    if (a.face != b.face) return a.face > b.face;
    return a.k > b.k;
  }
};

class Simplifier {
 public:
  Simplifier(QuadMesh& m, const ReferenceSurface& ref, const SimplifyOptions& opt)
      : m_(m), ref_(ref), opt_(opt), refuse_folds_(opt.refuse_folds) {}

  SimplifyReport run();

 private:
  void append_entries(Index f);
  void push_face(Index f);
  bool place(Index f, Index k, Vec3& pos, SurfacePoint& foot) const;
  bool touches_kept_border(Index f, Index k) const {
    return opt_.preserve_boundary && (m_.is_border_vertex(m_.vertex(f, k)) || m_.is_border_vertex(m_.vertex(f, k + 2)));
  }
  bool exceeds_valence(Index f, Index k) const {
    return opt_.max_valence > 0 &&
           m_.valence(m_.vertex(f, k)) + m_.valence(m_.vertex(f, k + 2)) - 2 > opt_.max_valence;
  }
  // The border ear f with b at corner k merges its neighbours a and c into one vertex of
  // val(a) + val(c) - 3 edges (border_ear.h).
  bool ear_exceeds_valence(Index f, Index k) const {
    return opt_.max_valence > 0 &&
           m_.valence(m_.vertex(f, k + 3)) + m_.valence(m_.vertex(f, k + 1)) - 3 > opt_.max_valence;
  }
  bool m_fitmap_allows(Index f, Index k, const Vec3& pos) const;
  bool within_m_fitmap(Index g, const Vec3* q) const;
  // The first check a diagonal collapse fails, in order, or Ok; pos and foot are set
  // once it passes the topology and valence checks. The loop and blocked_share() both
  // ask here, so that the halting measure sees exactly the collapses the loop would do.
  enum class Verdict { Topology, Valence, Geometry, Fitmap, Ok };
  Verdict check_collapse(Index f, Index k, Vec3& pos, SurfacePoint& foot) const;
  void cycle(Index f, Index k, const Vec3& pos, const SurfacePoint& foot);
  void coarsen_border();
  bool remove_border_vertex(Index b);
  bool border_merge_point(Index a, Index c, const Vec3& otherwise, Vec3& p) const;
  void after_change(std::initializer_list<Index> touched) { after_change(touched.begin(), touched.end()); }
  void after_change(const Index* first, const Index* last);
  bool collapse_chords();
  bool try_collapse_chord(const Chord& chord);
  void add_faces_around(Index v, std::vector<Index>& faces);
  void rotate_in_region();
  bool try_rotate(Index h);
  void unfold();
  bool unfold_face(Index f);
  bool relocate_corner(Index f);
  bool rotation_follows_reference(Index h, Rotation r, Index except = kNone) const;
  bool rotation_passes_cap(Index h, Rotation r) const;
  void smooth_region(int sweeps);
  void smooth_vertex(Index v);
  bool moved_faces_ok(Index v, const Vec3& p) const;
  bool shape_ok(Index f, const Vec3* q, const Vec3& extra_normal, bool bend_check = true) const;
  bool follows_reference(const Vec3& n, const std::array<Index, 4>& corners, const Vec3* q,
                         const Vec3& extra_normal) const;
  int target_valence_of_border(Index v) const;
  std::pair<Vec3, Vec3> border_directions(Index v) const;
  double border_turn(Index v) const;
  bool is_border_corner(Index v) const;
  int target_valence(Index v) const { return m_.is_border_vertex(v) ? target_valence_of_border(v) : 4; }
  void requeue_region();
  void rebuild_heap();
  double sample_fitmap(const std::vector<float>& field, const Vec3& p, const Vec3& n, Index& hint) const;
  double s_weight(Index f);
  // Where a walk to f's centre starts: the triangle under it at its last key, else a corner's.
  Index centre_hint(Index f) const { return centre_foot_[f] != kNone ? centre_foot_[f] : foot_face_[m_.vertex(f, 0)]; }
  // F_S as the priority and the sizing use it: clamped to [s_lo, s_hi].
  double clamped_s(double s) const { return std::clamp(s, s_lo_, s_hi_); }
  // Spring size relative to the rest from a clamped F_S: s_mid / F_S, within [1/2, 2].
  // The quantile clamp alone does not bound it where F_S is rounding noise (exactly flat
  // parts): ratios of noise left the bump test with 71% regular vertices and 2.3x the RMS
  // of a single mu.
  // On the scans the quantiles are within 1.5x of each other and this never binds.
  double target_size(double s) const { return std::clamp(s_mid_ / std::max(s, 1e-30), 0.5, 2.0); }
  double blocked_share() const;
  double predicted_halt() const;
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
  void record_foot(Index v, const SurfacePoint& s) {
    foot_normal_[v] = ref_.normal_at(s);
    foot_face_[v] = s.face;
    if (!opt_.adaptive) return;
    s_foot_[v] = clamped_s(ref_.interpolate(opt_.fitmaps->s, s));
    size_[v] = target_size(s_foot_[v]);
  }
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

  QuadMesh& m_;
  const ReferenceSurface& ref_;
  const SimplifyOptions& opt_;
  SimplifyReport rep_;
  double mu_ = 0;  // the mean edge of the whole mesh: search radii
  std::vector<Index> component_;     // per vertex
  std::vector<double> component_mu_;  // per component
  std::vector<std::uint32_t> version_, face_mark_, vertex_mark_;
  // Reference normal under each vertex (at its last projection): faces are checked
  // against these, so that no sequence of small turns can flip a face.
  std::vector<Vec3> foot_normal_;
  std::vector<Index> foot_face_;  // the triangle under each vertex: where project_near() starts
  std::vector<Index> centre_foot_;  // adaptive: the triangle under each face's centre at its last key
  // Adaptive mode: the F_S range the priority is clamped to, and the target size of each
  // vertex relative to the rest (s_mid / F_S under it, clamped alike) and its mean.
  double s_lo_ = 0, s_hi_ = std::numeric_limits<double>::infinity(), s_mid_ = 1;
  std::vector<double> s_foot_;  // clamped F_S under each vertex
  // target_size(s_foot_[v]), written only by record_foot(): rest_length() reads it for
  // every spring, and computing it there instead (two divisions a spring) measured 2-3%
  // slower on the adaptive armadillo and bunny (five of seven alternated runs).
  std::vector<double> size_;
  double size_mean_ = 1;
  double fine_above_ = std::numeric_limits<double>::infinity();  // the fine phase runs above this face count
  std::uint32_t stamp_ = 0;
  std::vector<Entry> heap_;
  std::vector<Index> region_faces_, region_verts_, work_, cand_, border_verts_;
  Chord chord_;
  std::vector<Index> beside_;
  std::vector<Vec3> chord_pos_;
  std::vector<SurfacePoint> chord_feet_;
  std::vector<std::size_t> edge_count_;  // per component, for update_mu()
  bool has_border_ = false;  // no operator makes a border where there was none
  double area_ = 0;  // of the mesh at the start
  bool refuse_folds_;  // opt_.refuse_folds, and on during unfold(): what every fold check reads
};

// Where a spring of length `rest` from q would put p: on the sphere of that radius
// around q, in p's direction (p itself when they coincide).
Vec3 spring_point(const Vec3& p, const Vec3& q, double rest) {
  const Vec3 d = p - q;
  const double l = d.norm();
  return l > 1e-30 ? Vec3(q + rest * d / l) : p;
}

// Calls fn(f, length) once for each edge of the mesh, f one of its faces, in face order.
template <class Fn>
void for_each_edge_length(const QuadMesh& m, Fn&& fn) {
  for (Index f = 0; f < m.face_capacity(); ++f) {
    if (!m.is_face_live(f)) continue;
    for (Index k = 0; k < 4; ++k) {
      const Index h = QuadMesh::halfedge(f, k), t = m.twin(h);
      if (t != kNone && t < h) continue;  // each edge once
      fn(f, (m.position(m.vertex(f, k)) - m.position(m.vertex(f, k + 1))).norm());
    }
  }
}

double norm_of_diagonal(const QuadMesh& m, Index f, Index k) {
  return (m.position(m.vertex(f, k)) - m.position(m.vertex(f, k + 2))).norm();
}

// [ours] F_S over the face rather than at its centre: the mean of the (clamped) values
// under the centre and under the four corners. The error a face makes comes from all of
// it, and F_S varies at the scale of M0's detail, so one point gives neighbouring faces
// jittery keys. Twelve fixed-count runs (bench/fixed_counts.py): RMS 19.9% below
// uniform instead of 17.0%, 79.9% regular vertices instead of 77.8% (bench/RESULTS.md).
double Simplifier::s_weight(Index f) {
  Index& hint = centre_foot_[f];
  hint = centre_hint(f);
  double sum = clamped_s(sample_fitmap(opt_.fitmaps->s, m_.face_centroid(f), m_.face_area_normal(f), hint));
  for (Index v : m_.face_vertices(f)) sum += s_foot_[v];
  return sum / 5;
}

// A fitmap at p projected along n, found by a walk on M0 from `hint`, which becomes the
// triangle found. The hint is where the face's centre was at its last key: faces move
// little between keys, so the walk crosses few triangles, where the BVH casts two rays.
// Adaptive bunny.ply with automatic halting: 12-17% less time. The keys differ from the
// BVH's by rounding (the walk is in double precision), and where a fold puts another
// sheet nearer along the ray, the walk keeps the face's own (bench/RESULTS.md).
double Simplifier::sample_fitmap(const std::vector<float>& field, const Vec3& p, const Vec3& n, Index& hint) const {
  const SurfacePoint s = ref_.project_near(hint, p, n, 4 * mu_);
  if (!s.found()) return 0.0;
  hint = s.face;
  return ref_.interpolate(field, s);
}

// [paper 3.3] Priority |d| * F_S(phi(c)), c the face centre and phi the projection
// onto M0 along the face normal, with F_S averaged over the face (s_weight()); uniform
// mode: |d|. Appends both diagonals of f with the face's current version.
void Simplifier::append_entries(Index f) {
  const double scale = opt_.adaptive ? s_weight(f) : 1.0;
  for (Index k = 0; k < 2; ++k) heap_.push_back({float(norm_of_diagonal(m_, f, k) * scale), f, version_[f], k});
}

void Simplifier::push_face(Index f) {
  ++version_[f];
  append_entries(f);
  std::push_heap(heap_.begin(), heap_.end() - 1, LaterFirst{});
  std::push_heap(heap_.begin(), heap_.end(), LaterFirst{});
}

void Simplifier::rebuild_heap() {
  heap_.clear();
  for (Index f = 0; f < m_.face_capacity(); ++f)
    if (m_.is_face_live(f)) {
      ++version_[f];
      append_entries(f);
    }
  std::make_heap(heap_.begin(), heap_.end(), LaterFirst{});
}

// A quad with normal n (diagonal cross product), corners `corners` at positions q, faces
// like the surface under it: like its corners' foot normals (plus the merged vertex's
// for a collapse) within acos(0.2).
bool Simplifier::follows_reference(const Vec3& n, const std::array<Index, 4>& corners, const Vec3* q,
                                   const Vec3& extra_normal) const {
  Vec3 r = extra_normal;
  double lowest = std::numeric_limits<double>::infinity();
  for (Index v : corners) {
    r += foot_normal_[v];
    lowest = std::min(lowest, foot_normal_[v].dot(n));
  }
  const double cos_r = n.dot(r);
  if (cos_r < 0 || cos_r * cos_r < 0.04 * n.squaredNorm() * r.squaredNorm()) return false;
  // A corner where the quad stands steep on M0 (or faces away) may mean it spans a
  // sharp fold (a wing's edge): the sum of the corner normals can still agree while the
  // surface under the quad's middle faces the other way. Rare, so the closest-point
  // query is affordable here. Steep is 45 degrees: at 78 (acos 0.2) and at 60, quads
  // still ended flipped over folds whose corners all stood at 46-75 degrees (pensatore
  // at 1K, gargoyle at 2K with --fast). The check only refuses: the Table 1 outputs
  // did not change.
  if (lowest < 0 || lowest * lowest < 0.5 * n.squaredNorm()) {
    const SurfacePoint mid = ref_.closest_to_quad_centre(q);
    if (mid.found() && ref_.normal_at(mid).dot(n) < 0) return false;
  }
  return true;
}

// A face with new corner positions q stays oriented like the reference surface under
// it and like itself before, a convex face stays convex, and with refuse_folds (and
// bend_check) no face bends further past 90 degrees. Over a folded-over patch of M0
// (ReferenceSurface::is_flap, over_flap()) a face that did not follow the reference
// need not start to: the working mesh follows the fold at first, and while it had to,
// no move there passed (glmark2's bunny split to 1.1M triangles, at 20,000 quads: 2
// flipped quads and a diagonal of 0.04 mu left at the fold).
bool Simplifier::shape_ok(Index f, const Vec3* q, const Vec3& extra_normal, bool bend_check) const {
  // The hottest check of the run (every smoothing move): one normal, no square roots.
  const Vec3 n = quad_normal(q[0], q[1], q[2], q[3]);
  if (!keeps_orientation(n, m_.face_area_normal(f))) return false;
  const auto c = m_.face_vertices(f);
  const Vec3 p[4] = {m_.position(c[0]), m_.position(c[1]), m_.position(c[2]), m_.position(c[3])};
  if (!follows_reference(n, c, q, extra_normal) &&
      !(over_flap(c) && !follows_reference(quad_normal(p[0], p[1], p[2], p[3]), c, p, Vec3::Zero())))
    return false;
  if (!quad_is_convex(q[0], q[1], q[2], q[3], n) && quad_is_convex(p[0], p[1], p[2], p[3])) return false;
  return !(refuse_folds_ && bend_check &&
           quad_folds_further(q[0], q[1], q[2], q[3], [&] { return quad_fold_cos(p[0], p[1], p[2], p[3]); }));
}

// Border vertices aim at valence 3, sharp border corners (turning by more than 60
// degrees) at 2 where the border turns towards the mesh (an inner angle under 120
// degrees: one face) and at 4 where it turns away from it (over 240: three faces).
// With 2 at both kinds, the two faces of a concave corner of bunny.ply's holes shared
// its 270 degrees, one of them at 160 degrees with an edge of 0.38 mu.
int Simplifier::target_valence_of_border(Index v) const {
  const auto [in, out] = border_directions(v);
  if (in.dot(out) >= 0.5) return 3;
  // Faces lie to the left of their half-edges: a left turn (about the surface's normal)
  // from the incoming border edge to the outgoing one is a convex corner.
  return in.cross(out).dot(foot_normal_[v]) > 0 ? 2 : 4;
}

// Unit directions of the border edges arriving at and leaving border vertex v.
std::pair<Vec3, Vec3> Simplifier::border_directions(Index v) const {
  const Vec3& p = m_.position(v);
  return {(p - m_.position(m_.from(m_.border_in(v)))).normalized(), (m_.position(m_.to(m_.out(v))) - p).normalized()};
}

// The angle between the two border edges at border vertex v.
double Simplifier::border_turn(Index v) const {
  const auto [in, out] = border_directions(v);
  return std::acos(std::clamp(in.dot(out), -1.0, 1.0));
}

// A border vertex stays where the border turns by more than 45 degrees while it runs
// on straighter (turning less than half as much) at both neighbours: the corners of a
// square or an L. Ours. Pinning every turn over 45 degrees and every vertex of valence
// 2, as before, pinned most vertices of bunny.ply's small, jagged holes (a loop of
// eight turns by 45 degrees at each), and the free ones between them bunched up at
// the pinned ones: over 16 face counts from 2K to 13K, 13 runs ended with an edge under
// 0.5 mu, 4 with this rule. Pinning nothing loses the square's corners.
bool Simplifier::is_border_corner(Index v) const {
  const double t = border_turn(v);
  if (t <= M_PI / 4) return false;
  const Index next = m_.to(m_.out(v)), prev = m_.from(m_.border_in(v));
  const double t_next = border_turn(next), t_prev = border_turn(prev);
  if (std::max(t_next, t_prev) < 0.5 * t) return true;
  // The end of a strip one quad wide: v and a neighbour w, both of valence 2 (the free
  // corners of a quad with three border edges), both turn by more than 45 degrees, and
  // the border runs on straighter beyond the pair. Unpinned, the springs and the chord
  // collapses there slid a strip's ends inwards (by half a quad per chord).
  const auto strip_end = [&](Index w, double t_w, double t_before_v, Index after_w) {
    return m_.valence(v) == 2 && m_.valence(w) == 2 && t_w > M_PI / 4 &&
           std::max(t_before_v, border_turn(after_w)) < 0.5 * std::min(t, t_w);
  };
  return strip_end(next, t_next, t_prev, m_.to(m_.out(next))) ||
         strip_end(prev, t_prev, t_next, m_.from(m_.border_in(prev)));
}

// Where the merged vertex goes: the midpoint re-projected onto M0 along the normal
// of the current mesh there (the faces around both ends), or the border end.
bool Simplifier::place(Index f, Index k, Vec3& pos, SurfacePoint& foot) const {
  const Index a = m_.vertex(f, k), c = m_.vertex(f, k + 2);
  auto shape_after = [&](const Vec3& p, const Vec3& p_normal) {
    return for_each_face_after_collapse(m_, f, k, p, [&](Index g, const Vec3* q) { return shape_ok(g, q, p_normal); });
  };
  if (m_.is_border_vertex(a) || m_.is_border_vertex(c)) {
    foot = ref_.closest_within(collapse_position(m_, f, k), 0.0);  // the border end is on M0 already
    pos = foot.point;
    return foot.found() && shape_after(pos, ref_.normal_at(foot));
  }
  // The paper's place: the midpoint projected along the normal. Where that would fold a
  // neighbour (small faces on curved parts), either end is tried too: both lie on M0,
  // and without this such faces stay, with their short edges, to the end.
  foot = ref_.project_near(foot_face_[a], collapse_position(m_, f, k), m_.vertex_area_normal(a) + m_.vertex_area_normal(c),
                           2 * norm_of_diagonal(m_, f, k));
  if (foot.found() && shape_after(foot.point, ref_.normal_at(foot))) {
    pos = foot.point;
    return true;
  }
  for (Index end : {a, c}) {
    foot = ref_.closest_within(m_.position(end), 0.0);
    if (foot.found() && shape_after(foot.point, ref_.normal_at(foot))) {
      pos = foot.point;
      return true;
    }
  }
  return false;
}

// [paper 3.3] No face the collapse enlarges may have a radius (largest centre-to-
// corner distance) above F_M at its centre. The faces are those around a and c
// after the merge, with the survivor at `pos`.
Simplifier::Verdict Simplifier::check_collapse(Index f, Index k, Vec3& pos, SurfacePoint& foot) const {
  if (!can_collapse_diagonal(m_, f, k) || touches_kept_border(f, k)) return Verdict::Topology;
  if (exceeds_valence(f, k)) return Verdict::Valence;
  if (!place(f, k, pos, foot)) return Verdict::Geometry;
  if (opt_.adaptive && !m_fitmap_allows(f, k, pos)) return Verdict::Fitmap;
  return Verdict::Ok;
}

bool Simplifier::m_fitmap_allows(Index f, Index k, const Vec3& pos) const {
  return for_each_face_after_collapse(m_, f, k, pos, [&](Index g, const Vec3* q) { return within_m_fitmap(g, q); });
}

// Whether face g with corners q has a radius within F_M at its centre.
bool Simplifier::within_m_fitmap(Index g, const Vec3* q) const {
  const Vec3 centre = 0.25 * (q[0] + q[1] + q[2] + q[3]);
  double radius = 0;
  for (int i = 0; i < 4; ++i) radius = std::max(radius, (q[i] - centre).norm());
  Index hint = centre_hint(g);
  const double fm = sample_fitmap(opt_.fitmaps->m, centre, quad_normal(q[0], q[1], q[2], q[3]), hint);
  return radius * opt_.m_factor <= fm;
}

void Simplifier::update_mu() {
  if (component_mu_.size() == 1) {
    mu_ = component_mu_[0] = mean_edge_length(m_);
  } else {
    // The same sums per component (in the same order, so mu_ is mean_edge_length()).
    std::vector<double>& length = component_mu_;
    std::fill(length.begin(), length.end(), 0.0);
    edge_count_.assign(length.size(), 0);
    double total = 0;
    std::size_t edges = 0;
    for_each_edge_length(m_, [&](Index f, double len) {
      const Index c = component_[m_.vertex(f, 0)];
      length[c] += len, ++edge_count_[c];
      total += len, ++edges;
    });
    mu_ = edges ? total / double(edges) : 0.0;
    for (std::size_t c = 0; c < length.size(); ++c)
      length[c] = edge_count_[c] ? length[c] / double(edge_count_[c]) : mu_;
  }
  if (!opt_.adaptive) return;
  double sum = 0;
  Index n = 0;
  for (Index v = 0; v < m_.vertex_capacity(); ++v)
    if (m_.is_vertex_live(v)) sum += size_[v], ++n;
  size_mean_ = n ? sum / n : 1.0;
}

// Where automatic halting will stop, predicted from the fitmaps alone. Faces grow in the
// order of their key |d| F_S, so at key level K a face at p has diagonal K / F_S(p), and
// its radius passes F_M(p) / m_factor once K > 2 F_M F_S / m_factor. Take the level where
// those places cover 5% of M0; faces of diagonal d cover d^2/2 each, so the count is the
// sum over M0 of 2 dA (F_S / K)^2; 0 if there is nothing to go by. A rough guide, not a
// rule: against the counts the datasets and re-rounded copies of them halt at, 0.44
// (pensatore) to 1.17 (armadillo) of the actual count (bench/RESULTS.md).
double Simplifier::predicted_halt() const {
  constexpr double kShare = 0.05;
  const TriMesh& t = ref_.mesh();
  struct Level {
    double level, area, s;
  };
  std::vector<Level> levels;
  levels.reserve(t.faces.size());
  double total = 0;
  for (const auto& f : t.faces) {
    const double area = triangle_area(t.positions[f[0]], t.positions[f[1]], t.positions[f[2]]);
    double fs = 0, fm = 0;
    for (Index v : f) fs += opt_.fitmaps->s[v] / 3.0, fm += opt_.fitmaps->m[v] / 3.0;
    fs = clamped_s(fs);
    levels.push_back({2 * fm * fs / opt_.m_factor, area, fs});
    total += area;
  }
  std::sort(levels.begin(), levels.end(), [](const Level& x, const Level& y) { return x.level < y.level; });
  double covered = 0, k = 0;
  for (const Level& l : levels) {
    covered += l.area;
    k = l.level;
    if (covered >= kShare * total) break;
  }
  if (!(k > 0)) return 0;
  double faces = 0;
  for (const Level& l : levels) faces += 2 * l.area * (l.s / k) * (l.s / k);
  return faces;
}

// Share of the surface where the M-fitmap blocks: faces whose every diagonal collapse
// that the other checks allow it refuses (and at least one), by area, against the
// mesh's area at the start. Measured afresh over all faces: a list of the refusals met in
// the loop (the fifth to tenth stops' rule) drops a face whenever a neighbour's collapse
// moves it, so its share was noisy and about a third of this one, and where it first
// crossed its threshold was decided by rounding (bench/RESULTS.md).
double Simplifier::blocked_share() const {
  double sum = 0;
  for (Index f = 0; f < m_.face_capacity(); ++f) {
    if (!m_.is_face_live(f)) continue;
    bool refused = false, allowed = false;
    for (Index k = 0; k < 2 && !allowed; ++k) {
      Vec3 pos;
      SurfacePoint foot;
      const Verdict v = check_collapse(f, k, pos, foot);
      allowed = v == Verdict::Ok;
      refused |= v == Verdict::Fitmap;
    }
    if (refused && !allowed) sum += 0.5 * m_.face_area_normal(f).norm();
  }
  return area_ > 0 ? sum / area_ : 0.0;
}

void Simplifier::add_faces_around(Index v, std::vector<Index>& faces) {
  if (v == kNone || !m_.is_vertex_live(v)) return;
  m_.for_each_outgoing(v, [&](Index h) { faces.push_back(QuadMesh::face(h)); });
}

// The new edge's endpoints gain one edge each: both must stay within the valence cap.
bool Simplifier::rotation_passes_cap(Index h, Rotation r) const {
  if (opt_.max_valence <= 0) return true;
  const auto [a, b] = rotated_edge(m_, h, r);
  return std::max(m_.valence(a), m_.valence(b)) < opt_.max_valence;
}

// As rotation_folds(), a rotated face with corner `except` is not checked.
bool Simplifier::rotation_follows_reference(Index h, Rotation r, Index except) const {
  for (const auto& c : rotated_faces(m_, h, r)) {
    if (except != kNone && std::find(c.begin(), c.end(), except) != c.end()) continue;
    const Vec3 q[4] = {m_.position(c[0]), m_.position(c[1]), m_.position(c[2]), m_.position(c[3])};
    if (!follows_reference(quad_normal(q[0], q[1], q[2], q[3]), c, q, Vec3::Zero())) return false;
  }
  return true;
}

bool Simplifier::try_rotate(Index h) {
  if (!m_.is_face_live(QuadMesh::face(h)) || m_.twin(h) == kNone) return false;
  const Index g = m_.twin(h);
  const Index u = m_.from(h), w = m_.to(h);
  const Index x1 = m_.to(QuadMesh::next(h)), x2 = m_.from(QuadMesh::prev(h));
  const Index y1 = m_.to(QuadMesh::next(g)), y2 = m_.from(QuadMesh::prev(g));
  // Energy [paper]: sum over the hexagon of |D(v) - target|. Ties are broken by the sum
  // of squares (ours): a 6-4 pair becoming 5-5 keeps the paper's energy but lowers the
  // maximum valence. The pair decreases lexicographically with every rotation, so the
  // rotations still terminate.
  const Index corner[6] = {u, w, x1, y1, x2, y2};
  int dev[6];
  for (int i = 0; i < 6; ++i) dev[i] = m_.valence(corner[i]) - target_valence(corner[i]);
  auto energy = [&](int gain_a, int gain_b) {  // gain_a on x1, y1; gain_b on x2, y2
    const int d[6] = {dev[0] - 1, dev[1] - 1, dev[2] + gain_a, dev[3] + gain_a, dev[4] + gain_b, dev[5] + gain_b};
    std::pair<int, int> e{0, 0};
    for (int x : d) e.first += std::abs(x), e.second += x * x;
    return e;
  };
  std::pair<int, int> keep{0, 0};
  for (int x : dev) keep.first += std::abs(x), keep.second += x * x;
  // A direction that would raise a vertex above the valence cap is never profitable.
  const std::pair<int, int> never{std::numeric_limits<int>::max(), 0};
  const auto e_a = rotation_passes_cap(h, Rotation::Ccw) ? energy(1, 0) : never;
  const auto e_b = rotation_passes_cap(h, Rotation::Cw) ? energy(0, 1) : never;
  if (std::min(e_a, e_b) >= keep) return false;
  // Prefer the lower energy; on a tie the shorter new edge.
  Rotation first = Rotation::Ccw, second = Rotation::Cw;
  const double la = (m_.position(x1) - m_.position(y1)).squaredNorm();
  const double lb = (m_.position(x2) - m_.position(y2)).squaredNorm();
  if (e_b < e_a || (e_b == e_a && lb < la)) std::swap(first, second);
  const auto e_second = second == Rotation::Ccw ? e_a : e_b;
  for (Rotation r : {first, second}) {
    if (r == second && e_second >= keep) break;
    if (!can_rotate_edge(m_, h, r) || rotation_folds(m_, h, r, kNone, refuse_folds_) ||
        !rotation_follows_reference(h, r))
      continue;
    const Index f1 = QuadMesh::face(h), f2 = QuadMesh::face(g);
    rotate_edge(m_, h, r);
    ++rep_.rotations;
    for (Index f : {f1, f2}) {
      region_faces_.push_back(f);
      for (Index k = 0; k < 4; ++k) cand_.push_back(QuadMesh::halfedge(f, k));
    }
    return true;
  }
  return false;
}

void Simplifier::rotate_in_region() {
  // Each interior edge once: the zone lists some faces more than once, and an edge has
  // two half-edges. Border edges never rotate.
  const std::uint32_t zone = ++stamp_, listed = ++stamp_;
  for (Index f : region_faces_)
    if (m_.is_face_live(f)) face_mark_[f] = zone;
  cand_.clear();
  for (Index f : region_faces_) {
    if (!m_.is_face_live(f) || face_mark_[f] != zone) continue;
    face_mark_[f] = listed;
    for (Index k = 0; k < 4; ++k) {
      const Index h = QuadMesh::halfedge(f, k), t = m_.twin(h);
      if (t != kNone && face_mark_[QuadMesh::face(t)] != listed) cand_.push_back(h);
    }
  }
  int budget = 64;  // each rotation lowers an integer energy, so this is only a guard
  for (std::size_t i = 0; i < cand_.size() && budget > 0; ++i)
    if (try_rotate(cand_[i])) --budget;
}

// Moving v to p keeps its faces sound (shape_ok) and brings it no closer to an edge
// neighbour already nearer than a quarter of their rest length. Convexity alone let
// the springs of a distorted fan drop a vertex next to a neighbour (adaptive bump
// test: an edge of 0.005 mu that no later move undid). The fan's outgoing edges reach
// every neighbour but, at a border vertex, the one across the incoming border edge.
// That one only may not come within a tenth: the interior springs of a border vertex
// of valence 4 or 5 can outweigh its border springs (bump test: three border vertices
// slid onto one point), while a quarter there held bunny.ply's border vertices where
// the projection onto its jagged holes first brings them closer (16 runs of 16 from
// 2K to 13K quads ended with a border edge under 0.5 mu, against 4).
// Border vertices are not held to refuse_folds: the quads at bunny.ply's jagged holes
// are bent, and held there, a border edge shrank to 0.38 mu (uniform, 11K quads).
bool Simplifier::moved_faces_ok(Index v, const Vec3& p) const {
  const Vec3& before = m_.position(v);
  auto comes_within = [&](Index e, double share) {
    const double near = share * rest_length(v, e);
    const double after2 = (p - m_.position(e)).squaredNorm();
    return after2 < near * near && after2 < (before - m_.position(e)).squaredNorm();
  };
  const bool border = m_.is_border_vertex(v);
  if (border && comes_within(m_.from(m_.border_in(v)), 0.1)) return false;
  bool ok = true;
  m_.for_each_outgoing(v, [&](Index h) {
    if (!ok) return;
    const Index f = QuadMesh::face(h);
    if (comes_within(m_.to(h), 0.25)) {
      ok = false;
      return;
    }
    Vec3 q[4];
    for (Index i = 0; i < 4; ++i) q[i] = m_.vertex(f, i) == v ? p : m_.position(m_.vertex(f, i));
    ok = shape_ok(f, q, Vec3::Zero(), !border);
  });
  return ok;
}

// Spring relaxation of one vertex [paper 3.2]: rest length mu to edge neighbours and
// sqrt(2) mu to diagonal ones; the equilibrium of sum (|p-q|-L)^2 is approached by
// one fixed-point step per sweep (the sweeps iterate; more steps per sweep measured the
// same quality for 3x the cost), its normal component dropped, and the result
// re-projected.
//
// Adaptive mode (the paper is silent): rest lengths follow the paper's prescription,
// face size inversely proportional to F_S, with F_S clamped as in the priority and the
// mean kept at mu. Unclamped, F_S spans orders of magnitude and springs that far from
// rest undid the adaptivity (bump test: faces 0.093 on the bump vs 0.092 on the flat
// part); one mu for all took the RMS gain over uniform at automatic halting from 17% to
// 9% (bunny), 22% to 5% (gargoyle), 28% to 14% (armadillo), with edges down to 0.02 mu
// in the transitions.
void Simplifier::smooth_vertex(Index v) {
  ++rep_.relaxations;
  const Vec3 p = m_.position(v);
  const bool border = m_.is_border_vertex(v);
  if (border && (opt_.preserve_boundary || is_border_corner(v))) return;
  // One fan walk gives the springs' fixed point and the vertex normal (the sum of the
  // faces' diagonal cross products).
  Vec3 sum = Vec3::Zero(), area_normal = Vec3::Zero();
  double w = 0;
  auto spring = [&](const Vec3& q, double rest, double weight) {
    sum += weight * spring_point(p, q, rest);
    w += weight;
  };
  m_.for_each_outgoing(v, [&](Index h) {
    // Per face: two edge springs (each edge is shared by two faces) and one diagonal.
    const Index i1 = m_.to(h), id = m_.to(QuadMesh::next(h)), i2 = m_.from(QuadMesh::prev(h));
    const Vec3 &e1 = m_.position(i1), &dg = m_.position(id), &e2 = m_.position(i2);
    area_normal += (dg - p).cross(e2 - e1);
    spring(e1, rest_length(v, i1), 0.5);
    spring(e2, rest_length(v, i2), 0.5);
    spring(dg, kSqrt2 * rest_length(v, id), 1.0);
  });
  Vec3 step, n = Vec3::Zero();
  if (border) {
    // The same springs (the border edges, in one face only, get their other half), and
    // the step along the border only. Springs to the two border neighbours alone left
    // the interior edges of border vertices free to stretch: bunny.ply at 5K had a
    // border quad with edges of 0.50 and 2.48 mu.
    const Index ia = m_.to(m_.out(v)), ib = m_.from(m_.border_in(v));
    const Vec3 a = m_.position(ia), b = m_.position(ib);
    spring(a, rest_length(v, ia), 0.5);
    spring(b, rest_length(v, ib), 0.5);
    const Vec3 t = (b - a).normalized();
    step = (sum / w - p).dot(t) * t;
  } else {
    n = area_normal.normalized();
    const Vec3 d = sum / w - p;
    step = d - d.dot(n) * n;
  }
  // Already at rest: skip the projection and the checks (most vertices in later sweeps).
  if (step.squaredNorm() < 1e-4 * mu_at(v) * mu_at(v)) return;
  // A step the checks refuse is tried again at half and a quarter of its length. All or
  // nothing left faces squeezed between neighbours stuck for good: on pensatore at 15K a
  // quad with a diagonal of 0.29 mu (corners at 4 and 8 degrees) whose every spring step
  // would have turned a neighbour non-convex, while a shorter one does not.
  for (double scale : {1.0, 0.5, 0.25}) {
    const Vec3 target = p + scale * step;
    SurfacePoint foot;
    if (border) {
      foot = ref_.closest_on_border(foot_face_[v], target, 4 * mu_);
      if (!foot.found()) foot = ref_.closest(target, 2 * mu_);
    } else {
      foot = ref_.project_near(foot_face_[v], target, n, 2 * mu_);
    }
    if (!foot.found()) return;
    if (moved_faces_ok(v, foot.point)) {
      m_.position(v) = foot.point;
      record_foot(v, foot);
      return;
    }
  }
}

void Simplifier::smooth_region(int sweeps) {
  // The vertices of the touched faces and one ring around them, in id order.
  ++stamp_;
  region_verts_.clear();
  auto add_vertex = [&](Index v) {
    if (vertex_mark_[v] != stamp_) {
      vertex_mark_[v] = stamp_;
      region_verts_.push_back(v);
    }
  };
  for (Index f : region_faces_)
    if (m_.is_face_live(f))
      for (Index k = 0; k < 4; ++k) add_vertex(m_.vertex(f, k));
  std::sort(region_verts_.begin(), region_verts_.end());
  for (int sweep = 0; sweep < sweeps; ++sweep)
    for (Index v : region_verts_) smooth_vertex(v);
}

void Simplifier::requeue_region() {
  ++stamp_;
  for (Index v : region_verts_) {
    if (!m_.is_vertex_live(v)) continue;
    m_.for_each_outgoing(v, [&](Index h) {
      const Index f = QuadMesh::face(h);
      if (face_mark_[f] == stamp_) return;
      face_mark_[f] = stamp_;
      push_face(f);
    });
  }
}

void Simplifier::cycle(Index f, Index k, const Vec3& pos, const SurfacePoint& foot) {
  const Index b = m_.vertex(f, k + 1), d = m_.vertex(f, k + 3);
  const Index v = collapse_diagonal(m_, f, k, pos);
  record_foot(v, foot);
  ++rep_.collapses;
  after_change({v, b, d});
}

// Border coarsening (ours; see ops/border_ear.h). A border vertex b whose two border
// edges are short next to mu is removed: the interior edge at b is rotated so that b's
// only face is an ear, then the ear collapses with the merged vertex at b (on M0's
// border). Nothing happens unless both steps pass their checks; a rotation whose ear
// is refused is undone.
void Simplifier::coarsen_border() {
  // The list is taken first: removals kill vertices and move others to the border.
  border_verts_.clear();
  for (Index v = 0; v < m_.vertex_capacity(); ++v)
    if (m_.is_vertex_live(v) && m_.is_border_vertex(v)) border_verts_.push_back(v);
  for (Index b : border_verts_)
    if (m_.is_vertex_live(b) && m_.is_border_vertex(b)) remove_border_vertex(b);
}

// Where border vertices a and c merge: at a border corner if one of them is one (false
// if both are), else at `otherwise`. Merging at the middle cut the corners of an
// L-shaped grid by a third of mu (border coarsening) and took half a quad off a strip's
// ends at every chord there.
bool Simplifier::border_merge_point(Index a, Index c, const Vec3& otherwise, Vec3& p) const {
  const bool corner_a = is_border_corner(a), corner_c = is_border_corner(c);
  if (corner_a && corner_c) return false;
  p = corner_a ? m_.position(a) : corner_c ? m_.position(c) : otherwise;
  return true;
}

bool Simplifier::remove_border_vertex(Index b) {
  const Index out = m_.out(b), ha = m_.border_in(b);  // b -> c and a -> b, both on the border
  const Index a = m_.from(ha), c = m_.to(out);
  const double ab = (m_.position(a) - m_.position(b)).norm(), bc = (m_.position(b) - m_.position(c)).norm();
  const int valence = m_.valence(b);
  if (ab + bc >= kBorderShort * mu_at(b) || valence > 3) return false;
  // a, b and c merge into one vertex, at b unless a or c is a corner.
  Vec3 keep;
  if (!border_merge_point(a, c, m_.position(b), keep)) return false;
  // The ear is f with b at corner k, once b has a single face.
  auto try_ear = [&](Index ear, Index k) {
    // Unchecked, a corner that kept its place took in its border neighbours one after
    // another: the corner of a grid of 200 x 4 skinny cells ended with valence 14.
    if (ear_exceeds_valence(ear, k)) return false;
    const SurfacePoint foot = ref_.closest_within(keep, 0.0);  // a vertex's place
    if (!can_collapse_border_ear(m_, ear, k) || !foot.found() ||
        !for_each_face_after_collapse(m_, ear, (k + 1) & 3u, keep,
                              [&](Index g, const Vec3* q) { return shape_ok(g, q, ref_.normal_at(foot)); }))
      return false;
    const Index d = m_.vertex(ear, k + 2);
    const Index v = collapse_border_ear(m_, ear, k, keep);
    record_foot(v, foot);
    ++rep_.border_collapses;
    after_change({v, d});
    return true;
  };
  if (valence == 2) return try_ear(QuadMesh::face(out), QuadMesh::corner(out));
  // Valence 3: rotate the interior edge b -> e away first, so that b keeps one face.
  const Index h = QuadMesh::next(ha);
  if (m_.twin(h) == kNone) return false;
  const Index g = m_.twin(h), f1 = QuadMesh::face(h), f2 = QuadMesh::face(g);
  const std::array<std::array<Index, 4>, 2> before = {m_.face_vertices(f1), m_.face_vertices(f2)};
  const std::array<Index, 6> outer = {m_.twin(QuadMesh::next(h)), m_.twin(QuadMesh::opposite_in_face(h)),
                                      m_.twin(QuadMesh::prev(h)),  m_.twin(QuadMesh::next(g)),
                                      m_.twin(QuadMesh::opposite_in_face(g)), m_.twin(QuadMesh::prev(g))};
  // The ear itself is not checked: it is collapsed next, and try_ear checks the faces
  // after that. Checking it refused every border vertex where the border is straight
  // or turns outwards (the ear's angle at b is then 180 degrees or more): on bunny.ply
  // at 11K, border edges of 0.44 mu stayed along a hole's staircase border.
  for (Rotation r : {Rotation::Ccw, Rotation::Cw}) {
    if (!rotation_passes_cap(h, r) || !can_rotate_edge(m_, h, r) || rotation_folds(m_, h, r, b, refuse_folds_) ||
        !rotation_follows_reference(h, r, b))
      continue;
    rotate_edge(m_, h, r);
    Index ear = kNone, k = 0;
    for (Index f : {f1, f2})
      for (Index i = 0; i < 4; ++i)
        if (m_.vertex(f, i) == b) ear = f, k = i;
    if (ear != kNone && try_ear(ear, k)) return true;
    const Index faces[2] = {f1, f2};
    detail::rewrite_faces(m_, faces, before.data(), 2, outer.data(), 6);  // undo the rotation
  }
  return false;
}

// Cleaning, rotations, smoothing and requeueing around vertices an operation changed.
void Simplifier::after_change(const Index* first, const Index* last) {
  region_faces_.clear();
  work_.assign(first, last);
  CleanCounts cc;
  clean_from(m_, work_, cc, &region_faces_);
  rep_.doublets += cc.doublets;
  rep_.singlets += cc.singlets;
  for (const Index* x = first; x != last; ++x) add_faces_around(*x, region_faces_);
  if (opt_.rotations) rotate_in_region();
  const bool fine = m_.n_faces() > fine_above_;  // see SimplifyOptions::fine_phase
  smooth_region(fine ? 1 : opt_.smoothing_sweeps);
  for (int pass = 1; pass < (fine ? 1 : opt_.passes); ++pass) {
    // Smoothing moved the zone: rotations the fold and convexity checks refused may
    // pass now, and the faces around the smoothed vertices get their turn too.
    // Measured on the paper's models: +4 to +6 points of regular vertices for about
    // twice the time (bench/RESULTS.md).
    region_faces_.clear();
    for (Index x : region_verts_) add_faces_around(x, region_faces_);
    if (opt_.rotations) rotate_in_region();
    // The zone is mostly relaxed already: one sweep fewer gave the same quality for
    // about 12% less time (bunny.obj at 5K: 90.4% regular against 90.6%).
    smooth_region(std::max(1, opt_.smoothing_sweeps - 1));
  }
  requeue_region();
}

// Poly-chord collapses (ours; SimplifyOptions::chord_collapses), once no diagonal
// collapse is left above the target: every chord of at most kChordFaces faces, shortest
// crossed edges (against their rest length) first. A chord is taken while that brings
// the face count closer to the target, and not if an earlier one of the same batch
// changed it; then the loop goes back to diagonal collapses. One chord per batch gave
// the same results on the odd inputs, but each batch walks the whole mesh: a ribbon of
// 5,000 quads to 50 took 2.9 s instead of 0.06 s. Without the marks (every allowed
// chord of the list, neighbours too) an annulus at 10 quads ended with RMS 11.8e-3
// instead of 3.1e-3.
bool Simplifier::collapse_chords() {
  constexpr Index kChordFaces = 64;
  const Index target = opt_.target_faces;
  struct Candidate {
    double key;
    Index h;
  };
  std::vector<Candidate> candidates;
  std::vector<char> seen(2 * std::size_t(m_.face_capacity()), 0);  // per face and parity of the crossed edges
  for (Index f = 0; f < m_.face_capacity(); ++f)
    for (Index k = 0; k < 2 && m_.is_face_live(f); ++k) {
      if (seen[2 * f + k]) continue;
      seen[2 * f + k] = 1;
      if (!gather_chord(m_, QuadMesh::halfedge(f, k), chord_, kChordFaces)) continue;
      double key = 0;
      for (Index i = 0; i < chord_.pairs(); ++i) {
        const Index l = chord_.left[i], r = chord_.right[i];
        key += (m_.position(l) - m_.position(r)).norm() / rest_length(l, r);
      }
      for (std::size_t i = 0; i < chord_.faces.size(); ++i)
        seen[2 * chord_.faces[i] + (QuadMesh::corner(chord_.entries[i]) & 1u)] = 1;
      candidates.push_back({key / double(chord_.pairs()), chord_.entries[0]});
    }
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.key != b.key ? a.key < b.key : a.h < b.h; });
  std::fill(seen.begin(), seen.end(), 0);  // now: faces changed by this batch
  Index done = 0;
  for (const Candidate& c : candidates) {
    if (m_.n_faces() <= target) break;
    if (!m_.is_face_live(QuadMesh::face(c.h)) || !gather_chord(m_, c.h, chord_, kChordFaces)) continue;
    if (2 * (m_.n_faces() - target) <= Index(chord_.faces.size())) continue;
    bool changed = false;
    for (Index f : chord_.faces) changed = changed || seen[f];
    if (changed || !try_collapse_chord(chord_)) continue;
    ++done;
    // after_change() left the smoothed zone in region_verts_: its faces have changed.
    for (Index v : region_verts_)
      if (m_.is_vertex_live(v)) m_.for_each_outgoing(v, [&](Index h) { seen[QuadMesh::face(h)] = 1; });
  }
  return done > 0;
}

bool Simplifier::try_collapse_chord(const Chord& chord) {
  if (!can_collapse_chord(m_, chord)) {
    ++rep_.refused_topology;
    return false;
  }
  const Index pairs = chord.pairs();
  for (Index i = 0; i < pairs; ++i) {
    const Index l = chord.left[i], r = chord.right[i];
    if (opt_.preserve_boundary && (m_.is_border_vertex(l) || m_.is_border_vertex(r))) {
      ++rep_.refused_topology;
      return false;
    }
    const bool open_end = !chord.closed && (i == 0 || i == pairs - 1);
    if (opt_.max_valence > 0 && m_.valence(l) + m_.valence(r) - (open_end ? 3 : 4) > opt_.max_valence) {
      ++rep_.refused_valence;
      return false;
    }
  }
  // Each merged vertex: a border end keeps its place; two border ends (an open end of
  // the chord) meet at a border corner if either is one, else at the point of M0
  // closest to their midpoint (not through closest_on_border(), whose walk may start on
  // the other border of a part one triangle wide: on a ribbon every chord was refused);
  // otherwise the midpoint projected onto M0.
  chord_pos_.resize(pairs);
  chord_feet_.resize(pairs);
  for (Index i = 0; i < pairs; ++i) {
    const Index l = chord.left[i], r = chord.right[i];
    const bool bl = m_.is_border_vertex(l), br = m_.is_border_vertex(r);
    const Vec3 mid = 0.5 * (m_.position(l) + m_.position(r));
    SurfacePoint foot;
    if (bl != br) {
      foot = ref_.closest_within(m_.position(bl ? l : r), 0.0);
    } else if (bl) {
      Vec3 p;
      if (!border_merge_point(l, r, mid, p)) {
        ++rep_.refused_topology;
        return false;
      }
      foot = ref_.closest_within(p, std::min((p - m_.position(l)).norm(), (p - m_.position(r)).norm()));
    } else {
      foot = ref_.project_near(foot_face_[l], mid, m_.vertex_area_normal(l) + m_.vertex_area_normal(r),
                               2 * (m_.position(l) - m_.position(r)).norm());
    }
    if (!foot.found()) {
      ++rep_.refused_geometry;
      return false;
    }
    chord_pos_[i] = foot.point;
    chord_feet_[i] = foot;
  }
  faces_beside_chord(m_, chord, beside_);
  for (Index g : beside_) {
    Vec3 q[4];
    for (Index k = 0; k < 4; ++k) {
      const Index v = m_.vertex(g, k);
      const int pair = chord_pair_of(chord, v);
      q[k] = pair >= 0 ? chord_pos_[pair] : m_.position(v);
    }
    if (!shape_ok(g, q, Vec3::Zero())) {
      ++rep_.refused_geometry;
      return false;
    }
    if (opt_.adaptive && !within_m_fitmap(g, q)) {  // the enlarged faces, as for a diagonal collapse
      ++rep_.refused_fitmap;
      return false;
    }
  }
  collapse_chord(m_, chord, chord_pos_);
  for (Index i = 0; i < pairs; ++i) record_foot(chord.left[i], chord_feet_[i]);
  ++rep_.chord_collapses;
  after_change(chord.left.data(), chord.left.data() + chord.left.size());
  return true;
}

// Unfolding (ours; SimplifyOptions::unfold): a quad bent past 90 degrees wraps a thin
// part (an ear's rim, a claw) too narrow for its size. Refusing such bends during the
// loop, as adaptive mode does, cost uniform meshes homeometry (bench/RESULTS.md); one
// rotation afterwards re-pairs the corners across the part instead. Of the rotations
// of f's interior edges that leave neither new quad folded, the one whose new quads
// bend least is taken, then the zone is smoothed with folds refused, so that the
// springs even out the new edge without bending anything past 90 degrees again.
bool Simplifier::unfold_face(Index f) {
  double best = -1;
  Index best_h = kNone;
  Rotation best_r = Rotation::Ccw;
  for (Index k = 0; k < 4; ++k) {
    const Index h = QuadMesh::halfedge(f, k), g = m_.twin(h);
    if (g == kNone) continue;
    for (Rotation r : {Rotation::Ccw, Rotation::Cw}) {
      if (!rotation_passes_cap(h, r) || !can_rotate_edge(m_, h, r) || rotation_folds(m_, h, r) ||
          !rotation_follows_reference(h, r))
        continue;
      const auto c = rotated_faces(m_, h, r);
      // Not folded <=> some split bends by less than 90 degrees <=> fold_cos >= 0.
      const double after = std::min(quad_fold_cos(m_.positions(), c[0]), quad_fold_cos(m_.positions(), c[1]));
      if (after >= 0 && after > best) best = after, best_h = h, best_r = r;
    }
  }
  if (best_h == kNone) return relocate_corner(f);
  const Index g = QuadMesh::face(m_.twin(best_h));
  rotate_edge(m_, best_h, best_r);
  region_faces_.clear();
  for (Index x : {f, g})
    for (Index k = 0; k < 4; ++k) add_faces_around(m_.vertex(x, k), region_faces_);
  smooth_region(opt_.smoothing_sweeps);
  return true;
}

// Where no rotation unfolds f (two opposite corners of valence 3 wrapping a thin rim),
// one interior corner moves part of the way towards the other three, onto M0: of the
// moves that keep the faces around it sound (moved_faces_ok() with folds refused) and
// its edges within [1/2, 2] mu or no worse than they were, the one that bends f least.
// Several passes may each take it a step further. Without the bound on the edges the
// armadillo at 3,000 quads got an edge of 0.09 mu; without the smoothing after it, a
// gargoyle run left [0.5, 2] mu (bench/RESULTS.md).
bool Simplifier::relocate_corner(Index f) {
  const auto c = m_.face_vertices(f);
  auto cos_with = [&](Index v, const Vec3& p) {
    Vec3 q[4];
    for (int i = 0; i < 4; ++i) q[i] = c[i] == v ? p : m_.position(c[i]);
    return quad_fold_cos(q[0], q[1], q[2], q[3]);
  };
  double best = quad_fold_cos(m_.positions(), c);
  Index best_v = kNone;
  SurfacePoint best_foot;
  for (int i = 0; i < 4; ++i) {
    const Index v = c[i];
    if (m_.is_border_vertex(v)) continue;
    const Vec3 others = (m_.position(c[(i + 1) % 4]) + m_.position(c[(i + 2) % 4]) + m_.position(c[(i + 3) % 4])) / 3;
    for (double t : {0.5, 0.25, 0.125}) {
      const Vec3 step = t * (others - m_.position(v));
      const SurfacePoint foot = ref_.closest_within(m_.position(v) + step, step.norm());
      if (!foot.found()) continue;
      const double after = cos_with(v, foot.point);
      if (after <= best || !moved_faces_ok(v, foot.point)) continue;
      bool even = true;
      m_.for_each_outgoing(v, [&](Index h) {
        const Vec3& q = m_.position(m_.to(h));
        const double before = (m_.position(v) - q).norm(), len = (foot.point - q).norm();
        even = even && len >= std::min(0.5 * mu_at(v), before) && len <= std::max(2.0 * mu_at(v), before);
      });
      if (even) best = after, best_v = v, best_foot = foot;
    }
  }
  if (best_v == kNone) return false;
  m_.position(best_v) = best_foot.point;
  record_foot(best_v, best_foot);
  region_faces_.clear();
  add_faces_around(best_v, region_faces_);
  smooth_region(opt_.smoothing_sweeps);
  return true;
}

// A rotation can unfold a quad next to one whose only unfolding rotation it had taken:
// a few passes, which end as soon as one finds nothing to do.
void Simplifier::unfold() {
  refuse_folds_ = true;
  for (int pass = 0; pass < 3; ++pass) {
    const Index before = rep_.unfolds;
    for (Index f = 0; f < m_.face_capacity(); ++f)
      if (m_.is_face_live(f) && quad_folds(m_.positions(), m_.face_vertices(f)) && unfold_face(f)) ++rep_.unfolds;
    if (rep_.unfolds == before) break;
  }
  refuse_folds_ = opt_.refuse_folds;
}

SimplifyReport Simplifier::run() {
  const auto t0 = std::chrono::steady_clock::now();
  if (opt_.adaptive && (!opt_.fitmaps || opt_.fitmaps->s.size() != ref_.mesh().n_vertices() ||
                        opt_.fitmaps->m.size() != ref_.mesh().n_vertices()))
    throw std::invalid_argument("simplify: adaptive mode needs fitmaps computed on the reference surface");
  const CleanCounts initial = clean_all(m_);
  rep_.doublets += initial.doublets;
  rep_.singlets += initial.singlets;
  rep_.initial_faces = m_.n_faces();
  version_.assign(m_.face_capacity(), 0);
  face_mark_.assign(m_.face_capacity(), 0);
  vertex_mark_.assign(m_.vertex_capacity(), 0);
  foot_normal_.assign(m_.vertex_capacity(), Vec3::Zero());
  foot_face_.assign(m_.vertex_capacity(), kNone);
  centre_foot_.assign(m_.face_capacity(), kNone);
  size_.assign(m_.vertex_capacity(), 1.0);
  if (opt_.adaptive) {
    std::vector<float> sorted = opt_.fitmaps->s;
    std::sort(sorted.begin(), sorted.end());
    s_mid_ = std::max(double(sorted[sorted.size() / 2]), 1e-30);  // a scale only: sizes are relative
    if (const double q = opt_.s_percentiles; q > 0) {
      s_lo_ = sorted[std::size_t(q * (sorted.size() - 1))];
      s_hi_ = sorted[std::size_t((1 - q) * (sorted.size() - 1))];
    }
    s_foot_.assign(m_.vertex_capacity(), s_mid_);  // size 1 where a vertex has no foot
  }
  for (Index v = 0; v < m_.vertex_capacity(); ++v)
    if (m_.is_vertex_live(v)) {
      const SurfacePoint s = ref_.closest_within(m_.position(v), 0.0);  // M0's own vertices
      if (s.found()) record_foot(v, s);
    }
  for (Index v = 0; v < m_.vertex_capacity() && !has_border_; ++v)
    has_border_ = m_.is_vertex_live(v) && m_.is_border_vertex(v);
  component_mu_.assign(connected_components(m_, component_), 0.0);
  update_mu();
  if (opt_.initial_sweeps > 0) {
    region_faces_.clear();
    for (Index f = 0; f < m_.face_capacity(); ++f)
      if (m_.is_face_live(f)) region_faces_.push_back(f);
    smooth_region(opt_.initial_sweeps);
    update_mu();
  }
  for (Index f = 0; f < m_.face_capacity(); ++f)
    if (m_.is_face_live(f)) area_ += 0.5 * m_.face_area_normal(f).norm();
  rebuild_heap();

  const Index target = opt_.target_faces;
  if (target == 0 && opt_.adaptive) rep_.predicted_faces = predicted_halt();
  if (opt_.fine_phase > 0) {
    // Automatic halting has no target: the predicted count stands in for it, times a
    // margin. The predictions were at least 0.44 of the actual counts, so the last
    // halving gets the full passes. With 1.6 the pensatore's halving did not, and its
    // regular share fell (bench/RESULTS.md).
    constexpr double kMargin = 3.0;
    if (target > 0)
      fine_above_ = opt_.fine_phase * target;
    else if (rep_.predicted_faces > 0)
      fine_above_ = opt_.fine_phase * kMargin * rep_.predicted_faces;
  }
  // Automatic halting measures the blocked share (the paper's rule, halt_share 1, runs
  // until nothing is left instead); `next_scan` is the face count of the next measure.
  const bool measure = target == 0 && opt_.adaptive && opt_.halt_share < 1;
  bool halted = false;
  Index next_scan = std::isfinite(fine_above_) ? Index(std::min(fine_above_, double(m_.n_faces()))) : m_.n_faces();
  // Where the input's own faces already reach F_M (a thin rim, noise) nothing will ever
  // coarsen; only what the collapses add counts towards the halt. A pancake's rim was
  // blocked over more than 15% of its area from the start, and it stopped after one
  // collapse (bench/RESULTS.md).
  const double base_share = measure ? blocked_share() : 0.0;
  const Index span = rep_.initial_faces > target ? rep_.initial_faces - target : 1;
  Index next_mu = 0;
  // Diagonal collapses; once none is left above the target, chords (collapse_chords()).
  for (;;) {
    while (m_.n_faces() > target && !heap_.empty()) {
      std::pop_heap(heap_.begin(), heap_.end(), LaterFirst{});
      const Entry e = heap_.back();
      heap_.pop_back();
      if (!m_.is_face_live(e.face) || e.version != version_[e.face]) continue;
      Vec3 pos;
      SurfacePoint foot;
      // A refused face comes back only when something around it changes.
      const Verdict verdict = check_collapse(e.face, e.k, pos, foot);
      if (verdict != Verdict::Ok) {
        Index& refusals = verdict == Verdict::Topology ? rep_.refused_topology
                          : verdict == Verdict::Valence ? rep_.refused_valence
                          : verdict == Verdict::Geometry ? rep_.refused_geometry
                                                         : rep_.refused_fitmap;
        ++refusals;
        continue;
      }
      cycle(e.face, e.k, pos, foot);
      if (measure && m_.n_faces() <= next_scan) {
        // The share grows smoothly as the faces grow: measured again after a step of the
        // faces that shrinks to 1% as it nears the halting share (about 15 measures a run).
        rep_.blocked_share = blocked_share();
        const double added = rep_.blocked_share - base_share;
        if ((halted = added >= opt_.halt_share)) break;
        const double step = std::clamp(0.25 * (1 - added / opt_.halt_share), 0.01, 0.25);
        next_scan = Index(double(m_.n_faces()) * (1 - step));
      }
      if (has_border_ && opt_.coarsen_border && !opt_.preserve_boundary && rep_.collapses % 64 == 0)
        coarsen_border();
      if (rep_.collapses >= next_mu) {
        // mu drifts slowly: an exact recount every 256 collapses is cheaper than tracking every
        // edge each operation touches, and as accurate, if it comes after at least 2% of the
        // faces (mu moves ~1%) and at most a tenth (~5%). Without that upper bound a 900-quad
        // grid simplified to 50 left mu far behind: the border (coarsened below 1.3 mu) kept
        // most of its edges, the target was missed at 70 quads, and quads spanned the grid.
        update_mu();
        next_mu = rep_.collapses + std::clamp<Index>(256, m_.n_faces() / 50, std::max<Index>(1, m_.n_faces() / 10));
      }
      if (heap_.size() > 16 * std::size_t(m_.n_faces()) + 1024) rebuild_heap();
      if (opt_.progress && rep_.collapses % 256 == 0) {
        // Without a target (automatic halting) the end is unknown: report the share of
        // faces removed, which only grows.
        const float done = float(rep_.initial_faces - m_.n_faces()) / float(target ? span : rep_.initial_faces);
        if (!opt_.progress(std::min(done, 1.f), "simplify")) {
          rep_.cancelled = true;
          break;
        }
      }
    }
    if (!opt_.chord_collapses || target == 0 || m_.n_faces() <= target || rep_.cancelled || !collapse_chords()) break;
  }
  if (opt_.adaptive && !halted) rep_.blocked_share = blocked_share();
  if (opt_.unfold && !opt_.refuse_folds && !rep_.cancelled) unfold();
  m_.compact();
  rep_.faces = m_.n_faces();
  rep_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (opt_.progress && !rep_.cancelled) opt_.progress(1.f, "simplify");
  return rep_;
}

}  // namespace

double mean_edge_length(const QuadMesh& m) {
  double sum = 0;
  std::size_t n = 0;
  for_each_edge_length(m, [&](Index, double length) { sum += length, ++n; });
  return n ? sum / double(n) : 0.0;
}

SimplifyReport simplify(QuadMesh& mesh, const ReferenceSurface& ref, const SimplifyOptions& options) {
  return Simplifier(mesh, ref, options).run();
}

}  // namespace qs
