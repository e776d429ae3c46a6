// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/mesh/quad_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <map>
#include <set>

#include "fixtures/shapes.h"
#include "quadsimp/util/errors.h"

using namespace qs;
using namespace qs::fixtures;

TEST(QuadMesh, single_quad_navigation) {
  QuadMesh m = single_quad();
  validate(m);
  EXPECT_EQ(m.n_faces(), 1u);
  EXPECT_EQ(m.n_vertices(), 4u);
  for (Index h = 0; h < 4; ++h) {
    EXPECT_EQ(QuadMesh::next(QuadMesh::prev(h)), h);
    EXPECT_EQ(QuadMesh::opposite_in_face(QuadMesh::opposite_in_face(h)), h);
    EXPECT_TRUE(m.is_border_halfedge(h));
    EXPECT_EQ(m.to(h), m.from(QuadMesh::next(h)));
  }
  for (Index v = 0; v < 4; ++v) {
    EXPECT_TRUE(m.is_border_vertex(v));
    EXPECT_EQ(m.valence(v), 2);  // a corner: two border edges
  }
  EXPECT_GT(m.face_area_normal(0).z(), 0);  // counter-clockwise seen from +z
}

TEST(QuadMesh, grid_valence_and_border) {
  QuadMesh m = quad_grid(4, 3);
  validate(m);
  EXPECT_EQ(m.n_faces(), 12u);
  EXPECT_EQ(m.n_vertices(), 20u);
  int inner = 0, side = 0, corner = 0;
  for (Index v = 0; v < m.n_vertices(); ++v) {
    const int val = m.valence(v);
    if (!m.is_border_vertex(v)) {
      EXPECT_EQ(val, 4);
      ++inner;
    } else if (val == 3) {
      ++side;
    } else {
      EXPECT_EQ(val, 2);
      ++corner;
    }
  }
  EXPECT_EQ(inner, 6);
  EXPECT_EQ(side, 10);
  EXPECT_EQ(corner, 4);
}

TEST(QuadMesh, one_ring_is_in_fan_order) {
  QuadMesh m = quad_grid(2, 2);
  const Index centre = 4;
  std::vector<Index> ring;
  m.for_each_outgoing(centre, [&](Index h) { ring.push_back(m.to(h)); });
  ASSERT_EQ(ring.size(), 4u);
  // Consecutive edge neighbours are corners of one face: they are 90 degrees apart.
  for (std::size_t i = 0; i < 4; ++i) {
    const Vec3 a = m.position(ring[i]) - m.position(centre);
    const Vec3 b = m.position(ring[(i + 1) % 4]) - m.position(centre);
    EXPECT_NEAR(a.dot(b), 0.0, 1e-12);
    EXPECT_GT(a.cross(b).z(), 0);  // counter-clockwise
  }
  // A border vertex starts its fan at the border and sees its faces in order.
  const Index side = 1;
  std::vector<Index> faces;
  m.for_each_outgoing(side, [&](Index h) { faces.push_back(QuadMesh::face(h)); });
  EXPECT_EQ(faces.size(), 2u);
  EXPECT_TRUE(m.is_border_halfedge(m.out(side)));
}

TEST(QuadMesh, cube_is_closed_and_valence_three) {
  QuadMesh m = cube();
  validate(m);
  for (Index v = 0; v < 8; ++v) {
    EXPECT_FALSE(m.is_border_vertex(v));
    EXPECT_EQ(m.valence(v), 3);
  }
  for (Index h = 0; h < m.halfedge_capacity(); ++h) EXPECT_NE(m.twin(h), kNone);
}

TEST(QuadMesh, hole_has_inner_border_loop) {
  QuadMesh m = grid_with_hole(3);
  validate(m);
  EXPECT_EQ(m.n_faces(), 8u);
  int border_edges = 0;
  for (Index h = 0; h < m.halfedge_capacity(); ++h) border_edges += m.is_border_halfedge(h);
  EXPECT_EQ(border_edges, 12 + 4);
  // The four hole corners are border vertices of valence 4 (2 border + 2 inner edges).
  for (Index v : {5u, 6u, 9u, 10u}) {
    EXPECT_TRUE(m.is_border_vertex(v));
    EXPECT_EQ(m.valence(v), 4);
  }
}

TEST(QuadMesh, border_in_arrives_on_the_border_and_loops_walk_both_ways) {
  // Outer corners (one face), outer edge vertices (two) and hole corners (three faces).
  QuadMesh m = grid_with_hole(3);
  int seen = 0;
  for (Index v = 0; v < m.vertex_capacity(); ++v) {
    if (!m.is_border_vertex(v)) continue;
    const Index h = m.border_in(v);
    EXPECT_TRUE(m.is_border_halfedge(h)) << v;
    EXPECT_EQ(m.to(h), v);
    EXPECT_NE(h, m.out(v));
    // The border loop continues: out(v) starts where h ends.
    EXPECT_EQ(m.from(m.out(v)), m.to(h));
    // Its neighbours along the loop are border vertices, and each walks back to v.
    EXPECT_TRUE(m.is_border_vertex(m.next_on_border(v)));
    EXPECT_EQ(m.prev_on_border(m.next_on_border(v)), v);
    EXPECT_EQ(m.next_on_border(m.prev_on_border(v)), v);
    EXPECT_NE(m.next_on_border(v), m.prev_on_border(v));
    ++seen;
  }
  EXPECT_EQ(seen, 16);
}

TEST(QuadMesh, from_faces_refuses_bad_connectivity) {
  std::vector<Vec3> p(8, Vec3::Zero());
  // Three quads on one edge.
  EXPECT_THROW(QuadMesh::from_faces(p, {{0, 1, 2, 3}, {1, 0, 4, 5}, {1, 0, 6, 7}}), InvalidInput);
  // Opposite orientation across the shared edge.
  EXPECT_THROW(QuadMesh::from_faces(p, {{0, 1, 2, 3}, {0, 1, 4, 5}}), InvalidInput);
  // Repeated vertex.
  EXPECT_THROW(QuadMesh::from_faces(p, {{0, 1, 1, 3}}), InvalidInput);
  // Out of range.
  EXPECT_THROW(QuadMesh::from_faces(p, {{0, 1, 2, 9}}), InvalidInput);
  // Two quads touching at one vertex only: a bowtie.
  EXPECT_THROW(QuadMesh::from_faces(std::vector<Vec3>(7, Vec3::Zero()), {{0, 1, 2, 3}, {0, 4, 5, 6}}), InvalidInput);
}

// Twins are matched among the half-edges leaving each vertex; a pole of valence 40,
// its quads listed out of order, checks that every one finds its own.
TEST(QuadMesh, from_faces_pairs_twins_around_a_vertex_of_high_valence) {
  constexpr Index n = 40;
  std::vector<Vec3> p = {Vec3::Zero()};
  for (Index k = 0; k < n; ++k) {
    const double a = 2 * M_PI * k / n;
    p.push_back(Vec3(std::cos(a), std::sin(a), 0));              // 1 + 2k: inner ring
    p.push_back(Vec3(1.5 * std::cos(a), 1.5 * std::sin(a), 0.1));  // 2 + 2k: outer ring
  }
  const auto inner = [&](Index k) { return 1 + 2 * (k % n); };
  const auto outer = [&](Index k) { return 2 + 2 * (k % n); };
  std::vector<std::array<Index, 4>> quads;
  for (Index j = 0; j < n; ++j) {
    const Index k = (7 * j) % n;  // 7 and 40 are coprime: every k once, out of order
    quads.push_back({0, inner(k), outer(k + 1), inner(k + 1)});
  }
  const QuadMesh m = QuadMesh::from_faces(p, quads);
  validate(m);
  EXPECT_EQ(m.valence(0), int(n));
  for (Index h = 0; h < m.halfedge_capacity(); ++h) {
    const Index t = m.twin(h);
    if (m.from(h) == 0 || m.to(h) == 0) {
      ASSERT_NE(t, kNone);
      EXPECT_EQ(m.from(t), m.to(h));
      EXPECT_EQ(m.to(t), m.from(h));
      EXPECT_EQ(m.twin(t), h);
    } else {
      EXPECT_EQ(t, kNone);  // the outer border
    }
  }
  // A third quad on one of the pole's edges, listed last.
  quads.push_back({inner(3), 0, outer(50), outer(51)});
  EXPECT_THROW(QuadMesh::from_faces(p, quads), InvalidInput);
}

TEST(QuadMesh, validate_catches_corruption) {
  // Each corruption of a 2 x 2 grid (centre vertex 4), and the check that must name it:
  // every operator test leans on validate(), so each check is shown to catch its own.
  const std::vector<std::pair<std::string, std::function<void(QuadMesh&)>>> cases = {
      {"twin of twin of half-edge " + std::to_string(quad_grid(2, 2).twin(1)) + " is not itself",
       [](QuadMesh& m) { m.set_twin(1, kNone); }},  // one-sided: its twin still points at it
      {"face 0 repeats vertex", [](QuadMesh& m) { m.set_origin(1, m.from(0)); }},
      {"vertex 1 is not a single fan",  // an interior out-edge on a border vertex hides part of its fan
       [](QuadMesh& m) { m.set_out(1, m.rotate(m.out(1))); }},
      {"vertex 8 has an invalid out half-edge",  // a corner left without faces but live
       [](QuadMesh& m) {
         m.kill_face(3);
         for (Index h = 0; h < 12; ++h)  // the other corners' fans start at the new border
           if (const Index v = m.from(h); v == 4 || v == 5 || v == 7) m.set_out(v, h), m.repair_out(v);
       }},
      {"face 0 uses a dead or invalid vertex", [](QuadMesh& m) { m.kill_vertex(4); }},
      {"has a dead twin",
       [](QuadMesh& m) {
         const Index h = m.twin(QuadMesh::halfedge(3, 0)), t = QuadMesh::halfedge(3, 0);
         m.kill_face(3);
         m.set_twin(h, t);
       }},
      {"and its twin are not reversed (orientation)",
       [](QuadMesh& m) {  // face 0's two interior edges swap twins
         std::vector<Index> inner;
         for (Index h = 0; h < 4; ++h)
           if (m.twin(h) != kNone) inner.push_back(h);
         const Index ta = m.twin(inner[0]), tb = m.twin(inner[1]);
         m.set_twin(inner[0], tb);
         m.set_twin(inner[1], ta);
       }},
      {"a directed edge appears twice", [](QuadMesh& m) { m.add_face(m.face_vertices(0)); }},
      {"vertex 4 has an invalid out half-edge", [](QuadMesh& m) { m.set_out(4, m.out(0)); }},
  };
  for (const auto& [message, corrupt] : cases) {
    QuadMesh m = quad_grid(2, 2);
    validate(m);
    corrupt(m);
    try {
      validate(m);
      ADD_FAILURE() << "not caught: " << message;
    } catch (const TopologyError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos)
          << e.what() << " (expected: " << message << ")";
    }
  }
}

TEST(QuadMesh, kill_and_compact) {
  QuadMesh m = quad_grid(3, 1);
  m.kill_face(2);
  for (Index v : {3u, 7u}) m.kill_vertex(v);
  // Face 1 = (1, 2, 6, 5): its corners 1 and 2 are the new fans of vertices 2 and 6.
  m.set_out(2, QuadMesh::halfedge(1, 1));
  m.set_out(6, QuadMesh::halfedge(1, 2));
  m.repair_out(2);
  m.repair_out(6);
  EXPECT_TRUE(m.is_border_halfedge(m.out(6)));
  validate(m);
  const std::vector<Index> live = m.live_vertex_ids();  // what compact() will give
  EXPECT_EQ(live, (std::vector<Index>{0, 1, 2, kNone, 3, 4, 5, kNone}));
  std::vector<Index> vmap, fmap;
  m.compact(&vmap, &fmap);
  EXPECT_EQ(vmap, live);
  validate(m);
  EXPECT_EQ(m.n_faces(), 2u);
  EXPECT_EQ(m.n_vertices(), 6u);
  EXPECT_EQ(fmap[2], kNone);
  EXPECT_EQ(vmap[3], kNone);
  EXPECT_EQ(vmap[4], 3u);
  EXPECT_EQ(m.face_capacity(), 2u);
}

TEST(QuadMesh, connected_components_label_each_part_apart) {
  // Two 2 x 2 grids side by side.
  std::vector<Vec3> p;
  std::vector<std::array<Index, 4>> quads;
  for (int part = 0; part < 2; ++part) {
    const Index base = Index(p.size());
    for (int j = 0; j <= 2; ++j)
      for (int i = 0; i <= 2; ++i) p.emplace_back(3.0 * part + i, j, 0);
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        const Index a = base + Index(j * 3 + i);
        quads.push_back({a, a + 1, a + 4, a + 3});
      }
  }
  QuadMesh m = QuadMesh::from_faces(p, quads);
  std::vector<Index> component;
  ASSERT_EQ(connected_components(m, component), 2u);
  ASSERT_EQ(component.size(), m.vertex_capacity());
  for (Index v = 0; v < 9; ++v) EXPECT_EQ(component[v], 0u);
  for (Index v = 9; v < 18; ++v) EXPECT_EQ(component[v], 1u);
}

namespace {

// Largest number of triangles on one segment, and whether a triangle repeats, when
// every face is split along split_diagonals().
std::pair<int, bool> split_triangles(const QuadMesh& m) {
  const auto split = split_diagonals(m);
  std::map<std::pair<Index, Index>, int> uses;
  std::set<std::array<Index, 3>> seen;
  bool repeated = false;
  for (Index f = 0; f < m.face_capacity(); ++f) {
    if (!m.is_face_live(f)) continue;
    const Index k = split[f];
    const Index a = m.vertex(f, k), b = m.vertex(f, k + 1), c = m.vertex(f, k + 2), d = m.vertex(f, k + 3);
    for (std::array<Index, 3> t : {std::array<Index, 3>{a, b, c}, std::array<Index, 3>{a, c, d}}) {
      for (int i = 0; i < 3; ++i) ++uses[std::minmax(t[i], t[(i + 1) % 3])];
      std::sort(t.begin(), t.end());
      repeated |= !seen.insert(t).second;
    }
  }
  int most = 0;
  for (const auto& [e, n] : uses) most = std::max(most, n);
  return {most, repeated};
}

}  // namespace

TEST(QuadMesh, a_shared_diagonal_renamed_by_a_merge_is_not_a_new_one) {
  // Shared: a-b (0-1), 2-4 and 3-5.
  enum : Index { a, b, a2 = 10 };
  MeshFile file = fixtures::shared_diagonal_quads();
  std::vector<Vec3>& P = file.positions;
  std::vector<std::array<Index, 4>>& Q = file.quads;
  const QuadMesh m = QuadMesh::from_faces(P, Q);
  const auto before = shared_diagonals(m);
  ASSERT_EQ(before.size(), 3u);
  const std::pair<Index, Index> none(kNone, kNone);
  EXPECT_EQ(new_shared_diagonal(m, before, before), none);
  EXPECT_EQ(new_shared_diagonal(m, {}, before), before[0]);
  EXPECT_EQ(new_shared_diagonal(m, {before[0], before[2]}, before), before[1]);
  // a merged into a vertex with a new id (a2), as a merge that keeps the other end's id
  // leaves it: a is dead, and b-a2 is a-b renamed. With a still live it is a new one.
  P.push_back(P[a]);
  for (auto& quad : Q)
    for (Index& v : quad) v = v == a ? Index(a2) : v;
  const QuadMesh merged = QuadMesh::from_faces(P, Q);
  ASSERT_FALSE(merged.is_vertex_live(a));
  const auto now = shared_diagonals(merged);
  ASSERT_EQ(now.size(), 3u);
  EXPECT_EQ(new_shared_diagonal(merged, before, now), none);
  EXPECT_EQ(new_shared_diagonal(m, before, now), std::make_pair(Index(b), Index(a2)));
  // Each of the earlier diagonals explains one of the new ones at most.
  const std::pair<Index, Index> other(b, a2 + 1);
  EXPECT_EQ(new_shared_diagonal(merged, {before[0]}, {now[0], other}), other);
}

TEST(QuadMesh, split_diagonals_keep_the_triangles_manifold) {
  // Two quads on the same four corners: split alike, they were the same two triangles.
  std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const QuadMesh pillow = QuadMesh::from_faces(p, {{0, 1, 2, 3}, {0, 3, 2, 1}});
  EXPECT_EQ(split_triangles(pillow), std::make_pair(2, false));
  // An octahedron paired into four quads: each quad's two diagonals both join corners
  // of another quad.
  const std::vector<Vec3> o = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  const QuadMesh octahedron =
      QuadMesh::from_faces(o, {{4, 0, 5, 2}, {4, 2, 5, 1}, {4, 1, 5, 3}, {4, 3, 5, 0}});
  EXPECT_FALSE(shared_diagonals(octahedron).empty());
  EXPECT_EQ(split_triangles(octahedron), std::make_pair(2, false));
  // Where no diagonal is shared, the shorter one.
  const QuadMesh g = fixtures::quad_grid(2, 2);
  QuadMesh skewed = g;
  skewed.position(4) += Vec3(0.3, 0.3, 0);  // the centre, towards corner 8
  const auto split = split_diagonals(skewed);
  for (Index f = 0; f < skewed.face_capacity(); ++f) {
    const double d0 = (skewed.position(skewed.vertex(f, 0)) - skewed.position(skewed.vertex(f, 2))).norm();
    const double d1 = (skewed.position(skewed.vertex(f, 1)) - skewed.position(skewed.vertex(f, 3))).norm();
    EXPECT_EQ(split[f], d0 > d1 ? 1 : 0) << "face " << f;
  }
}
