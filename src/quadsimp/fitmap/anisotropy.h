// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <vector>

#include "quadsimp/mesh/tri_mesh.h"

namespace qs {

//! A metric on the reference surface under which the adaptive mode's quads are long along
//! the surface's flatter direction and short across its most curved one (ours: the paper's
//! quads are as square as its smoothing makes them). A quad's error across a direction of
//! curvature k and length h grows as k h^2, so at a given count the error is least when the
//! sides follow the principal directions with lengths in the ratio sqrt(k1 / k2).
struct Anisotropy {
  //! Per vertex, the symmetric metric G as xx, xy, xz, yy, yz, zz: a vector d is
  //! sqrt(d^T G d) long under it. G = s t1 t1^T + t2 t2^T / s + n n^T, t1 the most curved
  //! direction, so G keeps areas. Empty: no anisotropy.
  std::vector<std::array<float, 6>> g;
  bool empty() const { return g.empty(); }
};

//! The metric at every vertex of a clean triangle mesh, from the triangles' normals within
//! `radius` (the part of the ball connected to the vertex on the surface, as the fitmaps
//! take it, on cells of a quarter of the radius): the tangential part of their
//! area-weighted second moment has eigenvalues l1 >= l2, the mean squares of the normals'
//! turn, k1 x and k2 x, so the stretch is s = sqrt(k1 / k2) = (l1 / l2)^(1/4), at most
//! `max_aspect`. Flat or evenly curved places (l1 = l2) get s = 1. In parallel (TBB).
//! `adjacency` is the mesh's triangle_adjacency() (the reference surface holds it).
Anisotropy compute_anisotropy(const TriMesh& mesh, const std::vector<std::array<Index, 3>>& adjacency,
                              double radius, double max_aspect);
//! The metric adaptive mode takes for a result of about `quads` quads: within twice the
//! side of `quads` squares covering the mesh.
Anisotropy anisotropy_for(const TriMesh& mesh, const std::vector<std::array<Index, 3>>& adjacency, double quads,
                          double max_aspect);

//! What the metric says at one vertex: quads there may be `aspect` times longer (s) along
//! `along` (t2, a unit vector) than across it; `along` is zero where aspect is at most
//! kLeastStretch.
struct Stretch {
  double aspect = 1;
  Vec3 along = Vec3::Zero();
};
//! Below this aspect t2 is float noise, and Stretch::along is left zero.
constexpr double kLeastStretch = 1.001;
Stretch stretch_at(const Anisotropy& a, Index v);

}  // namespace qs
