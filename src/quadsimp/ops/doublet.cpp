// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/ops/doublet.h"

#include <cassert>

#include "quadsimp/ops/local_rewrite.h"

namespace qs {

bool is_doublet(const QuadMesh& m, Index s) {
  return s < m.vertex_capacity() && m.is_vertex_live(s) && !m.is_border_vertex(s) && m.valence(s) == 2;
}

bool can_remove_doublet(const QuadMesh& m, Index s) {
  if (!is_doublet(m, s)) return false;
  const Index h1 = m.out(s), h2 = m.rotate(h1);
  const Index x = m.from(QuadMesh::opposite_in_face(h1)), y = m.from(QuadMesh::opposite_in_face(h2));
  return x != y;
}

Index remove_doublet(QuadMesh& m, Index s) {
  assert(can_remove_doublet(m, s));
  // h1 = s->p in F1 = (s, p, x, r); h2 = s->r in F2 = (s, r, y, p).
  const Index h1 = m.out(s), h2 = m.rotate(h1);
  const Index f1 = QuadMesh::face(h1), f2 = QuadMesh::face(h2);
  const Index p = m.to(h1), x = m.to(QuadMesh::next(h1)), r = m.to(h2), y = m.to(QuadMesh::next(h2));
  const Index outer[4] = {m.twin(QuadMesh::next(h1)), m.twin(QuadMesh::opposite_in_face(h1)),
                          m.twin(QuadMesh::next(h2)), m.twin(QuadMesh::opposite_in_face(h2))};
  m.kill_face(f2);
  m.kill_vertex(s);
  const std::array<Index, 4> merged = {p, x, r, y};
  detail::rewrite_faces(m, &f1, &merged, 1, outer, 4);
  return f1;
}

}  // namespace qs
