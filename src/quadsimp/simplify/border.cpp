// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// Border vertices: their target valences, the corners smoothing pins, and border
// coarsening (ours; ops/border_ear.h).
#include "quadsimp/simplify/simplifier.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "quadsimp/mesh/quad_geometry.h"
#include "quadsimp/metrics/metrics.h"
#include "quadsimp/ops/border_ear.h"
#include "quadsimp/ops/diagonal_collapse.h"
#include "quadsimp/ops/local_rewrite.h"

namespace qs::detail {
namespace {

// A border vertex is removed when its two border edges add up to less than this many
// mu. Measured on bunny.ply at 3K/5K/11K quads: 1.0 left homeometry minima of
// 0.46/0.30/0.44, 1.3 gives 0.53/0.52/0.44 with the same RMS, 1.6 starts to stretch
// border faces (maximum 3.09 at 5K).
constexpr double kBorderShort = 1.3;

}  // namespace

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
  return {(p - m_.position(m_.prev_on_border(v))).normalized(), (m_.position(m_.next_on_border(v)) - p).normalized()};
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
  if (held_[v]) return true;  // where a crease meets the border
  const double t = border_turn(v);
  if (t <= M_PI / 4) return false;
  // A piece of one quad: its corners all turn alike and pass neither test below, and the
  // springs slid two of them together (a strip asked for one quad ended a triangle).
  if (m_.valence(v) == 2) {
    const Index f = QuadMesh::face(m_.out(v));
    bool alone = true;
    for (Index k = 0; k < 4; ++k) alone &= m_.is_border_halfedge(QuadMesh::halfedge(f, k));
    if (alone) return true;
  }
  const Index next = m_.next_on_border(v), prev = m_.prev_on_border(v);
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
  return strip_end(next, t_next, t_prev, m_.next_on_border(next)) ||
         strip_end(prev, t_prev, t_next, m_.prev_on_border(prev));
}

// Border coarsening (ours; see ops/border_ear.h). A border vertex b whose two border
// edges are short next to mu is removed: the interior edge at b is rotated so that b's
// only face is an ear, then the ear collapses with the merged vertex at b (on M0's
// border). Nothing happens unless both steps pass their checks; a rotation whose ear
// is refused is undone.
void Simplifier::coarsen_border() {
  // The list is taken first, in id order: removals kill vertices and move others to the
  // border. Candidates no longer on it are dropped.
  border_verts_.clear();
  std::size_t kept = 0;
  for (Index v : border_candidates_) {
    if (m_.is_vertex_live(v) && m_.is_border_vertex(v))
      border_candidates_[kept++] = v, border_verts_.push_back(v);
    else
      border_noted_[v] = 0;
  }
  border_candidates_.resize(kept);
  std::sort(border_verts_.begin(), border_verts_.end());
  for (Index b : border_verts_)
    if (m_.is_vertex_live(b) && m_.is_border_vertex(b) && piece_room(b) > 0) remove_border_vertex(b);
}

// Which of border vertices a and c keeps its place when they merge: a border corner
// (`corner`, kNone if neither is one; false if both are). Merging at the middle cut the
// corners of an L-shaped grid by a third of mu (border coarsening) and took half a quad
// off a strip's ends at every chord there.
bool Simplifier::border_merge_corner(Index a, Index c, Index& corner) const {
  const bool corner_a = is_border_corner(a), corner_c = is_border_corner(c);
  corner = corner_a ? a : corner_c ? c : kNone;
  return !(corner_a && corner_c);
}

// The point of M0's border nearest p, on the stretch between border neighbours a and b
// (a chord's open end). M0's point nearest p lies inside wherever the border bends
// between them, and a border vertex left there no longer slides along the border: open
// spiky spheres taken down to 8-40 quads kept border vertices up to an input edge off it.
SurfacePoint Simplifier::border_point_between(Index a, Index b, const Vec3& p) const {
  const Vec3 &pa = m_.position(a), &pb = m_.position(b);
  ReferenceSurface::BorderArc arc{pa, pa, pa};  // from a, and not back past it
  if (m_.next_on_border(a) == b)
    arc.ahead = pb;
  else if (m_.prev_on_border(a) == b)
    arc.behind = pb;
  else
    return {};
  return ref_.closest_on_border(foot_face_[a], p, 2 * (pb - pa).norm() + 4 * mu_, arc);
}

bool Simplifier::remove_border_vertex(Index b) {
  const Index out = m_.out(b), ha = m_.border_in(b);  // b -> c and a -> b, both on the border
  const Index a = m_.from(ha), c = m_.to(out);
  const double ab = (m_.position(a) - m_.position(b)).norm(), bc = (m_.position(b) - m_.position(c)).norm();
  const int valence = m_.valence(b);
  if (ab + bc >= kBorderShort * mu_at(b) || valence > 3 || pinned(b)) return false;
  // a, b and c merge into one vertex, at b unless a or c is a corner.
  Index corner;
  if (!border_merge_corner(a, c, corner)) return false;
  const Vec3 keep = m_.position(corner != kNone ? corner : b);
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
  const RotationUndo undo = rotation_undo(m_, h);
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
    for (Index f : undo.faces)
      for (Index i = 0; i < 4; ++i)
        if (m_.vertex(f, i) == b) ear = f, k = i;
    if (ear != kNone && try_ear(ear, k)) return true;
    undo_rotation(m_, undo);
  }
  return false;
}

// Border inset (ours). Border vertices lie on M0's border, and the edge between two of
// them cuts across the notches of the outline between them. A range scan's outline is
// ragged at the scale of its grid: on the cleaned face range scan at 400 quads, 2.1% of
// the result missed the input along its normals, all within 0.75 mu of the border, 90%
// within a quarter mu, most within one input edge outside the outline. So a border vertex
// whose border edges miss the input moves inwards on M0, across the border, by the least
// of a few steps that brings them over it, or by the step that leaves the fewest misses.
// The steps stop at one mean edge of the input (taken in the tangent plane, then onto M0:
// where the surface bends at the border a vertex can end a little further from it, 1.003
// edges on bunny.ply, 1.054 on an open spiky sphere); allowed two, the outline the quads
// leave uncovered raised that scan's Hausdorff distance by half at 1,400 quads
// (bench/RESULTS.md, "The border moved inwards"). Sliding along the border instead did a
// fifth to a third as much.
void Simplifier::inset_border() {
  constexpr int kSweeps = 3, kSteps = 4;
  update_mu();  // keeps_lengths() compares with it: the loop's may be 256 collapses old
  // No inset folds a quad further, in uniform mode too (as unfold() does): it is a
  // small move that never needs one, and the first version, unchecked, left one.
  refuse_folds_ = true;
  // Each vertex's place on M0's border and its way inwards stay those before the first
  // sweep, so that no sweep takes a vertex further than kSteps steps.
  struct Start {
    Index v;
    Vec3 from, in;
    bool moved;
  };
  std::vector<Start> border;
  for (Index v = 0; v < m_.vertex_capacity(); ++v) {
    if (!m_.is_vertex_live(v) || !m_.is_border_vertex(v) || pinned(v)) continue;
    const Vec3& p = m_.position(v);
    const Vec3 along = m_.position(m_.next_on_border(v)) - m_.position(m_.prev_on_border(v));
    Vec3 across = foot_normal_[v].cross(along);
    if (!(across.squaredNorm() > 0)) continue;  // a loop of two edges has no inwards
    across.normalize();
    Vec3 towards = Vec3::Zero();
    m_.for_each_outgoing(v, [&](Index h) { towards += m_.position(m_.to(h)) - p; });
    border.push_back({v, p, across.dot(towards) < 0 ? -across : across, false});
  }
  for (int sweep = 0; sweep < kSweeps; ++sweep) {
    bool moved = false;
    for (Start& b : border) {
      int fewest = border_misses(b.v, m_.position(b.v));
      SurfacePoint best;
      const double step = std::min(ref_.mean_edge_length(), mu_at(b.v)) / kSteps;
      for (int k = 1; k <= kSteps && fewest > 0; ++k) {
        const SurfacePoint foot = ref_.closest_within(b.from + k * step * b.in, k * step);
        if (!foot.found() || !moved_faces_ok(b.v, foot.point) || !keeps_lengths(b.v, foot.point)) continue;
        if (const int misses = border_misses(b.v, foot.point); misses < fewest) fewest = misses, best = foot;
      }
      if (!best.found()) continue;
      m_.position(b.v) = best.point;
      record_foot(b.v, best);
      b.moved = moved = true;
    }
    if (!moved) break;
  }
  for (const Start& b : border) rep_.border_insets += b.moved;
  refuse_folds_ = opt_.refuse_folds;
}

// Whether moving v to p keeps its edges within half and twice their rest length and its
// faces' diagonals within those times sqrt(2), or brings them closer to that: Table 1's
// bound on homeometry. Moved by one input edge, the border vertices of bunny.ply's holes
// at 11,000 quads left an edge of 0.26 mu.
bool Simplifier::keeps_lengths(Index v, const Vec3& p) const {
  bool ok = true;
  m_.for_each_outgoing(v, [&](Index h) {
    const Index f = QuadMesh::face(h), k = QuadMesh::corner(h);
    for (Index i = 1; i < 4 && ok; ++i) {
      const Index w = m_.vertex(f, k + i);
      const double rest = (i == 2 ? kSqrt2 : 1.0) * rest_length(v, w);
      const double before = (m_.position(v) - m_.position(w)).norm() / rest, after = (p - m_.position(w)).norm() / rest;
      ok = !((after < 0.5 && after < before) || (after > 2 && after > before));
    }
  });
  return ok;
}

// How many points along border vertex v's two border edges, with v at p, miss M0 along
// their face's normal within the projectability measure's reach (kProjectabilityReach). The points
// sit a tenth of an input edge inwards: from the edge itself, rays missed along smooth
// outlines too, where the edge rises off a curved rim (the bowl of the CLI's crack test,
// whose border then left the outline), and along straight ones by rounding.
int Simplifier::border_misses(Index v, const Vec3& p) const {
  constexpr int kPoints = 8;
  const double inwards = 0.1 * ref_.mean_edge_length();
  const double reach = kProjectabilityReach * ref_.bbox_diagonal();
  int misses = 0;
  for (const Index h : {m_.border_in(v), m_.out(v)}) {
    const Index f = QuadMesh::face(h);
    Vec3 q[4];
    for (Index i = 0; i < 4; ++i) q[i] = m_.vertex(f, i) == v ? p : m_.position(m_.vertex(f, i));
    const Vec3 n = quad_normal(q[0], q[1], q[2], q[3]).normalized();
    const Vec3 centre = 0.25 * (q[0] + q[1] + q[2] + q[3]);
    const Vec3 a = m_.from(h) == v ? p : m_.position(m_.from(h)), b = m_.to(h) == v ? p : m_.position(m_.to(h));
    for (int i = 0; i < kPoints; ++i) {
      const Vec3 x = a + (i + 0.5) / kPoints * (b - a);
      const Vec3 to_centre = centre - x;
      const double l = to_centre.norm();
      misses += !ref_.ray_project(x + std::min(inwards / l, 0.25) * to_centre, n, reach).found();
    }
  }
  return misses;
}

}  // namespace qs::detail
