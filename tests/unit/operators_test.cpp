// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// Every topological operator on small hand-built meshes: effect, refusals, and
// validate() after each step.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "fixtures/shapes.h"
#include "quadsimp/mesh/clean.h"
#include "quadsimp/mesh/quad_geometry.h"
#include "quadsimp/convert/tri_to_quad.h"
#include "quadsimp/ops/border_ear.h"
#include "quadsimp/ops/chord_collapse.h"
#include "quadsimp/ops/cleaning.h"
#include "quadsimp/ops/diagonal_collapse.h"
#include "quadsimp/ops/doublet.h"
#include "quadsimp/ops/doublet_collapse.h"
#include "quadsimp/ops/edge_rotation.h"
#include "quadsimp/ops/singlet.h"
#include "quadsimp/util/errors.h"

using namespace qs;
using namespace qs::fixtures;

namespace {

Index face_with_corners(const QuadMesh& m, std::initializer_list<Index> vs) {
  for (Index f = 0; f < m.face_capacity(); ++f) {
    if (!m.is_face_live(f)) continue;
    bool all = true;
    for (Index v : vs) {
      bool in = false;
      for (Index k = 0; k < 4; ++k) in |= m.vertex(f, k) == v;
      all &= in;
    }
    if (all) return f;
  }
  return kNone;
}

Index corner_of(const QuadMesh& m, Index f, Index v) {
  for (Index k = 0; k < 4; ++k)
    if (m.vertex(f, k) == v) return k;
  return kNone;
}

Index halfedge_between(const QuadMesh& m, Index a, Index b) {
  for (Index h = 0; h < m.halfedge_capacity(); ++h)
    if (m.is_face_live(QuadMesh::face(h)) && m.from(h) == a && m.to(h) == b) return h;
  return kNone;
}

}  // namespace

// 3x3 grid, vertex ids:
//  12 13 14 15
//   8  9 10 11
//   4  5  6  7
//   0  1  2  3
TEST(DiagonalCollapse, centre_face_of_grid) {
  QuadMesh m = quad_grid(3, 3);
  const Index f = face_with_corners(m, {5, 6, 10, 9});
  const Index k = corner_of(m, f, 5);  // diagonal 5-10
  ASSERT_TRUE(can_collapse_diagonal(m, f, k));
  EXPECT_FALSE(collapse_folds(m, f, k, collapse_position(m, f, k)));
  const Index v = collapse_diagonal(m, f, k, collapse_position(m, f, k));
  validate(m);
  EXPECT_EQ(v, 5u);
  EXPECT_EQ(m.n_faces(), 8u);
  EXPECT_EQ(m.n_vertices(), 15u);
  EXPECT_FALSE(m.is_vertex_live(10));
  EXPECT_EQ(m.valence(5), 4 + 4 - 2);
  EXPECT_EQ(m.valence(6), 3);
  EXPECT_EQ(m.valence(9), 3);
  EXPECT_TRUE(m.position(5).isApprox(Vec3(1.5, 1.5, 0)));
}

TEST(DiagonalCollapse, border_end_keeps_its_position) {
  QuadMesh m = quad_grid(3, 3);
  const Index f = face_with_corners(m, {1, 2, 6, 5});
  const Index k = corner_of(m, f, 1);  // 1 is on the border, 6 inside
  ASSERT_TRUE(can_collapse_diagonal(m, f, k));
  EXPECT_TRUE(collapse_position(m, f, k).isApprox(m.position(1)));
  const Index v = collapse_diagonal(m, f, k, collapse_position(m, f, k));
  validate(m);
  EXPECT_TRUE(m.is_border_vertex(v));
  EXPECT_EQ(m.n_faces(), 8u);
}

TEST(DiagonalCollapse, refusals) {
  // Both ends on the border: a pinch.
  QuadMesh one = single_quad();
  EXPECT_FALSE(can_collapse_diagonal(one, 0, 0));
  QuadMesh g = quad_grid(3, 3);
  const Index f = face_with_corners(g, {0, 1, 5, 4});
  EXPECT_FALSE(can_collapse_diagonal(g, f, corner_of(g, f, 1)));  // 1-4: both border
  EXPECT_TRUE(can_collapse_diagonal(g, f, corner_of(g, f, 0)));   // 0-5: 5 is inside
  // Link condition: on a cube every diagonal's ends share more than b and d.
  QuadMesh c = cube();
  for (Index ff = 0; ff < 6; ++ff)
    for (Index k = 0; k < 2; ++k) EXPECT_FALSE(can_collapse_diagonal(c, ff, k));
  // Dead face.
  g.kill_face(0);
  EXPECT_FALSE(can_collapse_diagonal(g, 0, 0));
}

namespace {
// A 3x3 grid whose centre face is replaced by a doublet: s inside (5, 6, 10, 9)
// with faces (s, 5, 6, 10) and (s, 10, 9, 5).
QuadMesh grid_with_doublet(Index* s_out) {
  QuadMesh g = quad_grid(3, 3);
  auto quads = g.quads();
  auto pos = g.positions();
  quads.erase(quads.begin() + face_with_corners(g, {5, 6, 10, 9}));
  pos.emplace_back(1.4, 1.6, 0);
  const Index s = Index(pos.size() - 1);
  quads.push_back({s, 5, 6, 10});
  quads.push_back({s, 10, 9, 5});
  *s_out = s;
  return QuadMesh::from_faces(pos, quads);
}
}  // namespace

TEST(DiagonalCollapse, refuses_next_to_an_uncleaned_doublet) {
  Index s;
  QuadMesh m = grid_with_doublet(&s);
  validate(m);
  ASSERT_TRUE(is_doublet(m, s));
  // Face (s, 5, 6, 10), diagonal 5-10: s would be left with valence 1.
  const Index f = face_with_corners(m, {s, 5, 6, 10});
  EXPECT_FALSE(can_collapse_diagonal(m, f, corner_of(m, f, 5)));
  // Diagonal s-6 of the same face is fine: it merges s into 6 and removes the doublet.
  const Index k = corner_of(m, f, s);
  ASSERT_TRUE(can_collapse_diagonal(m, f, k));
  collapse_diagonal(m, f, k, m.position(6));
  validate(m);
  EXPECT_EQ(m.n_faces(), 9u);
}

TEST(DiagonalCollapse, folds_are_detected) {
  QuadMesh m = quad_grid(3, 3);
  const Index f = face_with_corners(m, {5, 6, 10, 9});
  const Index k = corner_of(m, f, 5);
  EXPECT_TRUE(collapse_folds(m, f, k, Vec3(-5, 1.5, 0)));  // far outside its ring
  EXPECT_FALSE(collapse_folds(m, f, k, Vec3(1.4, 1.6, 0)));
}

TEST(EdgeRotation, both_directions_on_a_grid) {
  for (Rotation r : {Rotation::Ccw, Rotation::Cw}) {
    QuadMesh m = quad_grid(3, 3);
    const Index h = halfedge_between(m, 5, 6);  // interior edge, faces below and above
    ASSERT_NE(h, kNone);
    ASSERT_TRUE(can_rotate_edge(m, h, r));
    const auto faces = rotated_faces(m, h, r);
    const auto [a, b] = rotated_edge(m, h, r);
    EXPECT_EQ(a, faces[0][0]);  // the new edge, as the new faces have it
    EXPECT_EQ(b, faces[1][0]);
    const int before_a = m.valence(a), before_b = m.valence(b);
    rotate_edge(m, h, r);
    validate(m);
    EXPECT_EQ(m.valence(a), before_a + 1);
    EXPECT_EQ(m.valence(b), before_b + 1);
    EXPECT_EQ(m.n_faces(), 9u);
    EXPECT_EQ(m.valence(5), 3);
    EXPECT_EQ(m.valence(6), 3);
    // The two new endpoints are the first corners of the new faces.
    EXPECT_EQ(m.valence(faces[0][0]), faces[0][0] == 1 || faces[0][0] == 2 ? 4 : 5);
    EXPECT_NE(halfedge_between(m, faces[0][0], faces[1][0]), kNone);
    EXPECT_EQ(halfedge_between(m, 5, 6), kNone);
  }
}

TEST(EdgeRotation, refusals) {
  QuadMesh m = quad_grid(3, 3);
  EXPECT_FALSE(can_rotate_edge(m, halfedge_between(m, 0, 1), Rotation::Ccw));  // border edge
  QuadMesh c = cube();  // every vertex has valence 3: a rotation would make a doublet
  for (Index h = 0; h < c.halfedge_capacity(); ++h) {
    EXPECT_FALSE(can_rotate_edge(c, h, Rotation::Ccw));
    EXPECT_FALSE(can_rotate_edge(c, h, Rotation::Cw));
  }
  // A border vertex of valence 3 may drop to 2; an inner one of valence 3 may not.
  QuadMesh g = quad_grid(2, 2);
  EXPECT_TRUE(can_rotate_edge(g, halfedge_between(g, 4, 1), Rotation::Ccw));
}

TEST(EdgeRotation, fold_check_can_leave_out_the_ear) {
  // Rotating the inner edge at border vertex 1 of a flat 2x2 grid (either way) leaves 1
  // in one face with its border neighbours 0 and 2, at 180 degrees: that face is not
  // convex, the other one is (with the centre raised off the row 3-4-5). The border ear
  // removal collapses that face right away.
  QuadMesh g = quad_grid(2, 2);
  g.position(4) = Vec3(1, 1.5, 0);
  const Index h = halfedge_between(g, 4, 1);
  ASSERT_NE(h, kNone);
  for (Rotation r : {Rotation::Ccw, Rotation::Cw}) {
    ASSERT_TRUE(can_rotate_edge(g, h, r));
    EXPECT_TRUE(rotation_folds(g, h, r));
    EXPECT_FALSE(rotation_folds(g, h, r, 1));
    EXPECT_TRUE(rotation_folds(g, h, r, 7));  // a vertex of neither face: both checked
  }
}

TEST(EdgeRotation, bend_check_sees_what_the_fold_check_does_not) {
  // A 2x2 grid with the corner 6 and its neighbour 7 raised: all four quads are convex
  // and bend by less than 90 degrees, and rotating the edge 4-3 clockwise makes a quad
  // that is convex and faces the old pair's way (rotation_folds() lets it pass) but bends
  // past 90 degrees whichever diagonal splits it (rotation_folds() with `bends` refuses).
  QuadMesh g = quad_grid(2, 2);
  const Index h = halfedge_between(g, 4, 3);
  ASSERT_NE(h, kNone);
  ASSERT_TRUE(can_rotate_edge(g, h, Rotation::Cw));
  // Flat: the bend check adds no refusal (the flat grid's rotation is refused, or not,
  // by convexity alone).
  EXPECT_EQ(rotation_folds(g, h, Rotation::Cw, kNone, true), rotation_folds(g, h, Rotation::Cw));
  g.position(6).z() = 3;
  g.position(7).z() = 4;
  for (Index f = 0; f < 4; ++f) {
    const auto c = g.face_vertices(f);
    EXPECT_FALSE(quad_folds(g.position(c[0]), g.position(c[1]), g.position(c[2]), g.position(c[3])));
  }
  EXPECT_FALSE(rotation_folds(g, h, Rotation::Cw));
  EXPECT_TRUE(rotation_folds(g, h, Rotation::Cw, kNone, true));
  // Left out, as for rotation_folds(), when the bent face holds `except`.
  Index bent_corner = kNone;
  for (const auto& q : rotated_faces(g, h, Rotation::Cw))
    if (quad_folds(g.position(q[0]), g.position(q[1]), g.position(q[2]), g.position(q[3]))) bent_corner = q[0];
  ASSERT_NE(bent_corner, kNone);
  EXPECT_FALSE(rotation_folds(g, h, Rotation::Cw, bent_corner, true));
}

TEST(EdgeRotation, never_makes_two_quads_share_a_diagonal) {
  // Random rotations on a grid (topology only): the predicate must refuse every one
  // after which two quads would touch at opposite corners. Without the diagonal check
  // this walk makes such a pair within a few hundred rotations.
  QuadMesh m = quad_grid(6, 6);
  std::mt19937 rng(7);
  int done = 0;
  for (int step = 0; step < 4000; ++step) {
    const Index h = Index(rng() % m.halfedge_capacity());
    const Rotation r = rng() % 2 ? Rotation::Ccw : Rotation::Cw;
    if (!can_rotate_edge(m, h, r)) continue;
    rotate_edge(m, h, r);
    ++done;
    validate(m);
    ASSERT_TRUE(shared_diagonals(m).empty()) << "after rotation " << done;
  }
  EXPECT_GT(done, 500);
}

TEST(EdgeRotation, rotation_and_back_restores_valences) {
  QuadMesh m = quad_grid(4, 4);
  std::vector<int> before;
  for (Index v = 0; v < m.n_vertices(); ++v) before.push_back(m.valence(v));
  const Index h = halfedge_between(m, 6, 7);
  const auto nf = rotated_faces(m, h, Rotation::Ccw);
  rotate_edge(m, h, Rotation::Ccw);
  validate(m);
  // The new edge runs between the new faces' first corners; rotating it the other way
  // brings back the old valences.
  const Index back = halfedge_between(m, nf[0][0], nf[1][0]);
  ASSERT_NE(back, kNone);
  Rotation undo = Rotation::Cw;
  if (!can_rotate_edge(m, back, undo)) undo = Rotation::Ccw;
  rotate_edge(m, back, undo);
  validate(m);
  std::vector<int> after;
  for (Index v = 0; v < m.n_vertices(); ++v) after.push_back(m.valence(v));
  EXPECT_EQ(before, after);
}

TEST(Doublet, two_faces_merge) {
  std::vector<Vec3> p = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {1, 1, 0}};
  QuadMesh m = QuadMesh::from_faces(p, {{4, 3, 0, 1}, {4, 1, 2, 3}});
  ASSERT_TRUE(is_doublet(m, 4));
  ASSERT_TRUE(can_remove_doublet(m, 4));
  remove_doublet(m, 4);
  validate(m);
  EXPECT_EQ(m.n_faces(), 1u);
  EXPECT_EQ(m.n_vertices(), 4u);
  for (Index v = 0; v < 4; ++v) EXPECT_EQ(m.valence(v), 2);
}

TEST(Doublet, inside_a_ring_and_refusals) {
  Index s;
  QuadMesh m = grid_with_doublet(&s);
  validate(m);
  ASSERT_TRUE(is_doublet(m, s));
  EXPECT_FALSE(is_doublet(m, 0));  // a border corner of valence 2 is not a doublet
  EXPECT_FALSE(is_doublet(m, 5));
  CleanCounts counts;
  std::vector<Index> work = {s};
  clean_from(m, work, counts);
  validate(m);
  EXPECT_EQ(counts.doublets, 1u);
  EXPECT_EQ(m.n_faces(), 9u);
  EXPECT_EQ(m.valence(5), 4);
}

TEST(Doublet, chain_is_removed_recursively) {
  // s=5 is a doublet between faces (5,4,1,2) and (5,2,3,4); p=4 has valence 3 and
  // drops to 2 when s goes: a second doublet, found only through the worklist.
  std::vector<Vec3> p = {{0, 0, 0}, {3, 0, 0}, {3, 3, 0}, {0, 3, 0}, {1.5, 1.5, 0}, {2.2, 1.9, 0}};
  QuadMesh m = QuadMesh::from_faces(p, {{0, 1, 4, 3}, {5, 4, 1, 2}, {5, 2, 3, 4}});
  validate(m);
  ASSERT_TRUE(is_doublet(m, 5));
  ASSERT_FALSE(is_doublet(m, 4));
  CleanCounts counts;
  std::vector<Index> work = {5};
  clean_from(m, work, counts);
  validate(m);
  EXPECT_EQ(counts.doublets, 2u);
  EXPECT_EQ(m.n_faces(), 1u);
  EXPECT_EQ(m.n_vertices(), 4u);
}

TEST(Doublet, pillow_is_refused) {
  std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  QuadMesh m = QuadMesh::from_faces(p, {{0, 1, 2, 3}, {0, 3, 2, 1}});
  validate(m);
  EXPECT_TRUE(is_doublet(m, 0));
  EXPECT_FALSE(can_remove_doublet(m, 0));
}

TEST(DoubletCollapse, a_vertex_rotated_down_to_two_faces_goes_with_two_segments) {
  // A crease along the middle row of a 4 x 2 grid; its vertex 7 between 6 and 8 is taken out.
  QuadMesh m = quad_grid(4, 2);
  const Index b = 7;
  const Index up = halfedge_between(m, b, 12);
  ASSERT_TRUE(can_rotate_edge(m, up, Rotation::Ccw));
  rotate_edge(m, up, Rotation::Ccw);
  validate(m);
  // Rotations make no doublet, unless told where one may be.
  const Index down = halfedge_between(m, b, 2);
  ASSERT_NE(down, kNone);
  EXPECT_FALSE(can_rotate_edge(m, down, Rotation::Ccw));
  EXPECT_FALSE(can_rotate_edge(m, down, Rotation::Cw));
  ASSERT_TRUE(can_rotate_edge(m, down, Rotation::Ccw, b));
  EXPECT_FALSE(can_rotate_edge(m, down, Rotation::Ccw, 6));  // another vertex named
  rotate_edge(m, down, Rotation::Ccw, b);
  validate(m);
  ASSERT_TRUE(is_doublet(m, b));
  const DoubletCorners c = doublet_corners(m, b);
  EXPECT_EQ(std::minmax(c.p, c.r), std::minmax(Index(6), Index(8)));
  ASSERT_TRUE(can_collapse_doublet(m, b));
  const int valence = m.valence(c.p) + m.valence(c.r) - 4;
  const Index faces = m.n_faces(), vertices = m.n_vertices();
  const Index v = collapse_doublet(m, b, m.position(b));
  validate(m);
  EXPECT_EQ(v, c.p);
  EXPECT_EQ(m.valence(v), valence);
  EXPECT_EQ(m.n_faces(), faces - 2);
  EXPECT_EQ(m.n_vertices(), vertices - 2);
  EXPECT_EQ(m.position(v), Vec3(2, 1, 0));
  EXPECT_TRUE(shared_diagonals(m).empty());
  // The crease runs 5 - v - 9 now, by edges.
  EXPECT_NE(halfedge_between(m, v, 5), kNone);
  EXPECT_NE(halfedge_between(m, v, 9), kNone);
}

TEST(DoubletCollapse, refusals_and_a_doublet_inside_a_grid) {
  QuadMesh g = quad_grid(3, 3);
  EXPECT_FALSE(can_collapse_doublet(g, 5));  // no doublet
  std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  EXPECT_FALSE(can_collapse_doublet(QuadMesh::from_faces(p, {{0, 1, 2, 3}, {0, 3, 2, 1}}), 0));  // the pillow
  // A doublet whose two neighbours are on the border: the merge would pinch it.
  std::vector<Vec3> q = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {1, 1, 0}};
  const QuadMesh pinch = QuadMesh::from_faces(q, {{4, 3, 0, 1}, {4, 1, 2, 3}});
  ASSERT_TRUE(is_doublet(pinch, 4));
  EXPECT_FALSE(can_collapse_doublet(pinch, 4));
  // Inside a grid: its neighbours 5 and 10 merge, and the grid keeps every invariant.
  Index s;
  QuadMesh m = grid_with_doublet(&s);
  ASSERT_TRUE(can_collapse_doublet(m, s));
  collapse_doublet(m, s, m.position(s));
  validate(m);
  EXPECT_EQ(m.n_faces(), 8u);
  EXPECT_TRUE(shared_diagonals(m).empty());
}

namespace {

// F_top = (p, x, t1, t2) above (with `top`), F_bot = (x, p, b1, b2) below (with
// `bottom`), and between them the singlet face (p, s, p, x) glued to those there: it has
// two p-x edges. Vertices p = 0, x = 1, and s the last.
QuadMesh with_singlet(bool top, bool bottom) {
  const Index p = 0, x = 1, t1 = 2, t2 = 3, b1 = 4, b2 = 5;
  std::vector<Vec3> pos = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, -1, 0}, {1, -1, 0}};
  std::vector<std::array<Index, 4>> faces;
  if (top) faces.push_back({p, x, t1, t2});
  if (bottom) faces.push_back({x, p, b1, b2});
  QuadMesh m = QuadMesh::from_faces(pos, faces);
  if (faces.empty()) m = QuadMesh(), m.add_vertex(pos[p]), m.add_vertex(pos[x]);
  const Index top_px = top ? halfedge_between(m, p, x) : kNone, bot_xp = bottom ? halfedge_between(m, x, p) : kNone;
  if (top) m.set_twin(top_px, kNone);
  if (bottom) m.set_twin(bot_xp, kNone);
  const Index s = m.add_vertex(Vec3(0.3, 0.0, 0.1));
  const Index f = m.add_face({p, s, p, x});
  m.set_twin(QuadMesh::halfedge(f, 0), QuadMesh::halfedge(f, 1));  // p->s with s->p
  m.set_twin(QuadMesh::halfedge(f, 2), bot_xp);                    // p->x with x->p below
  m.set_twin(QuadMesh::halfedge(f, 3), top_px);                    // x->p with p->x above
  m.set_out(s, QuadMesh::halfedge(f, 1));
  if (!top && !bottom) m.set_out(x, QuadMesh::halfedge(f, 3));
  return m;
}

}  // namespace

TEST(Singlet, face_with_two_edges_between_p_and_x_is_removed) {
  QuadMesh m = with_singlet(true, true);
  const Index p = 0, x = 1, s = 6;
  const Index top_px = halfedge_between(m, p, x), bot_xp = halfedge_between(m, x, p);
  ASSERT_TRUE(is_singlet(m, s));
  EXPECT_THROW(validate(m), TopologyError);  // the face repeats p
  EXPECT_EQ(remove_singlet(m, s), p);
  validate(m);
  EXPECT_EQ(m.n_faces(), 2u);
  EXPECT_EQ(m.twin(top_px), bot_xp);
  EXPECT_FALSE(is_singlet(m, p));
}

TEST(Singlet, glued_on_one_side_or_none) {
  // With a face on one side only, the other p-x edge becomes the border; with none, the
  // face goes with all its corners.
  for (const bool top : {true, false}) {
    QuadMesh m = with_singlet(top, !top);
    ASSERT_TRUE(is_singlet(m, 6));
    EXPECT_EQ(remove_singlet(m, 6), 0u);
    validate(m);
    EXPECT_EQ(m.n_faces(), 1u);
    EXPECT_EQ(m.n_vertices(), 4u);
    EXPECT_TRUE(m.is_border_vertex(0));
  }
  QuadMesh lone = with_singlet(false, false);
  ASSERT_TRUE(is_singlet(lone, 2));
  EXPECT_EQ(remove_singlet(lone, 2), kNone);
  EXPECT_EQ(lone.n_faces(), 0u);
  EXPECT_EQ(lone.n_vertices(), 0u);
}

TEST(Singlet, the_cleaning_removes_it) {
  // No operator leaves a singlet (their predicates refuse it), but the cleaning after
  // each must remove one if it did, and count it.
  QuadMesh m = with_singlet(true, true);
  CleanCounts counts;
  std::vector<Index> work = {6}, changed;
  clean_from(m, work, counts, &changed);
  validate(m);
  EXPECT_EQ(counts.singlets, 1u);
  EXPECT_EQ(counts.doublets, 0u);
  EXPECT_EQ(m.n_faces(), 2u);
  EXPECT_FALSE(changed.empty());
}

TEST(BorderEar, grid_corner_collapses) {
  // Corner 0 of the 3x3 grid has one face (0, 1, 5, 4): an ear. 4 and 1 merge.
  QuadMesh m = quad_grid(3, 3);
  const Index f = face_with_corners(m, {0, 1, 5, 4});
  const Index k = corner_of(m, f, 0);
  int border_before = 0;
  for (Index h = 0; h < m.halfedge_capacity(); ++h) border_before += m.is_border_halfedge(h);
  ASSERT_TRUE(can_collapse_border_ear(m, f, k));
  const Index v = collapse_border_ear(m, f, k, m.position(0));
  validate(m);
  EXPECT_EQ(m.n_faces(), 8u);
  EXPECT_EQ(m.n_vertices(), 14u);
  EXPECT_TRUE(m.is_border_vertex(v));
  EXPECT_EQ(m.valence(v), 3 + 3 - 3);
  EXPECT_EQ(m.valence(5), 3);
  int border_after = 0;
  for (Index h = 0; h < m.halfedge_capacity(); ++h)
    border_after += m.is_face_live(QuadMesh::face(h)) && m.is_border_halfedge(h);
  EXPECT_EQ(border_after, border_before - 2);
  EXPECT_TRUE(m.position(v).isApprox(Vec3(0, 0, 0)));
}

TEST(BorderEar, refusals) {
  QuadMesh one = single_quad();  // a-d is a border edge too
  for (Index k = 0; k < 4; ++k) EXPECT_FALSE(can_collapse_border_ear(one, 0, k));
  QuadMesh g = quad_grid(3, 3);
  const Index f = face_with_corners(g, {0, 1, 5, 4});
  EXPECT_FALSE(can_collapse_border_ear(g, f, corner_of(g, f, 1)));  // 1 has two faces
  EXPECT_FALSE(can_collapse_border_ear(g, f, corner_of(g, f, 5)));  // interior vertex
  const Index centre = face_with_corners(g, {5, 6, 10, 9});
  for (Index k = 0; k < 4; ++k) EXPECT_FALSE(can_collapse_border_ear(g, centre, k));
  // A strip of two quads: the loop (6 edges) would close onto a pinch.
  QuadMesh strip = quad_grid(2, 1);
  for (Index ff = 0; ff < 2; ++ff)
    for (Index k = 0; k < 4; ++k) EXPECT_FALSE(can_collapse_border_ear(strip, ff, k));
  g.kill_face(f);
  EXPECT_FALSE(can_collapse_border_ear(g, f, 0));
}

namespace {

// Converted closed and open meshes, and quad grids with and without a hole.
std::vector<QuadMesh> operator_test_meshes() {
  std::vector<QuadMesh> meshes;
  for (TriMesh t : {tri_sphere(10, 14), tri_torus(16, 10), tri_grid(9, 8, 0.3), two_spheres()}) {
    clean(t);
    meshes.push_back(tri_to_quad(t));
  }
  meshes.push_back(quad_grid(6, 5));
  meshes.push_back(grid_with_hole(7));
  return meshes;
}

std::vector<Vec3> chord_midpoints(const QuadMesh& m, const Chord& c) {
  std::vector<Vec3> p;
  for (Index i = 0; i < c.pairs(); ++i) p.push_back(0.5 * (m.position(c.left[i]) + m.position(c.right[i])));
  return p;
}

// Gathers the chord through a -> b (or b -> a) and collapses it if allowed.
bool collapse_chord_through(QuadMesh& m, Index a, Index b, Chord* out = nullptr) {
  Index h = halfedge_between(m, a, b);
  if (h == kNone) h = halfedge_between(m, b, a);
  Chord c;
  if (h == kNone || !gather_chord(m, h, c, 64) || !can_collapse_chord(m, c)) return false;
  collapse_chord(m, c, chord_midpoints(m, c));
  if (out) *out = c;
  return true;
}

// After a chord of `faces` quads and `pairs` crossed edges was collapsed: a valid mesh of
// `faces_left` quads and `vertices_left` vertices with no shared diagonal.
void expect_chord_collapsed(const QuadMesh& m, const Chord& c, std::size_t faces, Index pairs, Index faces_left,
                            Index vertices_left) {
  EXPECT_EQ(c.faces.size(), faces);
  EXPECT_EQ(c.pairs(), pairs);
  validate(m);
  EXPECT_EQ(m.n_faces(), faces_left);
  EXPECT_EQ(m.n_vertices(), vertices_left);
  EXPECT_TRUE(shared_diagonals(m).empty());
}

}  // namespace

// Tube of 4 x 6 quads: vertex (i, j) is 4 j + i, ring j at z = j.
TEST(ChordCollapse, ring_comes_out_of_a_tube) {
  QuadMesh m = quad_tube(4, 6);
  Chord c;
  ASSERT_TRUE(gather_chord(m, halfedge_between(m, 8, 12), c, 64));
  EXPECT_TRUE(c.closed);
  EXPECT_EQ(c.faces.size(), 4u);
  EXPECT_EQ(c.pairs(), 4u);
  for (Index i = 0; i < c.pairs(); ++i)  // each crossed edge joins ring 2 to ring 3
    EXPECT_EQ(std::abs(int(c.left[i] / 4) - int(c.right[i] / 4)), 1);
  ASSERT_TRUE(can_collapse_chord(m, c));
  collapse_chord(m, c, chord_midpoints(m, c));
  expect_chord_collapsed(m, c, 4, 4, 20, 24);
  for (Index v : c.left) {
    EXPECT_EQ(m.valence(v), 4);
    EXPECT_NEAR(m.position(v).z(), 2.5, 1e-12);
  }
  // The chord along the tube is open (border to border): it takes one quad out of
  // every ring, 4 around -> 3; a second one would leave quads sharing two edges.
  ASSERT_TRUE(collapse_chord_through(m, 0, 1, &c));
  EXPECT_FALSE(c.closed);
  expect_chord_collapsed(m, c, 5, 6, 15, 18);
  const Index left = c.left[0];
  Index other = kNone;
  m.for_each_outgoing(left, [&](Index h) {
    if (m.twin(h) == kNone) other = m.to(h);
  });
  QuadMesh before = m;
  EXPECT_FALSE(collapse_chord_through(m, left, other));
  EXPECT_EQ(m.n_faces(), before.n_faces());
}

// 5 x 1 strip: bottom row 0..5, top row 6..11.
TEST(ChordCollapse, strip_loses_one_quad_across_not_along) {
  QuadMesh m = quad_grid(5, 1);
  Chord along;
  ASSERT_TRUE(gather_chord(m, halfedge_between(m, 3, 9), along, 64));
  EXPECT_EQ(along.faces.size(), 5u);
  EXPECT_FALSE(can_collapse_chord(m, along)) << "every rung joins two border vertices: a pinch";
  Chord across;
  ASSERT_TRUE(collapse_chord_through(m, 2, 3, &across));
  expect_chord_collapsed(m, across, 1, 2, 4, 10);
  EXPECT_TRUE(m.is_border_vertex(2));
  EXPECT_EQ(m.valence(2), 3);
}

TEST(ChordCollapse, grid_column_and_refusals) {
  QuadMesh g = quad_grid(3, 3);
  Chord c;
  ASSERT_TRUE(collapse_chord_through(g, 1, 2, &c));
  expect_chord_collapsed(g, c, 3, 4, 6, 12);

  // 3 x 3 minus its centre: the chord through the bottom row crosses two edges from the
  // outer border to the hole's; merging their ends would join the two borders into one
  // (the ring would become a disc, a valid mesh of another topology).
  QuadMesh ring = grid_with_hole(3);
  EXPECT_FALSE(collapse_chord_through(ring, 1, 5));
  EXPECT_TRUE(collapse_chord_through(ring, 1, 2));  // one quad out of the ring
  validate(ring);
  QuadMesh one = single_quad();  // nothing would be left
  EXPECT_FALSE(collapse_chord_through(one, 0, 1));
  QuadMesh box = cube();  // the two faces left would share all four corners
  EXPECT_FALSE(collapse_chord_through(box, 0, 4));
  QuadMesh torus = quad_tube(4, 3, true);  // 4 x 2 would have quads sharing two edges
  EXPECT_FALSE(collapse_chord_through(torus, 0, 4));
  QuadMesh bigger = quad_tube(4, 4, true);
  EXPECT_TRUE(collapse_chord_through(bigger, 0, 4));
  validate(bigger);
  EXPECT_EQ(bigger.n_faces(), 12u);
  // A tube wound as one helical strip: quad k is (k, k+1, k+1+n, k+n). The chord across
  // its edges k-(k+n) runs along the helix, and one turn later its left side is the
  // ring its right side had: it touches itself.
  const int n = 4, quads = 20;
  std::vector<Vec3> p;
  for (int k = 0; k <= quads + n; ++k)
    p.emplace_back(std::cos(2 * M_PI * k / n), std::sin(2 * M_PI * k / n), double(k) / n);
  std::vector<std::array<Index, 4>> q;
  for (int k = 0; k < quads; ++k) q.push_back({Index(k), Index(k + 1), Index(k + 1 + n), Index(k + n)});
  QuadMesh helix = QuadMesh::from_faces(p, q);
  Chord spiral;
  ASSERT_TRUE(gather_chord(helix, halfedge_between(helix, 8 + n, 8), spiral, 64));
  EXPECT_EQ(spiral.faces.size(), std::size_t(quads));
  EXPECT_FALSE(can_collapse_chord(helix, spiral));
  Chord longer;  // gathering stops past max_faces
  EXPECT_FALSE(gather_chord(bigger, halfedge_between(bigger, 0, 1), longer, 2));
}

// Every chord of several meshes, each collapsed on a copy where allowed: the result
// must pass validate() and have no shared diagonal.
TEST(ChordCollapse, every_allowed_chord_keeps_every_invariant) {
  std::vector<QuadMesh> meshes = operator_test_meshes();
  meshes.push_back(grid_with_hole(3));
  meshes.push_back(quad_tube(5, 4));
  meshes.push_back(quad_tube(6, 5, true));
  int collapsed = 0, refused = 0;
  for (QuadMesh& m : meshes) {
    CleanCounts counts = clean_all(m);
    (void)counts;
    for (Index h = 0; h < m.halfedge_capacity(); ++h) {
      Chord c;
      if (!gather_chord(m, h, c, 1000)) continue;
      if (!can_collapse_chord(m, c)) {
        ++refused;
        continue;
      }
      QuadMesh copy = m;
      collapse_chord(copy, c, chord_midpoints(m, c));
      ASSERT_NO_THROW(validate(copy)) << "chord of " << c.faces.size() << " faces from half-edge " << h;
      EXPECT_TRUE(shared_diagonals(copy).empty());
      EXPECT_EQ(copy.n_faces() + c.faces.size(), m.n_faces());
      EXPECT_EQ(copy.n_vertices() + c.pairs(), m.n_vertices());
      ++collapsed;
    }
  }
  EXPECT_GT(collapsed, 100);
  EXPECT_GT(refused, 100);
}

TEST(Operators, random_sequences_keep_every_invariant) {
  std::vector<QuadMesh> meshes = operator_test_meshes();
  std::mt19937 rng(7);
  int ears = 0, chords = 0;
  for (QuadMesh& m : meshes) {
    CleanCounts counts = clean_all(m);
    (void)counts;
    validate(m);
    int done = 0;
    for (int step = 0; step < 400; ++step) {
      const Index f = std::uniform_int_distribution<Index>(0, m.face_capacity() - 1)(rng);
      if (!m.is_face_live(f)) continue;
      if (step % 7 == 6) {
        Chord c;
        if (!gather_chord(m, QuadMesh::halfedge(f, step % 4), c, 1000) || !can_collapse_chord(m, c)) continue;
        collapse_chord(m, c, chord_midpoints(m, c));
        ++chords;
      } else if (step % 5 == 4) {
        const Index k = step % 4;
        if (!can_collapse_border_ear(m, f, k)) continue;
        collapse_border_ear(m, f, k, m.position(m.vertex(f, k)));
        ++ears;
      } else if (step % 2 == 0) {
        const Index k = step % 4 == 0 ? 0 : 1;
        if (!can_collapse_diagonal(m, f, k)) continue;
        const Index v = collapse_diagonal(m, f, k, collapse_position(m, f, k));
        std::vector<Index> work = {v};
        m.for_each_outgoing(v, [&](Index h) { work.push_back(m.to(h)); });
        CleanCounts c;
        clean_from(m, work, c);
      } else {
        const Index h = QuadMesh::halfedge(f, step % 4);
        const Rotation r = step % 3 ? Rotation::Ccw : Rotation::Cw;
        if (!can_rotate_edge(m, h, r)) continue;
        rotate_edge(m, h, r);
      }
      ++done;
      ASSERT_NO_THROW(validate(m)) << "after operation " << done;
    }
    EXPECT_GT(done, 20);
    m.compact();
    validate(m);
  }
  EXPECT_GT(ears, 0) << "no border ear was exercised";
  EXPECT_GT(chords, 0) << "no chord collapse was exercised";
}
