// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/ops/border_ear.h"

#include <cassert>

#include "quadsimp/ops/local_rewrite.h"

namespace qs {

bool can_collapse_border_ear(const QuadMesh& m, Index f, Index k) {
  if (f >= m.face_capacity() || !m.is_face_live(f)) return false;
  const Index hb = QuadMesh::halfedge(f, k);  // b -> c
  const Index ha = QuadMesh::prev(hb);        // a -> b
  const Index hc = QuadMesh::next(hb);        // c -> d
  const Index hd = QuadMesh::next(hc);        // d -> a
  if (m.twin(ha) != kNone || m.twin(hb) != kNone) return false;  // b's only face is f
  if (m.twin(hc) == kNone || m.twin(hd) == kNone) return false;
  const Index a = m.from(ha), b = m.from(hb), c = m.from(hc), d = m.from(hd);
  // The border neighbours beyond a and c.
  const Index x = m.prev_on_border(a), y = m.next_on_border(c);
  if (x == c || y == a || x == y) return false;  // the loop would shrink below three edges
  return detail::link_condition(m, a, c, b, d);
}

Index collapse_border_ear(QuadMesh& m, Index f, Index k, const Vec3& p) {
  assert(can_collapse_border_ear(m, f, k));
  const Index hb = QuadMesh::halfedge(f, k);
  const Index ha = QuadMesh::prev(hb), hc = QuadMesh::next(hb), hd = QuadMesh::next(hc);
  const Index a = m.from(ha), b = m.from(hb), c = m.from(hc), d = m.from(hd);
  const Index t_dc = m.twin(hc), t_ad = m.twin(hd);  // d -> c and a -> d outside f
  thread_local std::vector<Index> fan_c;
  fan_c.clear();
  m.for_each_outgoing(c, [&](Index h) {
    if (QuadMesh::face(h) != f) fan_c.push_back(h);
  });
  m.kill_face(f);
  m.kill_vertex(b);
  m.set_twin(t_dc, t_ad);
  for (Index h : fan_c) m.set_origin(h, a);
  m.kill_vertex(c);
  m.set_out(a, t_ad);
  m.set_out(d, t_dc);
  m.repair_out(a);
  m.repair_out(d);
  m.position(a) = p;
  return a;
}

}  // namespace qs
