// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/ops/diagonal_collapse.h"

#include <algorithm>
#include <cassert>

#include "quadsimp/mesh/quad_geometry.h"
#include "quadsimp/ops/local_rewrite.h"

namespace qs {

bool can_collapse_diagonal(const QuadMesh& m, Index f, Index k) {
  if (f >= m.face_capacity() || !m.is_face_live(f)) return false;
  const Index a = m.vertex(f, k), b = m.vertex(f, k + 1), c = m.vertex(f, k + 2), d = m.vertex(f, k + 3);
  if (m.is_border_vertex(a) && m.is_border_vertex(c)) return false;
  for (Index x : {b, d})
    if (!m.is_border_vertex(x) && m.valence(x) <= 2) return false;
  return detail::link_condition(m, a, c, b, d);
}

Vec3 collapse_position(const QuadMesh& m, Index f, Index k) {
  const Index a = m.vertex(f, k), c = m.vertex(f, k + 2);
  if (m.is_border_vertex(a)) return m.position(a);
  if (m.is_border_vertex(c)) return m.position(c);
  return 0.5 * (m.position(a) + m.position(c));
}

bool collapse_folds(const QuadMesh& m, Index f, Index k, const Vec3& p) {
  return !for_each_face_after_collapse(m, f, k, p, [&](Index g, const Vec3* q) {
    return quad_keeps_orientation(q[0], q[1], q[2], q[3], m.face_area_normal(g));
  });
}

Index collapse_diagonal(QuadMesh& m, Index f, Index k, const Vec3& p) {
  assert(can_collapse_diagonal(m, f, k));
  const Index h0 = QuadMesh::halfedge(f, k);  // a -> b
  const Index h1 = QuadMesh::next(h0), h2 = QuadMesh::next(h1), h3 = QuadMesh::next(h2);
  const Index a = m.from(h0), b = m.from(h1), c = m.from(h2), d = m.from(h3);
  const Index t0 = m.twin(h0), t1 = m.twin(h1), t2 = m.twin(h2), t3 = m.twin(h3);

  thread_local std::vector<Index> fan_c;
  fan_c.clear();
  m.for_each_outgoing(c, [&](Index h) {
    if (QuadMesh::face(h) != f) fan_c.push_back(h);
  });
  m.kill_face(f);
  // b-a and c-b become one edge b-v; d-c and a-d become one edge v-d.
  if (t0 != kNone) m.set_twin(t0, t1);
  else if (t1 != kNone) m.set_twin(t1, kNone);
  if (t2 != kNone) m.set_twin(t2, t3);
  else if (t3 != kNone) m.set_twin(t3, kNone);
  for (Index h : fan_c) m.set_origin(h, a);
  m.kill_vertex(c);

  // New out-edges for the three vertices whose out-edge may have lived in f.
  m.set_out(a, t3 != kNone ? t3 : t1);
  m.set_out(b, t0 != kNone ? t0 : QuadMesh::next(t1));
  m.set_out(d, t2 != kNone ? t2 : QuadMesh::next(t3));
  for (Index v : {a, b, d}) m.repair_out(v);
  m.position(a) = p;
  return a;
}

}  // namespace qs
