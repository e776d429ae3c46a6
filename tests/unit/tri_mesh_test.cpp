// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/mesh/tri_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <vector>

#include "fixtures/shapes.h"
#include "quadsimp/mesh/clean.h"

using namespace qs;
using namespace qs::fixtures;

TEST(FaceComponents, counts_the_pieces) {
  TriMesh t = two_spheres();
  std::vector<Index> c;
  EXPECT_EQ(face_components(triangle_adjacency(t), c), 2u);
  EXPECT_EQ(face_components(triangle_adjacency(tri_torus(8, 6)), c), 1u);
}

// Same triangles (as position triples, orientation kept), neighbours close in memory.
TEST(SortSpatially, keeps_the_surface_and_groups_neighbours) {
  TriMesh t = tri_sphere(24, 32);
  // Scramble the order first, so that the sort has something to do.
  for (Index f = 0; f + 7 < t.n_faces(); f += 3) std::swap(t.faces[f], t.faces[f + 7]);
  auto triples = [](const TriMesh& m) {
    std::vector<std::array<double, 9>> out;
    for (const auto& f : m.faces) {
      // Rotate each triangle to start at its smallest vertex position: orientation is kept.
      int s = 0;
      for (int k = 1; k < 3; ++k)
        if (std::lexicographical_compare(m.positions[f[k]].data(), m.positions[f[k]].data() + 3,
                                         m.positions[f[s]].data(), m.positions[f[s]].data() + 3))
          s = k;
      std::array<double, 9> a;
      for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 3; ++c) a[3 * k + c] = m.positions[f[(s + k) % 3]][c];
      out.push_back(a);
    }
    std::sort(out.begin(), out.end());
    return out;
  };
  auto mean_step = [](const TriMesh& m) {  // distance between consecutive faces' first corners
    double sum = 0;
    for (Index f = 1; f < m.n_faces(); ++f) sum += (m.positions[m.faces[f][0]] - m.positions[m.faces[f - 1][0]]).norm();
    return sum / (m.n_faces() - 1);
  };
  const TriMesh before = t;
  sort_spatially(t);
  EXPECT_EQ(t.n_vertices(), before.n_vertices());
  EXPECT_EQ(triples(t), triples(before));
  EXPECT_LT(mean_step(t), 0.5 * mean_step(before));
  TriMesh copy = t;
  EXPECT_EQ(clean(copy).flipped_faces, 0u);  // still consistently oriented
}

TEST(VertexRings, neighbours_once_each_in_order_and_the_border_marked) {
  // A 3 x 3 grid of squares: vertex 5 (column 1, row 1) is inner, with its four axis
  // neighbours and the diagonal ones its triangles share; the outline's 12 are border.
  const TriMesh t = tri_grid(3, 3);
  const VertexRings r = vertex_rings(t);
  auto share_a_face = [&](Index v, Index w) {
    return std::any_of(t.faces.begin(), t.faces.end(), [&](const auto& f) {
      return std::count(f.begin(), f.end(), v) && std::count(f.begin(), f.end(), w);
    });
  };
  ASSERT_EQ(r.start.size(), t.positions.size() + 1);
  Index border = 0;
  for (Index v = 0; v < t.n_vertices(); ++v) {
    const std::vector<Index> ring(r.next.begin() + r.start[v], r.next.begin() + r.start[v + 1]);
    EXPECT_TRUE(std::is_sorted(ring.begin(), ring.end()));
    EXPECT_EQ(std::adjacent_find(ring.begin(), ring.end()), ring.end()) << "vertex " << v;
    for (Index w : ring) EXPECT_TRUE(share_a_face(v, w)) << v << " " << w;
    const Vec3& p = t.positions[v];
    EXPECT_EQ(bool(r.border[v]), p.x() == 0 || p.x() == 1 || p.y() == 0 || p.y() == 1) << "vertex " << v;
    border += r.border[v];
  }
  EXPECT_EQ(border, 12u);
  const std::vector<Index> five(r.next.begin() + r.start[5], r.next.begin() + r.start[6]);
  for (Index w : {1u, 4u, 6u, 9u}) EXPECT_NE(std::find(five.begin(), five.end(), w), five.end()) << w;
  // A closed sphere has no border.
  const VertexRings s = vertex_rings(tri_sphere(6, 8));
  EXPECT_EQ(std::count(s.border.begin(), s.border.end(), 1), 0);
}

TEST(SurfaceArea, and_vertex_area_normals_of_a_cube_and_a_square) {
  TriMesh cube = fixtures::tri_cube(4);
  clean(cube);  // welds the sides along the edges
  EXPECT_NEAR(surface_area(cube), 6.0, 1e-12);
  const std::vector<Vec3> normals = vertex_area_normals(cube);
  ASSERT_EQ(normals.size(), cube.n_vertices());
  Vec3 sum = Vec3::Zero();
  for (Index v = 0; v < cube.n_vertices(); ++v) {
    // The outward normals of the sides the vertex lies on: inside a side its normal is
    // that side's exactly; on an edge or at a corner it lies between them.
    const Vec3 d = cube.positions[v] - Vec3(0.5, 0.5, 0.5);
    const Vec3 out = d.cwiseSign().cwiseProduct((d.cwiseAbs().array() > 0.5 - 1e-9).matrix().cast<double>());
    const double cos = normals[v].normalized().dot(out.normalized());
    EXPECT_GT(cos, out.cwiseAbs().sum() == 1 ? 1 - 1e-12 : 0.5) << cube.positions[v].transpose();
    sum += normals[v];
  }
  EXPECT_LT(sum.norm(), 1e-12);  // each triangle's area normal three times: none on a closed surface
  // On a flat square each vertex normal is twice the area of its triangles, which count
  // at their three corners.
  const TriMesh square = fixtures::tri_grid(10, 10);
  double length = 0;
  for (const Vec3& n : vertex_area_normals(square)) length += n.norm();
  EXPECT_NEAR(surface_area(square), 1.0, 1e-12);
  EXPECT_NEAR(length, 6.0, 1e-12);
}

TEST(VertexAngleNormals, a_cubes_corners_point_along_its_diagonals_however_split) {
  // tri_cube's sides are split along alternating diagonals, so its corners have one or
  // two triangles on each side: area weights tilt their normals, angle weights do not.
  TriMesh cube = fixtures::tri_cube(4);
  clean(cube);
  const std::vector<Vec3> normals = vertex_angle_normals(cube);
  int corners = 0;
  for (Index v = 0; v < cube.n_vertices(); ++v) {
    const Vec3 d = cube.positions[v] - Vec3(0.5, 0.5, 0.5);
    const Vec3 out = d.cwiseSign().cwiseProduct((d.cwiseAbs().array() > 0.5 - 1e-9).matrix().cast<double>());
    if (out.cwiseAbs().sum() != 3) continue;
    ++corners;
    EXPECT_NEAR(normals[v].dot(out.normalized()), 1.0, 1e-12) << cube.positions[v].transpose();
  }
  EXPECT_EQ(corners, 8);
  for (const Vec3& n : vertex_angle_normals(fixtures::tri_grid(10, 10))) EXPECT_NEAR(n.z(), 1.0, 1e-12);
}
