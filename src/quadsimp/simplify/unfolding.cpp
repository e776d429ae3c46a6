// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// Unfolding of quads bent past 90 degrees after the loop (ours; SimplifyOptions::unfold).
#include "quadsimp/simplify/simplifier.h"

#include <algorithm>

#include "quadsimp/mesh/quad_geometry.h"

namespace qs::detail {

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
// armadillo at 3,000 quads got an edge of 0.09 mu when it came in (eighth stop; since
// then the loop changed, and over 20 uniform runs of six models the bound changes three,
// with a longest edge of 2.31 against 2.59 mu on the worst, the armadillo at 2,000, but
// a shortest of 0.24 against 0.34); without the smoothing after it, a gargoyle run left
// [0.5, 2] mu (bench/RESULTS.md).
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
    if (m_.is_border_vertex(v) || pinned(v)) continue;
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

}  // namespace qs::detail
