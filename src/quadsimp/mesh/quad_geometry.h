// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// Small geometric predicates on quads given by their four corner positions.
#pragma once

#include <algorithm>
#include <cmath>

#include "quadsimp/util/types.h"

namespace qs {

//! A square's diagonal over its side: homeometry and the springs compare diagonals to it.
inline constexpr double kSqrt2 = 1.4142135623730951;

//! Twice the vector area of the quad (cross product of its diagonals).
inline Vec3 quad_normal(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3) {
  return (p2 - p0).cross(p3 - p1);
}

//! False when the quad's normal turns by 90 degrees or more from `reference`, or
//! (nearly) vanishes relative to it: the quad would be folded or degenerate.
inline bool keeps_orientation(const Vec3& n, const Vec3& reference) {
  return n.dot(reference) > 0 && n.squaredNorm() > 1e-24 * reference.squaredNorm();
}
inline bool quad_keeps_orientation(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3,
                                   const Vec3& reference) {
  return keeps_orientation(quad_normal(p0, p1, p2, p3), reference);
}

//! True when every corner turns the same way as the quad's normal n (the cross of its
//! diagonals): convex in its own (best) plane.
inline bool quad_is_convex(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3, const Vec3& n) {
  const Vec3 e0 = p1 - p0, e1 = p2 - p1, e2 = p3 - p2, e3 = p0 - p3;
  return e3.cross(e0).dot(n) > 0 && e0.cross(e1).dot(n) > 0 && e1.cross(e2).dot(n) > 0 && e2.cross(e3).dot(n) > 0;
}
inline bool quad_is_convex(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3) {
  return quad_is_convex(p0, p1, p2, p3, quad_normal(p0, p1, p2, p3));
}

//! True when the quad bends by more than 90 degrees whichever diagonal splits it: the
//! normals of its two triangles point apart for both splits (no square roots).
inline bool quad_folds(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3) {
  return (p1 - p0).cross(p2 - p0).dot((p2 - p0).cross(p3 - p0)) < 0 &&
         (p1 - p0).cross(p3 - p0).dot((p2 - p1).cross(p3 - p1)) < 0;
}

//! Cosine of the angle between the normals of the quad's two triangles, for the
//! diagonal that bends it least: 1 when planar, below 0 when quad_folds().
inline double quad_fold_cos(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3) {
  auto cos_between = [](const Vec3& a, const Vec3& b) {
    const double d = std::sqrt(a.squaredNorm() * b.squaredNorm());
    return d > 0 ? a.dot(b) / d : 1.0;
  };
  return std::max(cos_between((p1 - p0).cross(p2 - p0), (p2 - p0).cross(p3 - p0)),
                  cos_between((p1 - p0).cross(p3 - p0), (p2 - p1).cross(p3 - p1)));
}

//! The same two for a quad given by its corner ids into `pos` (a mesh's positions()).
template <class Positions, class Corners>
bool quad_folds(const Positions& pos, const Corners& c) {
  return quad_folds(pos[c[0]], pos[c[1]], pos[c[2]], pos[c[3]]);
}
template <class Positions, class Corners>
double quad_fold_cos(const Positions& pos, const Corners& c) {
  return quad_fold_cos(pos[c[0]], pos[c[1]], pos[c[2]], pos[c[3]]);
}

//! The fold rule of the checks: the quad folds (quad_folds()) and bends further than
//! `before()`, a quad_fold_cos() each caller takes from its own "before" (the face now,
//! the more bent of two faces, the face at the start). The cheap sign test goes first,
//! and `before` is called only when it fires: almost no quad folds.
template <class Before>
bool quad_folds_further(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3, Before&& before) {
  return quad_folds(p0, p1, p2, p3) && quad_fold_cos(p0, p1, p2, p3) < before();
}

}  // namespace qs
