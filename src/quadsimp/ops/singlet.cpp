// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/ops/singlet.h"

#include <cassert>

namespace qs {

bool is_singlet(const QuadMesh& m, Index s) {
  if (s >= m.vertex_capacity() || !m.is_vertex_live(s) || m.is_border_vertex(s)) return false;
  const Index h = m.out(s);
  return m.rotate(h) == h;
}

Index remove_singlet(QuadMesh& m, Index s) {
  assert(is_singlet(m, s));
  // h = s->p at corner 1 of (p, s, p, x); corners 2->3 and 3->0 are the two p-x edges.
  const Index h = m.out(s);
  const Index px = QuadMesh::next(h), xp = QuadMesh::next(px);
  const Index p = m.from(px), x = m.from(xp);
  const Index t1 = m.twin(px), t2 = m.twin(xp);  // x->p and p->x outside the face
  m.kill_face(QuadMesh::face(h));
  m.kill_vertex(s);
  if (t1 != kNone && t2 != kNone) m.set_twin(t1, t2);  // else kill_face() left the one there on the border
  if (t1 == kNone && t2 == kNone) {
    // The face stood alone: its other corners go with it.
    m.kill_vertex(p);
    m.kill_vertex(x);
    return kNone;
  }
  m.set_out(p, t2 != kNone ? t2 : QuadMesh::next(t1));
  m.set_out(x, t1 != kNone ? t1 : QuadMesh::next(t2));
  m.repair_out(p);
  m.repair_out(x);
  return p;
}

}  // namespace qs
