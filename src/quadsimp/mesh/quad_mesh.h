// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "quadsimp/util/types.h"

namespace qs {

//! A pure-quad, index-based half-edge mesh.
//!
//! Half-edge h = 4*f + k runs from corner k of face f to corner k+1, so the face,
//! next and prev of a half-edge are arithmetic. Stored per half-edge: its origin
//! vertex and its twin (kNone on the border). Stored per vertex: one outgoing
//! half-edge and the position. Faces are counter-clockwise seen from outside.
//!
//! For a border vertex, out(v) is its outgoing border half-edge, so that walking
//! the fan with `rotate(h) = twin(prev(h))` visits every incident face once.
//!
//! Deletion leaves tombstones (a dead face has corner 0 == kNone, a dead vertex has
//! out == kNone); compact() renumbers once at the end.
class QuadMesh {
 public:
  QuadMesh() = default;

  //! Builds the connectivity from indexed quads. Throws InvalidInput if an edge
  //! has more than two faces, two faces disagree on orientation, a face repeats a
  //! vertex, or a vertex's faces do not form a single fan.
  static QuadMesh from_faces(std::vector<Vec3> positions,
                             const std::vector<std::array<Index, 4>>& quads);

  // --- sizes (tombstones included in the *_capacity counts) ---
  Index n_vertices() const { return n_live_vertices_; }
  Index n_faces() const { return n_live_faces_; }
  Index vertex_capacity() const { return Index(pos_.size()); }
  Index face_capacity() const { return Index(origin_.size() / 4); }
  Index halfedge_capacity() const { return Index(origin_.size()); }

  // --- half-edge arithmetic ---
  static Index face(Index h) { return h >> 2; }
  static Index corner(Index h) { return h & 3u; }
  static Index next(Index h) { return (h & ~3u) | ((h + 1) & 3u); }
  static Index prev(Index h) { return (h & ~3u) | ((h + 3) & 3u); }
  static Index opposite_in_face(Index h) { return (h & ~3u) | ((h + 2) & 3u); }
  static Index halfedge(Index f, Index k) { return 4 * f + (k & 3u); }

  Index twin(Index h) const { return twin_[h]; }
  Index from(Index h) const { return origin_[h]; }
  Index to(Index h) const { return origin_[next(h)]; }
  Index out(Index v) const { return out_[v]; }
  //! Next outgoing half-edge around from(h), kNone past the last face at a border.
  Index rotate(Index h) const { return twin_[prev(h)]; }
  Index vertex(Index f, Index k) const { return origin_[4 * f + (k & 3u)]; }
  std::array<Index, 4> face_vertices(Index f) const {
    return {origin_[4 * f], origin_[4 * f + 1], origin_[4 * f + 2], origin_[4 * f + 3]};
  }

  bool is_face_live(Index f) const { return origin_[4 * f] != kNone; }
  bool is_vertex_live(Index v) const { return out_[v] != kNone; }
  bool is_border_halfedge(Index h) const { return twin_[h] == kNone; }
  bool is_border_vertex(Index v) const { return twin_[out_[v]] == kNone; }
  //! The border half-edge arriving at border vertex v (the one out(v) does not reach).
  Index border_in(Index v) const {
    Index h = out_[v];
    for (Index t = twin_[prev(h)]; t != kNone; t = twin_[prev(t)]) h = t;
    return prev(h);
  }
  //! The border vertices after and before border vertex v along its border loop.
  Index next_on_border(Index v) const { return to(out_[v]); }
  Index prev_on_border(Index v) const { return from(border_in(v)); }

  //! Number of edges incident to v (a border vertex counts its two border edges).
  int valence(Index v) const { return int(face_count_[v]) + (is_border_vertex(v) ? 1 : 0); }

  const Vec3& position(Index v) const { return pos_[v]; }
  //! The positions of a quad's corners c (a face's, or one a change would make).
  std::array<Vec3, 4> positions_of(const std::array<Index, 4>& c) const {
    return {pos_[c[0]], pos_[c[1]], pos_[c[2]], pos_[c[3]]};
  }
  Vec3& position(Index v) { return pos_[v]; }
  const std::vector<Vec3>& positions() const { return pos_; }

  //! Calls fn(h) for the outgoing half-edge of v in each of its faces, in fan order
  //! (one per face). At a border vertex the walk starts on the outgoing border edge;
  //! the incoming border edge belongs to no outgoing half-edge, so the visits number
  //! one less than the valence there.
  template <class Fn>
  void for_each_outgoing(Index v, Fn&& fn) const {
    const Index start = out_[v];
    Index h = start;
    do {
      fn(h);
      h = rotate(h);
    } while (h != kNone && h != start);
  }

  //! Face normal as the cross product of the diagonals (twice the vector area).
  Vec3 face_area_normal(Index f) const;
  //! The sum of face_area_normal() over the faces around v.
  Vec3 vertex_area_normal(Index v) const;
  Vec3 face_centroid(Index f) const;

  // --- editing primitives for the operators ---
  Index add_vertex(const Vec3& p);
  //! Appends a face with the given corners; twins are left unset (kNone).
  Index add_face(const std::array<Index, 4>& v);
  void set_twin(Index a, Index b) {
    twin_[a] = b;
    if (b != kNone) twin_[b] = a;
  }
  void set_origin(Index h, Index v) {
    if (origin_[h] != kNone) --face_count_[origin_[h]];
    if (v != kNone) ++face_count_[v];
    origin_[h] = v;
  }
  void set_out(Index v, Index h) { out_[v] = h; }
  void kill_face(Index f);
  void kill_vertex(Index v);
  //! Re-chooses out(v) so that a border vertex starts its fan at the border.
  //! Marks v dead if no live face uses it.
  void repair_out(Index v);

  //! Each live vertex's number among the live ones, in order of id (kNone for a
  //! tombstone): the ids compact() gives, and the order files and MeshLab layers list them.
  std::vector<Index> live_vertex_ids() const;

  //! Removes tombstones. Optional maps give old id -> new id (kNone if removed).
  void compact(std::vector<Index>* vertex_map = nullptr, std::vector<Index>* face_map = nullptr);

  //! Indexed quads of the live faces (after compact(), ids match the mesh's).
  std::vector<std::array<Index, 4>> quads() const;

 private:
  std::vector<Vec3> pos_;
  std::vector<Index> out_;
  std::vector<Index> origin_;  // 4 per face
  std::vector<Index> twin_;    // 4 per face
  // Faces at each vertex, kept by the editing primitives: valence() is the inner
  // loop of the rotation energy, and walking the fan there cost a tenth of the run.
  std::vector<Index> face_count_;
  Index n_live_vertices_ = 0;
  Index n_live_faces_ = 0;
};

//! Checks every invariant (twins, orientation, one fan per vertex, border out-edges,
//! four distinct live vertices per face, no doubled edge, live counts). Throws
//! TopologyError naming the first violation.
void validate(const QuadMesh& mesh);

//! Whether p and q are corners of one face other than the faces skip_a and skip_b.
bool share_a_face(const QuadMesh& mesh, Index p, Index q, Index skip_a = kNone, Index skip_b = kNone);

//! The other face of f's piece when that piece is f and one other face on the same four
//! corners (sharing all four edges: what a tetrahedron converts to, the least a closed
//! quad mesh has), else kNone.
Index two_quad_piece_partner(const QuadMesh& mesh, Index f);

//! The face diagonals whose two corners also share another face, as corner pairs (lower
//! id first), sorted, each once. Such quads touch at two corners without the edge between
//! them; split into triangles along that diagonal, as vcglib's importers did with one such
//! pair, they make an edge of four triangles. validate() accepts them, and an input may
//! have some (the pairing of a low-poly mesh), but the operators never make one.
//! Two-quad pieces (two_quad_piece_partner()) share theirs by nature and are left out.
std::vector<std::pair<Index, Index>> shared_diagonals(const QuadMesh& mesh);

//! The first of `now` (mesh's shared_diagonals()) that is not one of `before` (an earlier
//! state's) renamed by merges: each end the same vertex, or a vertex merged away since
//! (dead: ids are never reused). {kNone, kNone} if there is none. A merge that keeps the
//! other end's id renames a diagonal without making one; ids alone would call it new.
std::pair<Index, Index> new_shared_diagonal(const QuadMesh& mesh, const std::vector<std::pair<Index, Index>>& before,
                                            const std::vector<std::pair<Index, Index>>& now);

//! For each face (by id; dead faces get 0), the diagonal along which to split it into two
//! triangles, k for corners k and k+2: where possible not one whose corners are joined
//! by an edge or by the split of another face, since either puts that segment in four
//! triangles and MeshLab's polygon view then merges quads into 8-gons (two quads on the
//! same four corners; the quads of a converted octahedron); then not one whose corners
//! share another face; then the shorter.
std::vector<std::uint8_t> split_diagonals(const QuadMesh& mesh);

//! Labels every live vertex with its connected component (through faces), in order of
//! their lowest vertex id; dead vertices get kNone. Returns the number of components.
Index connected_components(const QuadMesh& mesh, std::vector<Index>& vertex_component);

}  // namespace qs
