// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// Whether a face may take new corner positions: orientation against M0 and itself,
// convexity and folds, for every move the loop, smoothing and the other steps make.
#include "quadsimp/simplify/simplifier.h"

#include <algorithm>
#include <limits>

#include "quadsimp/mesh/quad_geometry.h"

namespace qs::detail {

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
// it and like itself before, a convex face stays convex, and with refuse_folds no face
// bends further past 90 degrees. Over a folded-over patch of M0
// (ReferenceSurface::is_flap, over_flap()) a face that did not follow the reference
// need not start to: the working mesh follows the fold at first, and while it had to,
// no move there passed (glmark2's bunny split to 1.1M triangles, at 20,000 quads: 2
// flipped quads and a diagonal of 0.04 mu left at the fold).
bool Simplifier::shape_ok(Index f, const Vec3* q, const Vec3& extra_normal) const {
  // The hottest check of the run (every smoothing move): one normal, no square roots.
  const Vec3 n = quad_normal(q[0], q[1], q[2], q[3]);
  if (!keeps_orientation(n, m_.face_area_normal(f))) return false;
  const auto c = m_.face_vertices(f);
  const auto p = m_.positions_of(c);
  if (!follows_reference(n, c, q, extra_normal) &&
      !(over_flap(c) && !follows_reference(quad_normal(p[0], p[1], p[2], p[3]), c, p.data(), Vec3::Zero())))
    return false;
  if (!quad_is_convex(q[0], q[1], q[2], q[3], n) && quad_is_convex(p[0], p[1], p[2], p[3])) return false;
  return !(refuse_folds_ &&
           quad_folds_further(q[0], q[1], q[2], q[3], [&] { return quad_fold_cos(p[0], p[1], p[2], p[3]); }));
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
// Border vertices are held to refuse_folds like the others. Exempt (a border edge of
// bunny.ply once shrank to 0.38 mu at 11K quads when held), they folded quads at the
// holes of damaged scans in adaptive mode, which promises none: bunny.ply with 5% of its
// triangles taken out, 12 folded quads at 7,410 (none now). bunny.ply's own adaptive runs
// are the same but at 600 quads (bench/RESULTS.md).
bool Simplifier::moved_faces_ok(Index v, const Vec3& p) const {
  const Vec3& before = m_.position(v);
  auto comes_within = [&](Index e, double share) {
    const double near = share * rest_length(v, e);
    const double after2 = (p - m_.position(e)).squaredNorm();
    return after2 < near * near && after2 < (before - m_.position(e)).squaredNorm();
  };
  if (m_.is_border_vertex(v) && comes_within(m_.prev_on_border(v), 0.1)) return false;
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
    ok = shape_ok(f, q, Vec3::Zero());
  });
  return ok;
}

}  // namespace qs::detail
