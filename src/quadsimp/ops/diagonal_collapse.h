// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include "quadsimp/mesh/quad_mesh.h"

namespace qs {

//! Diagonal collapse [Bozzo et al. 2010, Fig. 1 left]: quad f = (a, b, c, d), with
//! a = corner k, loses its diagonal a-c; a and c merge into one vertex. k = 0 or 1 names
//! each diagonal; k + 2 names the same one from its other end, which then survives.
//!
//!        d                 d
//!      /   \               |
//!     a  f  c     ->       v        V-1, E-2, F-1
//!      \   /               |
//!        b                 b
//!
//! The survivor keeps a's id. val(v) = val(a)+val(c)-2; b and d each lose one edge
//! (and may become doublets, which the caller cleans).
//!
//! Refused (false) when: f is dead; a and c are both on the border (a pinch);
//! the link condition fails (the vertices sharing a face with a and with c are not
//! exactly {b, d}: doubled edges, faces with a repeated vertex); b or d is an
//! interior vertex of valence <= 2 (an uncleaned doublet).
bool can_collapse_diagonal(const QuadMesh& mesh, Index f, Index k);

//! Where the survivor goes when only topology decides: a border end keeps its place
//! (the border stays on the input's border), otherwise the midpoint.
Vec3 collapse_position(const QuadMesh& mesh, Index f, Index k);

//! Calls test(g, corners) for every face g other than f around diagonal k, with the
//! corners it would have after the collapse (the merged vertex at p), until one call
//! returns false; returns whether all passed. For geometric checks of a collapse.
template <class Test>
bool for_each_face_after_collapse(const QuadMesh& mesh, Index f, Index k, const Vec3& p, Test&& test) {
  const Index a = mesh.vertex(f, k), c = mesh.vertex(f, k + 2);
  bool ok = true;
  for (Index x : {a, c})
    mesh.for_each_outgoing(x, [&](Index h) {
      const Index g = QuadMesh::face(h);
      if (g == f || !ok) return;
      Vec3 q[4];
      for (Index i = 0; i < 4; ++i) {
        const Index v = mesh.vertex(g, i);
        q[i] = (v == a || v == c) ? p : mesh.position(v);
      }
      ok = test(g, q);
    });
  return ok;
}

//! True when moving the merged vertex to `p` would fold a face around it: the
//! normal (cross of the diagonals) of a face incident to a or c other than f turns
//! by 90 degrees or more, or vanishes.
bool collapse_folds(const QuadMesh& mesh, Index f, Index k, const Vec3& p);

//! Performs the collapse and puts the survivor at `p`. \pre can_collapse_diagonal.
//! \return the surviving vertex (a).
Index collapse_diagonal(QuadMesh& mesh, Index f, Index k, const Vec3& p);

}  // namespace qs
