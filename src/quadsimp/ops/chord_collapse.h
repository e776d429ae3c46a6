// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <vector>

#include "quadsimp/mesh/quad_mesh.h"

namespace qs {

//! A chord: the strip of quads met by walking from an edge to the opposite edge of
//! its face, across into the next face, and so on, until the walk comes back (a
//! closed chord, such as a ring around a tube) or reaches the border at both ends.
//! Face i has the corners (left[i], right[i], right[i+1], left[i+1]) in its own order
//! (indices taken modulo the face count when closed); entries[i] is its half-edge
//! left[i] -> right[i]. The crossed edges are left[i]-right[i]: n of them when
//! closed, n + 1 when open (the first and the last on the border).
struct Chord {
  std::vector<Index> faces, entries, left, right;
  bool closed = false;
  Index pairs() const { return Index(left.size()); }
};

//! Gathers the chord through half-edge h's edge. Returns false (and leaves `chord`
//! partial) when h's face is dead or the chord has more than `max_faces` faces.
bool gather_chord(const QuadMesh& mesh, Index h, Chord& chord, Index max_faces);

//! Poly-chord collapse (ours; the paper has no operator that thins a strip): every
//! crossed edge of the chord collapses to one vertex and the chord's faces vanish, so
//! that the faces beside it on both sides become neighbours. It takes a ring of quads
//! out of a tube, or one quad's length out of a strip, where a diagonal collapse would
//! pinch the part.
//!
//!     l0 --- l1 --- l2          m0 --- m1 --- m2
//!     |  f0  |  f1  |    ->    (the faces above and below now share m0-m1-m2)
//!     r0 --- r1 --- r2
//!
//! V - pairs, E - (faces + pairs), F - faces. val(m) = val(l) + val(r) - 4 inside,
//! - 3 at an open end.
//!
//! Refused (false) when: the chord meets a face twice or a vertex twice (it crosses
//! or touches itself); a crossed edge joins two border vertices without being a border
//! edge itself (the merge would pinch the border, or join two borders into one and
//! change the topology); some merged vertex would have no face left; or, on the faces
//! around the chord with their corners merged, a face repeats a corner, an edge has
//! more than two faces or two faces run it the same way, or two faces share anything
//! but one edge (a doubled edge or a shared diagonal).
bool can_collapse_chord(const QuadMesh& mesh, const Chord& chord);

//! The faces outside the chord that have a corner on it (sorted): the ones the
//! collapse changes.
void faces_beside_chord(const QuadMesh& mesh, const Chord& chord, std::vector<Index>& faces);

//! The pair whose crossed edge has v as an end, or -1.
int chord_pair_of(const Chord& chord, Index v);

//! Performs it: left[i] survives at positions[i], right[i] is removed. \pre
//! can_collapse_chord.
void collapse_chord(QuadMesh& mesh, const Chord& chord, const std::vector<Vec3>& positions);

}  // namespace qs
