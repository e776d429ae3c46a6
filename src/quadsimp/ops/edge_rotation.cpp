// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/ops/edge_rotation.h"

#include <algorithm>
#include <cassert>

#include "quadsimp/mesh/quad_geometry.h"
#include "quadsimp/ops/local_rewrite.h"

namespace qs {
namespace {

struct Hexagon {
  Index u, w, x1, x2, y1, y2;
  Index f1, f2;
};

Hexagon hexagon(const QuadMesh& m, Index h) {
  const Index g = m.twin(h);
  Hexagon x;
  x.f1 = QuadMesh::face(h);
  x.f2 = QuadMesh::face(g);
  x.u = m.from(h);
  x.w = m.to(h);
  x.x1 = m.to(QuadMesh::next(h));
  x.x2 = m.from(QuadMesh::prev(h));
  x.y1 = m.to(QuadMesh::next(g));
  x.y2 = m.from(QuadMesh::prev(g));
  return x;
}

int min_valence(const QuadMesh& m, Index v) { return m.is_border_vertex(v) ? 2 : 3; }

}  // namespace

std::array<std::array<Index, 4>, 2> rotated_faces(const QuadMesh& m, Index h, Rotation r) {
  const Hexagon x = hexagon(m, h);
  if (r == Rotation::Ccw) return {{{x.x1, x.x2, x.u, x.y1}, {x.y1, x.y2, x.w, x.x1}}};
  return {{{x.x2, x.u, x.y1, x.y2}, {x.y2, x.w, x.x1, x.x2}}};
}

std::array<Index, 2> rotated_edge(const QuadMesh& m, Index h, Rotation r) {
  const Hexagon x = hexagon(m, h);
  return r == Rotation::Ccw ? std::array<Index, 2>{x.x1, x.y1} : std::array<Index, 2>{x.x2, x.y2};
}

bool can_rotate_edge(const QuadMesh& m, Index h, Rotation r, Index doublet) {
  if (h >= m.halfedge_capacity() || !m.is_face_live(QuadMesh::face(h)) || m.twin(h) == kNone) return false;
  const Hexagon x = hexagon(m, h);
  if (x.f1 == x.f2) return false;
  std::array<Index, 6> c = {x.u, x.w, x.x1, x.x2, x.y1, x.y2};
  std::sort(c.begin(), c.end());
  if (std::adjacent_find(c.begin(), c.end()) != c.end()) return false;
  auto least = [&](Index v) { return v == doublet ? 2 : min_valence(m, v); };
  if (m.valence(x.u) - 1 < least(x.u) || m.valence(x.w) - 1 < least(x.w)) return false;
  // The new edge would be doubled. Two corners that end up opposite in a new face and
  // already share another face would make two quads touch at two corners without the
  // edge between them (see shared_diagonals).
  const Index p = r == Rotation::Ccw ? x.x1 : x.x2, q = r == Rotation::Ccw ? x.y1 : x.y2;
  if (share_a_face(m, p, q, x.f1, x.f2)) return false;
  for (const auto& n : rotated_faces(m, h, r)) {
    // A doublet's two faces have the same opposite corners, its neighbours.
    if (doublet != kNone && std::find(n.begin(), n.end(), doublet) != n.end()) continue;
    if (share_a_face(m, n[0], n[2], x.f1, x.f2) || share_a_face(m, n[1], n[3], x.f1, x.f2)) return false;
  }
  return true;
}

bool rotation_folds(const QuadMesh& m, Index h, Rotation r, Index except, bool bends) {
  const Hexagon x = hexagon(m, h);
  const Vec3 ref = m.face_area_normal(x.f1) + m.face_area_normal(x.f2);
  double bent_now = 2;  // the more bent of the two faces now, computed only when needed
  for (const auto& q : rotated_faces(m, h, r)) {
    if (except != kNone && std::find(q.begin(), q.end(), except) != q.end()) continue;
    const Vec3 &p0 = m.position(q[0]), &p1 = m.position(q[1]), &p2 = m.position(q[2]), &p3 = m.position(q[3]);
    if (!quad_keeps_orientation(p0, p1, p2, p3, ref) || !quad_is_convex(p0, p1, p2, p3)) return true;
    if (bends && quad_folds_further(p0, p1, p2, p3, [&] {
          if (bent_now > 1)
            bent_now = std::min(quad_fold_cos(m.positions(), m.face_vertices(x.f1)),
                                quad_fold_cos(m.positions(), m.face_vertices(x.f2)));
          return bent_now;
        }))
      return true;
  }
  return false;
}

RotationUndo rotation_undo(const QuadMesh& m, Index h) {
  const Index g = m.twin(h);
  RotationUndo u;
  u.faces[0] = QuadMesh::face(h), u.faces[1] = QuadMesh::face(g);
  u.before = {m.face_vertices(u.faces[0]), m.face_vertices(u.faces[1])};
  u.outer = {m.twin(QuadMesh::next(h)), m.twin(QuadMesh::opposite_in_face(h)), m.twin(QuadMesh::prev(h)),
             m.twin(QuadMesh::next(g)), m.twin(QuadMesh::opposite_in_face(g)), m.twin(QuadMesh::prev(g))};
  return u;
}

void undo_rotation(QuadMesh& m, const RotationUndo& u) {
  detail::rewrite_faces(m, u.faces, u.before.data(), 2, u.outer.data(), 6);
}

void rotate_edge(QuadMesh& m, Index h, Rotation r, [[maybe_unused]] Index doublet) {
  assert(can_rotate_edge(m, h, r, doublet));
  const RotationUndo around = rotation_undo(m, h);  // its faces and outer twins
  const auto quads = rotated_faces(m, h, r);
  detail::rewrite_faces(m, around.faces, quads.data(), 2, around.outer.data(), 6);
}

}  // namespace qs
