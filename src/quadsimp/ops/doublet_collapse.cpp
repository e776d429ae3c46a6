// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/ops/doublet_collapse.h"

#include <cassert>

#include "quadsimp/ops/diagonal_collapse.h"
#include "quadsimp/ops/doublet.h"
#include "quadsimp/ops/local_rewrite.h"

namespace qs {

DoubletCorners doublet_corners(const QuadMesh& m, Index s) {
  const Index h1 = m.out(s), h2 = m.rotate(h1);
  return {m.to(h1), m.to(QuadMesh::next(h1)), m.to(h2), m.to(QuadMesh::next(h2))};
}

bool can_collapse_doublet(const QuadMesh& m, Index s) {
  if (!can_remove_doublet(m, s)) return false;
  const DoubletCorners c = doublet_corners(m, s);
  if (m.is_border_vertex(c.p) && m.is_border_vertex(c.r)) return false;
  // Removing s leaves x and y their valences: the diagonal collapse's own test.
  for (Index x : {c.x, c.y})
    if (!m.is_border_vertex(x) && m.valence(x) <= 2) return false;
  return detail::link_condition(m, c.p, c.r, c.x, c.y, s);
}

Index collapse_doublet(QuadMesh& m, Index s, const Vec3& position) {
  assert(can_collapse_doublet(m, s));
  // remove_doublet() leaves the face (p, x, r, y), p at corner 0.
  const Index f = remove_doublet(m, s);
  return collapse_diagonal(m, f, 0, position);
}

}  // namespace qs
