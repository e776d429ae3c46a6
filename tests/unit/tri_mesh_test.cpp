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
