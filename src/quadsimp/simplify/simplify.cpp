// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// The loop [Bozzo et al. 2010, 3.2-3.3]: the heap of diagonals and its keys, the checks
// every collapse passes (the M-fitmap's among them), automatic halting, and what follows
// each collapse. The other steps are in the files named in simplifier.h.
#include "quadsimp/simplify/simplify.h"

#include <tbb/blocked_range.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "quadsimp/fitmap/tips.h"
#include "quadsimp/mesh/quad_geometry.h"
#include "quadsimp/ops/cleaning.h"
#include "quadsimp/ops/diagonal_collapse.h"
#include "quadsimp/simplify/simplifier.h"
#include "quadsimp/util/errors.h"
#include "quadsimp/util/parallel.h"

namespace qs {
namespace {

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

// F_S's median (a scale only: sizes are relative) and the bounds it is clamped to
// (SimplifyOptions::s_percentiles; none for 0).
struct SRange {
  double lo = 0, mid = 1, hi = std::numeric_limits<double>::infinity();
};
SRange s_range(const std::vector<float>& s, double q) {
  std::vector<float> sorted = s;
  std::sort(sorted.begin(), sorted.end());
  SRange r;
  r.mid = std::max(double(sorted[sorted.size() / 2]), detail::kLeastS);
  if (q > 0) {
    r.lo = std::max(double(sorted[std::size_t(q * (sorted.size() - 1))]), 0.5 * r.mid);
    // Not below the median: where F_S is 0 (exactly planar) up to the upper quantile, the
    // median is raised to kLeastS and the quantile is not, and std::clamp needs lo <= hi.
    const double upper = sorted[std::size_t((1 - q) * (sorted.size() - 1))];
    r.hi = std::min(std::max(upper, r.mid), 2.0 * r.mid);
  }
  return r;
}

// Faces grow in the order of their key |d| F_S, so at key level K a face at p has
// diagonal K / F_S(p), and its radius passes F_M(p) / m_factor once K > 2 F_M F_S /
// m_factor. Take the level where those places cover 5% of M0; faces of diagonal d cover
// d^2/2 each, so the count is the sum over M0 of 2 dA (F_S / K)^2. A rough guide, not a
// rule: against the counts the datasets and re-rounded copies of them halt at, 0.44
// (pensatore) to 1.17 (armadillo) of the actual count (bench/RESULTS.md). `range` is
// s_range() of the fitmaps (the loop has it already: one sort of F_S per run).
double predicted_halting_faces(const TriMesh& t, const SimplifyOptions& opt, const SRange& range) {
  constexpr double kShare = 0.05;
  struct Level {
    double level, area, s;
  };
  std::vector<Level> levels;
  levels.reserve(t.faces.size());
  double total = 0;
  for (const auto& f : t.faces) {
    const double area = triangle_area(t.positions[f[0]], t.positions[f[1]], t.positions[f[2]]);
    double fs = 0, fm = 0;
    for (Index v : f) fs += opt.fitmaps->s[v] / 3.0, fm += opt.fitmaps->m[v] / 3.0;
    fs = std::clamp(fs, range.lo, range.hi);
    levels.push_back({2 * fm * fs / opt.m_factor, area, fs});
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

}  // namespace

double predicted_halting_faces(const TriMesh& t, const SimplifyOptions& opt) {
  if (!opt.adaptive || !opt.fitmaps || t.n_vertices() == 0 || opt.fitmaps->s.size() != t.n_vertices() ||
      opt.fitmaps->m.size() != t.n_vertices())
    return 0;
  return predicted_halting_faces(t, opt, s_range(opt.fitmaps->s, opt.s_percentiles));
}

double mean_edge_length(const QuadMesh& m) {
  double sum = 0;
  std::size_t n = 0;
  for_each_edge_length(m, [&](Index, double length) { sum += length, ++n; });
  return n ? sum / double(n) : 0.0;
}

namespace detail {

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
// mode: |d|. With anisotropy |d| is measured in the metric under the face's four corners:
// without it there, the springs alone stretched the quads and the RMS gain stayed where it
// was (a prototype: 20.7% over the fixed counts; bench/RESULTS.md). Appends both diagonals of f with
// the face's current version.
void Simplifier::append_entries(Index f) {
  const double scale = opt_.adaptive ? s_weight(f) : 1.0;
  const auto c = m_.face_vertices(f);
  const Metric g = anisotropy_.empty() ? Metric{} : mean_metric({c[0], c[1], c[2], c[3]});
  for (Index k = 0; k < 2; ++k) {
    const double length = anisotropy_.empty()
                              ? norm_of_diagonal(m_, f, k)
                              : std::sqrt(length2_under(g, m_.position(c[k]) - m_.position(c[k + 2])));
    heap_.push_back({float(length * scale), 2 * f + k, version_[f]});
  }
}

void Simplifier::push_face(Index f) {
  ++version_[f];
  append_entries(f);
  std::push_heap(heap_.begin(), heap_.end() - 1, LaterFirst{});
  std::push_heap(heap_.begin(), heap_.end(), LaterFirst{});
}

void Simplifier::rebuild_heap() {
  heap_.clear();
  // Room for what upkeep() lets the heap grow to, so that it never moves: grown by
  // doubling, each move held the old entries beside the new (151 MB at the peak of an
  // adaptive run of 1.1 M triangles, whose heap holds 100 MB). Room never written takes
  // no memory. Later rebuilds, with fewer faces, find it there. The margin is for the
  // entries one collapse's requeue adds past the check (two a face of its region).
  heap_.reserve(kHeapPerFace * std::size_t(m_.n_faces()) + kHeapExtra + 4096);
  for (Index f = 0; f < m_.face_capacity(); ++f)
    if (m_.is_face_live(f)) {
      ++version_[f];
      append_entries(f);
    }
  std::make_heap(heap_.begin(), heap_.end(), LaterFirst{});
}

// Where the merged vertex goes: the midpoint re-projected onto M0 along the normal
// of the current mesh there (the faces around both ends), or the border end.
bool Simplifier::place(Index f, Index k, Vec3& pos, SurfacePoint& foot) const {
  const Index a = m_.vertex(f, k), c = m_.vertex(f, k + 2);
  auto shape_after = [&](const Vec3& p, const Vec3& p_normal) {
    return for_each_face_after_collapse(m_, f, k, p, [&](Index g, const Vec3* q) { return shape_ok(g, q, p_normal); });
  };
  Index tip;
  if (!merge_keeps_tip(a, c, tip)) return false;
  if (tip != kNone) {
    pos = m_.position(tip);
    foot = ref_.closest_within(pos, 0.0);
    return foot.found() && shape_after(pos, ref_.normal_at(foot));
  }
  if (m_.is_border_vertex(a) || m_.is_border_vertex(c)) {
    foot = ref_.closest_within(collapse_position(m_, f, k), 0.0);  // the border end is on M0 already
    pos = foot.point;
    return foot.found() && shape_after(pos, ref_.normal_at(foot));
  }
  // The paper's place: the midpoint projected along the normal. Where that would fold a
  // neighbour (small faces on curved parts), either end is tried too: both lie on M0,
  // and without this such faces stay, with their short edges, to the end.
  foot = ref_.project_near(foot_face_[a], collapse_position(m_, f, k),
                           m_.vertex_area_normal(a) + m_.vertex_area_normal(c), 2 * norm_of_diagonal(m_, f, k));
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

Simplifier::Verdict Simplifier::check_collapse(Index f, Index k, Vec3& pos, SurfacePoint& foot, Bound bound) const {
  if (!can_collapse_diagonal(m_, f, k) || touches_kept_border(f, k)) return Verdict::Topology;
  if (!crease_.empty()) {
    const Index a = m_.vertex(f, k), c = m_.vertex(f, k + 2);
    if (joins_pinned(a, c) || joins_pinned(c, a)) return Verdict::Topology;
  }
  if (exceeds_valence(f, k)) return Verdict::Valence;
  if (!place(f, k, pos, foot)) return Verdict::Geometry;
  return opt_.adaptive ? check_grown_faces(f, k, pos, bound) : Verdict::Ok;
}

// The faces a collapse grows are those around a and c after the merge, with the
// survivor at `pos`; the first one refused gives the verdict.
Simplifier::Verdict Simplifier::check_grown_faces(Index f, Index k, const Vec3& pos, Bound bound) const {
  Verdict v = Verdict::Ok;
  for_each_face_after_collapse(m_, f, k, pos, [&](Index g, const Vec3* q) {
    v = check_grown_face(g, q, bound);
    return v == Verdict::Ok;
  });
  return v;
}

Simplifier::QuadShape Simplifier::shape_of(const Vec3* q) {
  QuadShape s{0.25 * (q[0] + q[1] + q[2] + q[3]), quad_normal(q[0], q[1], q[2], q[3]), 0.0};
  for (int i = 0; i < 4; ++i) s.radius = std::max(s.radius, (q[i] - s.centre).norm());
  return s;
}

// Face g with corners q: [paper 3.3] its radius at most F_M at its centre; then ours,
// the input within reach along its normal. The loop's slack (SimplifyOptions::m_slack)
// is for faces smaller than the reach only, which no ray check looks at: on large faces
// it took a smooth shape's projectability under 99.5% (bench/RESULTS.md, "The slack for
// faces under the reach"). Without the reach, the paper's bound holds everywhere.
Simplifier::Verdict Simplifier::check_grown_face(Index g, const Vec3* q, Bound bound) const {
  const QuadShape s = shape_of(q);
  Index hint = centre_hint(g);
  const bool slack = bound == Bound::Loop && under_reach(s);
  const double factor = slack ? opt_.m_factor / opt_.m_slack : opt_.m_factor;
  if (bound_radius(g, q, s, bound) * factor > sample_fitmap(opt_.fitmaps->m, s.centre, s.normal, hint))
    return Verdict::Fitmap;
  return beyond_reach(g, q, s) ? Verdict::Reach : Verdict::Ok;
}

// The radius the M-fitmap bounds: the paper's, s.radius, but in the loop with anisotropy
// (ours) the corners' distances from the centre under the corners' mean metric, divided
// by the metric's stretch: across the most curved direction a face keeps the paper's
// bound, along the flatter one, where the surface's normal turns less, it may reach
// stretch times as far, the aspect the springs give it. With the paper's radius there,
// the long side of the stretched quads of thin parts (fingers, ears) held them to 60% of
// a square quad's area at aspect 3 (bench/RESULTS.md, "The M-fitmap's bound along the
// stretch"). The halting measure keeps the paper's radius, as it keeps the bound without
// the slack.
double Simplifier::bound_radius(Index g, const Vec3* q, const QuadShape& s, Bound bound) const {
  if (anisotropy_.empty() || bound == Bound::Halting) return s.radius;
  const auto c = m_.face_vertices(g);
  const Metric G = mean_metric({c[0], c[1], c[2], c[3]});
  // G's eigenvalues are s, 1/s and 1 (along the normal), so its trace is s + 1/s + 1.
  const double t = G[0] + G[3] + G[5] - 1;
  const double stretch = std::max(1.0, 0.5 * (t + std::sqrt(std::max(0.0, t * t - 4))));
  double r2 = 0;
  for (int i = 0; i < 4; ++i) r2 = std::max(r2, length2_under(G, q[i] - s.centre));
  return std::sqrt(r2 / stretch);
}

// SimplifyOptions::reach: whether face g with corners q (shape s) is large and misses the
// input from its centre or an edge's midpoint, as the projectability measure casts its
// rays (metrics.h). A border edge's midpoint is not checked: it lies at M0's border, where
// a ray may pass just outside it. A face beside a hole is checked from its centre and its
// other edges like any face, so that it cannot grow across the hole: skipping such faces
// whole let a scan with many small holes grow its faces past them until no collapse was
// left (bench/RESULTS.md, "Faces beside holes").
bool Simplifier::beyond_reach(Index g, const Vec3* q, const QuadShape& s) const {
  if (!(reach_ > 0) || under_reach(s)) return false;
  if (!ref_.ray_project(s.centre, s.normal, reach_).found()) return true;
  for (Index i = 0; i < 4; ++i) {
    if (m_.is_border_halfedge(QuadMesh::halfedge(g, i))) continue;
    if (!ref_.ray_project(0.5 * (q[i] + q[(i + 1) % 4]), s.normal, reach_).found()) return true;
  }
  return false;
}

void Simplifier::count_refusal(Verdict v) {
  switch (v) {
    case Verdict::Topology: ++rep_.refused_topology; break;
    case Verdict::Valence: ++rep_.refused_valence; break;
    case Verdict::Geometry: ++rep_.refused_geometry; break;
    case Verdict::Fitmap: ++rep_.refused_fitmap; break;
    case Verdict::Reach: ++rep_.refused_reach; break;
    case Verdict::Ok: break;
  }
}

// The check sees each face where a collapse grows it; the rotations and smoothing moves
// after it are not checked (checking them cost 10-23% more time, bench/RESULTS.md; kept
// through the smoothing, it mended a CAD block far below its halting count but left a
// cube less projectable: "The reach kept through the smoothing"), so the faces beyond
// the reach at the end are listed for the log (and the filters' selection).
std::vector<Index> Simplifier::faces_beyond_reach() const {
  std::vector<Index> out;
  for (Index f = 0; f < m_.face_capacity(); ++f) {
    if (!m_.is_face_live(f)) continue;
    const auto q = m_.positions_of(m_.face_vertices(f));
    if (beyond_reach(f, q.data(), shape_of(q.data()))) out.push_back(f);
  }
  return out;
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

// Share of the surface where the M-fitmap blocks: faces whose every diagonal collapse
// that the other checks allow it refuses (and at least one), by area, against the
// mesh's area at the start. Measured afresh over all faces: a list of the refusals met in
// the loop (the fifth to tenth stops' rule) drops a face whenever a neighbour's collapse
// moves it, so its share was noisy and about a third of this one, and where it first
// crossed its threshold was decided by rounding (bench/RESULTS.md).
// The M-fitmap refuses here at its bound with the paper's radius, not at the loop's slack
// past it nor along the stretch (bound_radius()): the loop's faces may pass the bound, and
// where they do the surface counts as blocked.
// check_collapse() only reads, so the faces are judged in parallel (a seventh of the
// adaptive bunny's loop, judged one by one), with this thread's floating-point settings
// (parallel_for_as_here()); the areas are summed in face order, so the share, and where
// the run halts, do not depend on the threads.
double Simplifier::blocked_share() {
  blocked_area_.assign(m_.face_capacity(), 0.0);
  parallel_for_as_here(tbb::blocked_range<Index>(0, m_.face_capacity(), 512), [&](const tbb::blocked_range<Index>& r) {
    for (Index f = r.begin(); f != r.end(); ++f) {
      if (!m_.is_face_live(f)) continue;
      bool refused = false, allowed = false;
      for (Index k = 0; k < 2 && !allowed; ++k) {
        Vec3 pos;
        SurfacePoint foot;
        const Verdict v = check_collapse(f, k, pos, foot, Bound::Halting);
        allowed = v == Verdict::Ok;
        refused |= v == Verdict::Fitmap || v == Verdict::Reach;
      }
      if (refused && !allowed) blocked_area_[f] = 0.5 * m_.face_area_normal(f).norm();
    }
  });
  double sum = 0;
  for (double a : blocked_area_) sum += a;
  return area_ > 0 ? sum / area_ : 0.0;
}

// A piece that cannot shrink to its share of the target (a speck of scan debris keeps one
// to eight quads whatever the target) was paid for by the others: bunny.ply with 300
// flakes of twelve triangles beside it, asked for 1,000 quads, came out as a bunny of 36
// quads beside 964 quads of flakes, and nothing said why. Each piece now stops at its
// share by area, as quads of one size would share it, and the run ends above the target
// (target_shortfall() says why; bench/RESULTS.md, "Pieces share the target").
void Simplifier::share_target(const std::vector<double>& area) {
  const Index pieces = Index(area.size());
  if (opt_.target_faces == 0 || pieces < 2) return;
  // A piece with fewer faces than its share keeps them, and the others share what is left
  // by area. The target alone hands them that surplus only while it is the count that
  // stops the run: beside debris that holds it above the target, each piece stops at its
  // share, and a coarse piece's unused share would be lost to the others. The pieces kept
  // are the sparsest (fewest faces per area): one pass in that order, however many pieces.
  std::vector<Index> order(pieces);
  std::iota(order.begin(), order.end(), Index(0));
  std::sort(order.begin(), order.end(), [&](Index x, Index y) {
    const double fx = double(piece_faces_[x]) * area[y], fy = double(piece_faces_[y]) * area[x];
    return fx != fy ? fx < fy : x < y;
  });
  double left = double(opt_.target_faces), open_area = 0;
  for (double a : area) open_area += a;
  std::vector<char> kept(pieces, 0);
  for (Index c : order) {
    if (!(double(piece_faces_[c]) * open_area <= left * area[c])) break;  // more faces than its share
    kept[c] = 1, left -= double(piece_faces_[c]), open_area -= area[c];
  }
  share_.resize(pieces);
  for (Index c = 0; c < pieces; ++c)
    share_[c] = kept[c] ? double(piece_faces_[c]) : open_area > 0 ? left * area[c] / open_area : 0.0;
  rep_.pieces = pieces;
}

// Each piece's faces, counted afresh into piece_faces_ (after_change() keeps the count
// only while there are shares), and its area, or with by_size its area in faces of the
// target sizes (over the square of the corners' mean size: faces per area go as
// 1 / size^2); `total` gets the sum over the mesh, added up face by face.
std::vector<double> Simplifier::count_pieces(bool by_size, double& total) {
  std::vector<double> sum(component_mu_.size(), 0.0);
  piece_faces_.assign(component_mu_.size(), 0);
  total = 0;
  for (Index f = 0; f < m_.face_capacity(); ++f)
    if (m_.is_face_live(f)) {
      double w = 0.5 * m_.face_area_normal(f).norm();
      if (by_size) {
        double size = 0;
        for (Index v : m_.face_vertices(f)) size += 0.25 * size_[v];
        w /= size * size;
      }
      const Index c = component_[m_.vertex(f, 0)];
      total += w, sum[c] += w, ++piece_faces_[c];
    }
  counted_faces_ = m_.n_faces();
  return sum;
}

// Automatic halting has no target to share (share_target()), and the halt is one measure
// over the whole surface: a piece the loop could not shrink kept what it had. Scan
// debris is such a piece, strips one quad wide that no diagonal collapse shrinks and
// whose chords ran only towards a target: pymeshlab's face range scan halted at 375
// quads, 109 of them on its 21 debris pieces (3% of its area; 32 at a target of 375).
// So once the run halts, each piece gets its share of the count reached, by its area in
// faces of its target sizes (count_pieces()); the loop then takes the pieces above
// theirs down towards it, chords included. Returns whether any piece is above.
bool Simplifier::share_halting_count() {
  const std::size_t pieces = component_mu_.size();
  if (pieces < 2) return false;
  double total = 0;
  const std::vector<double> weight = count_pieces(true, total);
  rep_.pieces = Index(pieces);
  share_.resize(pieces);
  bool above = false;
  for (std::size_t c = 0; c < pieces; ++c) {
    share_[c] = total > 0 ? double(m_.n_faces()) * weight[c] / total : double(piece_faces_[c]);
    above = above || double(piece_faces_[c]) > share_[c];
  }
  if (above) rebuild_heap();  // the debris' refused faces left the heap
  return above;
}

void Simplifier::add_faces_around(Index v, std::vector<Index>& faces) {
  if (v == kNone || !m_.is_vertex_live(v)) return;
  m_.for_each_outgoing(v, [&](Index h) { faces.push_back(QuadMesh::face(h)); });
}

void Simplifier::requeue_region() {
  ++stamp_;
  requeued_.clear();
  for (Index v : region_verts_) {
    if (!m_.is_vertex_live(v)) continue;
    m_.for_each_outgoing(v, [&](Index h) {
      const Index f = QuadMesh::face(h);
      if (face_mark_[f] == stamp_) return;
      face_mark_[f] = stamp_;
      requeued_.push_back(f);
    });
  }
  // In adaptive mode each key walks M0 from under the face's centre (s_weight()), and
  // those triangles missed the cache as the smoothing's did (prefetch_feet()).
  if (opt_.adaptive)
    for (Index f : requeued_) ref_.prefetch_triangle(centre_hint(f));
  for (Index f : requeued_) push_face(f);
}

void Simplifier::cycle(Index f, Index k, const Vec3& pos, const SurfacePoint& foot) {
  const Index b = m_.vertex(f, k + 1), c = m_.vertex(f, k + 2), d = m_.vertex(f, k + 3);
  const Index a = m_.vertex(f, k);
  const char held = held_[a] | held_[c];
  const bool c_kept = pinned(c);  // place() kept c's place (merge_keeps_tip())
  const Index v = collapse_diagonal(m_, f, k, pos);
  held_[v] = held;
  if (c_kept) inherit(v, c);
  record_foot(v, foot);
  ++rep_.collapses;
  after_change({v, b, d});
}

// Cleaning, rotations, smoothing and requeueing around vertices an operation changed.
void Simplifier::after_change(const Index* first, const Index* last) {
  region_faces_.clear();
  work_.assign(first, last);
  CleanCounts cc;
  clean_from(m_, work_, cc, &region_faces_, crease_.empty() ? nullptr : &on_crease_);
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
  if (has_border_)
    for (Index v : region_verts_) note_border(v);
  if (!share_.empty()) {  // every operation, and the cleaning after it, stays in one piece
    piece_faces_[component_[*first]] -= counted_faces_ - m_.n_faces();
    counted_faces_ = m_.n_faces();
  }
  if (opt_.check_invariants) check_invariants();
}

// Border coarsening visits only its candidates (border_candidates_): a vertex an
// operation brings to the border must be noted by after_change(), or it is never
// coarsened, and nothing else would show it. The same for the pieces' face counts.
void Simplifier::check_invariants(bool border_on_m0) {
  validate(m_);
  check_shared_diagonals();
  for (Index v = 0; v < m_.vertex_capacity(); ++v)
    if (m_.is_vertex_live(v) && m_.is_border_vertex(v) && !border_noted_[v])
      throw std::logic_error("simplify: border vertex " + std::to_string(v) + " is not a border-coarsening candidate");
  if (border_on_m0) check_border_on_m0();
  if (!crease_.empty()) check_creases();
  if (share_.empty()) return;
  std::vector<Index> faces(share_.size(), 0);
  for (Index f = 0; f < m_.face_capacity(); ++f)
    if (m_.is_face_live(f)) ++faces[component_[m_.vertex(f, 0)]];
  if (faces != piece_faces_) throw std::logic_error("simplify: the pieces' face counts are off");
}

// The operators make no shared diagonal; a merge may rename one (new_shared_diagonal()).
void Simplifier::check_shared_diagonals() {
  auto shared = shared_diagonals(m_);
  const auto [p, q] = new_shared_diagonal(m_, shared_, shared);
  if (p != kNone)
    throw std::logic_error("simplify: the corners " + std::to_string(p) + " and " + std::to_string(q) +
                           " of a diagonal share another quad, and no such diagonal was there before (" +
                           std::to_string(shared.size()) + " such diagonals now, " + std::to_string(shared_.size()) +
                           " at the last check)");
  shared_ = std::move(shared);
}

// Border vertices lie on M0's border: one left off it no longer slides along the border
// (a chord's open end once did that). Every border edge of M0 is tried: the check must
// not lean on the walk along the border it guards.
void Simplifier::check_border_on_m0() const {
  for (Index v = 0; v < m_.vertex_capacity(); ++v) {
    if (!m_.is_vertex_live(v) || !m_.is_border_vertex(v)) continue;
    const double gap = ref_.border_distance(m_.position(v));
    if (!(gap <= 1e-4 * ref_.mean_edge_length()))  // rounding: up to 1e-6 edges seen
      throw std::logic_error("simplify: border vertex " + std::to_string(v) + " is off M0's border by " +
                             std::to_string(gap / ref_.mean_edge_length()) + " input edges, at " +
                             std::to_string(m_.n_faces()) + " quads");
  }
}

// SimplifyOptions::keep_tips. The mesh's vertices are M0's own at the start (the
// conversion's pairs keep them), so a tip's vertex is the one whose foot is that corner.
void Simplifier::hold_tips() {
  const double count = opt_.target_faces > 0 ? double(opt_.target_faces) : rep_.predicted_faces;
  if (!opt_.keep_tips || !(count > 0)) return;
  const std::vector<Index> tips = find_tips(ref_.mesh(), tip_options_for(ref_.mesh(), count));
  if (tips.empty()) return;
  const TriMesh& t = ref_.mesh();
  for (Index v = 0; v < m_.vertex_capacity(); ++v) {
    if (!m_.is_vertex_live(v) || foot_face_[v] == kNone) continue;
    for (Index u : t.faces[foot_face_[v]])
      if (t.positions[u] == m_.position(v) && std::binary_search(tips.begin(), tips.end(), u)) held_[v] |= kHeldTip;
  }
}

SimplifyReport Simplifier::run() {
  const auto t0 = std::chrono::steady_clock::now();
  if (opt_.adaptive && (!opt_.fitmaps || opt_.fitmaps->s.size() != ref_.mesh().n_vertices() ||
                        opt_.fitmaps->m.size() != ref_.mesh().n_vertices()))
    throw std::invalid_argument("simplify: adaptive mode needs fitmaps computed on the reference surface");
  set_up();
  const bool halted = collapse_all();
  finish(halted);
  rep_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (opt_.progress && !rep_.cancelled) opt_.progress(1.f, "simplify");
  return rep_;
}

// The first cleaning, the per-vertex state, feet on M0, mu, the initial smoothing, the
// pieces' shares of the target and the heap.
void Simplifier::set_up() {
  // Crease vertices are known before the first cleaning, which must keep their doublets.
  held_.assign(m_.vertex_capacity(), 0);
  mark_creases();
  rep_.given_faces = m_.n_faces();
  const CleanCounts initial = clean_all(m_, crease_.empty() ? nullptr : &on_crease_);
  rep_.doublets += initial.doublets;
  rep_.singlets += initial.singlets;
  rep_.target_faces = opt_.target_faces;
  rep_.initial_faces = m_.n_faces();
  if (m_.face_capacity() > (Index(1) << 31))  // heap entries hold 2 face + k in 32 bits (Entry)
    throw std::length_error("simplify: over 2^31 quads");
  version_.assign(m_.face_capacity(), 0);
  face_mark_.assign(m_.face_capacity(), 0);
  vertex_mark_.assign(m_.vertex_capacity(), 0);
  foot_normal_.assign(m_.vertex_capacity(), Vec3::Zero());
  foot_face_.assign(m_.vertex_capacity(), kNone);
  centre_foot_.assign(m_.face_capacity(), kNone);
  size_.assign(m_.vertex_capacity(), 1.0);
  if (opt_.adaptive) {
    const SRange range = s_range(opt_.fitmaps->s, opt_.s_percentiles);
    s_lo_ = range.lo, s_mid_ = range.mid, s_hi_ = range.hi;
    s_foot_.assign(m_.vertex_capacity(), s_mid_);  // size 1 where a vertex has no foot
    reach_ = opt_.reach * ref_.bbox_diagonal();
    if (opt_.target_faces == 0) rep_.predicted_faces = predicted_halting_faces(ref_.mesh(), opt_, range);
    const double count = opt_.target_faces > 0 ? double(opt_.target_faces) : rep_.predicted_faces;
    if (opt_.max_aspect > 1 && count > 0) {
      anisotropy_ = anisotropy_for(ref_.mesh(), ref_.adjacency(), count, opt_.max_aspect);
      metric_.assign(m_.vertex_capacity(), {1.f, 0.f, 0.f, 1.f, 0.f, 1.f});  // where a vertex has no foot
    }
  }
  for (Index v = 0; v < m_.vertex_capacity(); ++v)
    if (m_.is_vertex_live(v)) {
      const SurfacePoint s = ref_.closest_within(m_.position(v), 0.0);  // M0's own vertices
      if (s.found()) record_foot(v, s);
    }
  hold_tips();
  if (opt_.check_invariants) shared_ = shared_diagonals(m_);
  border_noted_.assign(m_.vertex_capacity(), 0);
  for (Index v = 0; v < m_.vertex_capacity(); ++v) note_border(v);
  has_border_ = !border_candidates_.empty();
  if (opt_.check_invariants) check_invariants();
  component_mu_.assign(connected_components(m_, component_), 0.0);
  update_mu();
  // The conversion's flat quads at crease midpoints (ConvertReport::crease_midpoints) go
  // first: their straight angles are the worst quads the conversion leaves.
  if (!crease_.empty()) coarsen_creases();
  if (opt_.initial_sweeps > 0) {
    region_faces_.clear();
    for (Index f = 0; f < m_.face_capacity(); ++f)
      if (m_.is_face_live(f)) region_faces_.push_back(f);
    smooth_region(opt_.initial_sweeps);
    update_mu();
  }
  share_target(count_pieces(false, area_));
  rebuild_heap();
}

// Diagonal collapses from the heap until the target (or automatic halting), then chords
// and crease doublets while they let more pass; after automatic halting, the same for the
// pieces above their share of its count (share_halting_count()). Returns whether
// automatic halting stopped it.
bool Simplifier::collapse_all() {
  const Index target = opt_.target_faces;
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
  // until nothing is left instead).
  HaltingSchedule halting;
  halting.on = target == 0 && opt_.adaptive && opt_.halt_share < 1;
  halting.next_scan = std::isfinite(fine_above_) ? Index(std::min(fine_above_, double(m_.n_faces()))) : m_.n_faces();
  // The prediction can be far below where the run halts: where nothing faces away from
  // its fitted planes (a height field, a range scan) F_M is the largest radius everywhere
  // and the prediction a few faces, so neither the measure nor the full passes would start
  // before the run had collapsed all it could (a range scan of a face, pymeshlab's
  // sample, ran out at 146 quads, 2.6 times uniform mode's RMS; bench/RESULTS.md, "Range
  // scans and height fields"). A measure at every halving of the faces above the
  // predicted range brings both forward once the share is half way to the halt; it only
  // reads, so where the prediction holds the run is the same.
  halting.next_early = halting.on && m_.n_faces() / 2 > halting.next_scan ? m_.n_faces() / 2 : 0;
  // Where the input's own faces already reach F_M (a thin rim, noise) nothing will ever
  // coarsen; only what the collapses add counts towards the halt. A pancake's rim was
  // blocked over more than 15% of its area from the start, and it stopped after one
  // collapse (bench/RESULTS.md).
  halting.base_share = halting.on ? blocked_share() : 0.0;
  Index next_mu = 0;
  const bool halted = collapse_until(halting, next_mu);
  rep_.ran_out = halting.on && !halted && !rep_.cancelled;
  if (target == 0 && !rep_.cancelled && share_halting_count()) {
    halting.on = false;
    collapse_until(halting, next_mu);
  }
  return halted;
}

// The loop of collapse_all(): diagonal collapses from the heap until the target (or
// automatic halting's measure), then crease doublets and chords while they let more
// pass. Returns whether automatic halting stopped it.
bool Simplifier::collapse_until(HaltingSchedule& halting, Index& next_mu) {
  const Index target = opt_.target_faces;
  const Index span = rep_.initial_faces > target ? rep_.initial_faces - target : 1;
  bool halted = false;
  for (;;) {
    while (m_.n_faces() > target && !heap_.empty()) {
      std::pop_heap(heap_.begin(), heap_.end(), LaterFirst{});
      const Entry e = heap_.back();
      heap_.pop_back();
      const Index f = e.face(), k = e.k();
      if (!m_.is_face_live(f) || e.version != version_[f]) continue;
      if (piece_room(m_.vertex(f, 0)) <= 0) continue;  // its piece has its share (share_target())
      Vec3 pos;
      SurfacePoint foot;
      // A refused face comes back only when something around it changes.
      const Verdict verdict = check_collapse(f, k, pos, foot, Bound::Loop);
      if (verdict != Verdict::Ok) {
        count_refusal(verdict);
        continue;
      }
      cycle(f, k, pos, foot);
      if (halting.on && m_.n_faces() <= std::max(halting.next_scan, halting.next_early) &&
          (halted = halting_due(halting)))
        break;
      upkeep(next_mu);
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
    // Crease doublets the last collapses left; their removal may let more collapses pass.
    if (!crease_.empty() && !halted && !rep_.cancelled && m_.n_faces() > target && coarsen_creases()) continue;
    if (!opt_.chord_collapses || (target == 0 && share_.empty()) || m_.n_faces() <= target || rep_.cancelled ||
        !collapse_chords())
      break;
  }
  return halted;
}

// Automatic halting's measure, at a face count its schedule has reached: true when the
// faces the M-fitmap blocks have grown by the halting share.
bool Simplifier::halting_due(HaltingSchedule& h) {
  rep_.blocked_share = blocked_share();
  const double added = rep_.blocked_share - h.base_share;
  // Above the predicted range: the schedule starts here once the share is half way to the
  // halt; until then the next halving is measured.
  if (m_.n_faces() > h.next_scan && added >= 0.5 * opt_.halt_share) fine_above_ = double(h.next_scan = m_.n_faces());
  h.next_early = m_.n_faces() / 2 > h.next_scan ? m_.n_faces() / 2 : 0;
  if (m_.n_faces() > h.next_scan) return false;
  if (added >= opt_.halt_share) return true;
  // The share grows smoothly as the faces grow: measured again after a step of the faces
  // that shrinks to 1% as it nears the halting share (about 15 measures a run).
  const double step = std::clamp(0.25 * (1 - added / opt_.halt_share), 0.01, 0.25);
  h.next_scan = Index(double(m_.n_faces()) * (1 - step));
  return false;
}

// What the loop does every so many collapses: border and crease coarsening, mu's recount
// and the heap's rebuild.
void Simplifier::upkeep(Index& next_mu) {
  if (has_border_ && opt_.coarsen_border && !opt_.preserve_boundary && rep_.collapses % 64 == 0) coarsen_border();
  if (!crease_.empty() && rep_.collapses % 64 == 0) coarsen_creases();
  if (rep_.collapses >= next_mu) {
    // mu drifts slowly: an exact recount every 256 collapses is cheaper than tracking every
    // edge each operation touches, and as accurate, if it comes after at least 2% of the
    // faces (mu moves ~1%) and at most a tenth (~5%). Without that upper bound a 900-quad
    // grid simplified to 50 left mu far behind: the border (coarsened below 1.3 mu) kept
    // most of its edges, the target was missed at 70 quads, and quads spanned the grid.
    update_mu();
    next_mu = rep_.collapses + std::clamp<Index>(256, m_.n_faces() / 50, std::max<Index>(1, m_.n_faces() / 10));
  }
  if (heap_.size() > kHeapPerFace * std::size_t(m_.n_faces()) + kHeapExtra) rebuild_heap();
}

// After the loop: the pieces above their share, the last measures, the unfolding (uniform
// mode), the border's inset, and the report's counts.
void Simplifier::finish(bool halted) {
  for (std::size_t c = 0; c < share_.size(); ++c)
    if (double(piece_faces_[c]) > share_[c]) ++rep_.pieces_above_share, rep_.faces_above_share += piece_faces_[c];
  if (opt_.adaptive && !halted) rep_.blocked_share = blocked_share();
  if (opt_.unfold && !opt_.refuse_folds && !rep_.cancelled) unfold();
  // Last: the unfolding smooths, and a border vertex the inset has moved off M0's border
  // no longer slides along it. When the inset came first, bunny.ply with 0.1% of its
  // triangles taken out, stopping at 295 quads, ended with one 8.4 input edges off it.
  if (has_border_ && opt_.inset_border && !opt_.preserve_boundary && !rep_.cancelled) inset_border();
  if (opt_.adaptive) rep_.beyond_reach_faces = faces_beyond_reach();
  if (opt_.check_invariants) check_invariants(rep_.border_insets == 0);  // the inset moves them off on purpose
  for (Index v = 0; v < m_.vertex_capacity(); ++v) {
    if (!m_.is_vertex_live(v)) continue;
    rep_.tips += (held_[v] & kHeldTip) != 0;
    rep_.crease_vertices += !on_crease_.empty() && on_crease_[v];
  }
  std::vector<Index> face_map;
  m_.compact(nullptr, &face_map);
  for (Index& f : rep_.beyond_reach_faces) f = face_map[f];  // compact() keeps the faces' order
  rep_.faces = m_.n_faces();
}

}  // namespace detail

SimplifyReport simplify(QuadMesh& mesh, const ReferenceSurface& ref, const SimplifyOptions& options) {
  return detail::Simplifier(mesh, ref, options).run();
}

}  // namespace qs
