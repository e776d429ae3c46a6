// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// Small geometric predicates on quads given by their four corner positions.
#pragma once

#include "quadsimp/util/types.h"

namespace qs {

//! Twice the vector area of the quad (cross product of its diagonals).
inline Vec3 quad_normal(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3) {
  return (p2 - p0).cross(p3 - p1);
}

//! False when the quad's normal turns by 90 degrees or more from `reference`, or
//! (nearly) vanishes relative to it: the quad would be folded or degenerate.
inline bool quad_keeps_orientation(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3,
                                   const Vec3& reference) {
  const Vec3 n = quad_normal(p0, p1, p2, p3);
  return n.dot(reference) > 0 && n.squaredNorm() > 1e-24 * reference.squaredNorm();
}

//! True when every corner turns the same way as the quad's normal: convex in its
//! own (best) plane.
inline bool quad_is_convex(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3) {
  const Vec3 p[4] = {p0, p1, p2, p3};
  const Vec3 n = quad_normal(p0, p1, p2, p3);
  for (int k = 0; k < 4; ++k)
    if ((p[(k + 1) % 4] - p[k]).cross(p[(k + 3) % 4] - p[k]).dot(n) <= 0) return false;
  return true;
}

}  // namespace qs
