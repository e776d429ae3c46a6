// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// Spring smoothing [paper 3.2]: tangential relaxation of the zone around each change,
// every moved vertex re-projected onto M0.
#include "quadsimp/simplify/simplifier.h"

#include <algorithm>
#include <cmath>

#include "quadsimp/mesh/quad_geometry.h"

namespace qs::detail {

namespace {

// Where a spring of length `rest` from q would put p, given the length l of d = p - q:
// at q + rest d / l, in p's direction (p itself when they coincide). With anisotropy l is
// d's length under the metric, so the spring rests longer along the flatter direction.
Vec3 spring_point(const Vec3& p, const Vec3& q, const Vec3& d, double l, double rest) {
  return l > 0 ? Vec3(q + rest * d / l) : p;  // not an absolute tolerance: lengths have units
}

}  // namespace

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
// With anisotropy (SimplifyOptions::max_aspect) springs rest at their length under the
// metric of their two ends (spring_point()).
void Simplifier::smooth_vertex(Index v) {
  ++rep_.relaxations;
  const Vec3 p = m_.position(v);
  const bool border = m_.is_border_vertex(v);
  if ((border && (opt_.preserve_boundary || is_border_corner(v))) || held_[v]) return;
  // One fan walk gives the springs' fixed point and the vertex normal (the sum of the
  // faces' diagonal cross products).
  Vec3 sum = Vec3::Zero(), area_normal = Vec3::Zero();
  double w = 0;
  auto spring = [&](Index u, double rest, double weight) {
    const Vec3& q = m_.position(u);
    const Vec3 d = p - q;
    const double l = anisotropy_.empty() ? d.norm() : std::sqrt(metric_length2(v, u, d));
    sum += weight * spring_point(p, q, d, l, rest);
    w += weight;
  };
  m_.for_each_outgoing(v, [&](Index h) {
    // Per face: two edge springs (each edge is shared by two faces) and one diagonal.
    const Index i1 = m_.to(h), id = m_.to(QuadMesh::next(h)), i2 = m_.from(QuadMesh::prev(h));
    const Vec3 &e1 = m_.position(i1), &dg = m_.position(id), &e2 = m_.position(i2);
    area_normal += (dg - p).cross(e2 - e1);
    spring(i1, rest_length(v, i1), 0.5);
    spring(i2, rest_length(v, i2), 0.5);
    spring(id, kSqrt2 * rest_length(v, id), 1.0);
  });
  if (!crease_.empty() && crease_[v] != kNone) {
    slide_on_crease(v, sum / w);
    return;
  }
  Vec3 step, n = Vec3::Zero();
  // A border vertex slides along M0's border no further than its border neighbours.
  // Sliding past one, across a crack of bunny.ply, reversed the border's order there at
  // 8 of 38 counts from 1.5K to 20K quads, and left a quad stretched over the hole:
  // non-convex, flipped or folded at 2 of them, with homeometry under 0.3 at 5 more.
  ReferenceSurface::BorderArc arc;
  if (border) {
    // The same springs (the border edges, in one face only, get their other half), and
    // the step along the border only. Springs to the two border neighbours alone left
    // the interior edges of border vertices free to stretch: bunny.ply at 5K had a
    // border quad with edges of 0.50 and 2.48 mu.
    const Index ia = m_.next_on_border(v), ib = m_.prev_on_border(v);
    const Vec3 a = m_.position(ia), b = m_.position(ib);
    spring(ia, rest_length(v, ia), 0.5);
    spring(ib, rest_length(v, ib), 0.5);
    const Vec3 t = (b - a).normalized();
    step = (sum / w - p).dot(t) * t;
    arc = {p, a, b};
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
      // Where none is found (no border edge under v's foot), v stays: M0's closest point,
      // the old fallback, leaves the border. Neither the tests nor any dataset run got here.
      foot = ref_.closest_on_border(foot_face_[v], target, 4 * mu_, arc);
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
  prefetch_feet();
  for (int sweep = 0; sweep < sweeps; ++sweep)
    for (Index v : region_verts_) smooth_vertex(v);
}

// The triangles under the region's vertices lie anywhere in M0's arrays, and on large
// inputs each first read of one missed the cache: the walks of the first sweep stalled on
// them one after the other (project_near() was 16% of a uniform run of 1.1 million
// triangles). Asked for all at once, their fetches overlap.
void Simplifier::prefetch_feet() const {
  for (Index v : region_verts_) ref_.prefetch_triangle(foot_face_[v]);
  // Then their corners, whose numbers the first fetches brought.
  for (Index v : region_verts_) ref_.prefetch_corners(foot_face_[v]);
}

}  // namespace qs::detail
