// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// Isotropic remeshing before the conversion (the CLI's --remesh), on CAD tessellations of
// long, thin triangles, which give poor quads as they are.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "fixtures/shapes.h"
#include "quadsimp/convert/prepare_input.h"
#include "quadsimp/mesh/clean.h"
#include "quadsimp/metrics/metrics.h"
#include "quadsimp/reference/reference_surface.h"
#include "quadsimp/remesh/isotropic_remesh.h"
#include "quadsimp/simplify/pipeline.h"

using namespace qs;
using namespace qs::fixtures;

namespace {

// One row of 128 triangles round its side, a fan of 64 round each cap's centre: every
// triangle long and thin, as CAD tessellations write a cylinder.
TriMesh one_row_cylinder() {
  return cad_cylinder(64, 1, 2.0);
}

MeshFile file_of(const TriMesh& t) {
  return MeshFile{t.positions, t.faces, {}};
}

Retriangulate remeshing() {
  return [](const TriMesh& s) { return remesh_isotropic(s); };
}

QuadQuality simplified(const MeshFile& file, const Retriangulate& retriangulate, Index target) {
  Input in = prepare_input(file, "cylinder", {}, {}, retriangulate);
  const ReferenceSurface ref(in.reference);
  SimplifyParams params;
  params.target_faces = target;
  simplify_input(in, ref, params);
  validate(in.quads);
  return quad_quality(in.quads, &ref);
}

}  // namespace

TEST(Remesh, a_cad_cylinder_becomes_even_triangles_on_its_surface_with_its_rims_kept) {
  const TriMesh cylinder = one_row_cylinder();
  RemeshReport report;
  TriMesh t = remesh_isotropic(cylinder, {}, &report);
  EXPECT_EQ(report.input_triangles, cylinder.n_faces());
  EXPECT_EQ(report.triangles, t.n_faces());
  // 1% of the diagonal (sqrt(12)); the surface (6 pi) then holds about 36,000 triangles.
  EXPECT_NEAR(report.edge_length, 0.01 * std::sqrt(12.0), 1e-12);
  EXPECT_NEAR(report.diagonal, std::sqrt(12.0), 1e-12);
  EXPECT_GT(t.n_faces(), 20000u);
  EXPECT_LT(t.n_faces(), 60000u);
  EXPECT_NEAR(mean_edge_length(t), report.edge_length, 0.25 * report.edge_length);
  Index thin = 0, longest = 0;
  for (const auto& f : t.faces) thin += thinness(t, f, longest) < 0.1;
  EXPECT_LT(thin, t.n_faces() / 1000) << "long, thin triangles left";
  // Every vertex on the faceted cylinder, a cap's plane or a side's facet (within the
  // rounding of the closest-point queries, which run in float).
  const ReferenceSurface input(cylinder);
  for (const Vec3& p : t.positions) ASSERT_LT((input.closest(p).point - p).norm(), 1e-6);
  // Both rims stay edges (the feature angle, 30 degrees, keeps edges of 90): each holds a
  // vertex at least every 4/3 of the edge length (the longest vcglib leaves unsplit), its
  // vertices sliding along it but never off it. Without the feature angle (180) they are
  // rounded off and none is left on the rims.
  auto rim_vertices = [](const TriMesh& m, double z) {
    return std::count_if(m.positions.begin(), m.positions.end(), [&](const Vec3& p) {
      return std::abs(p.z() - z) < 1e-6 && p.head<2>().norm() > std::cos(M_PI / 64) - 1e-6;
    });
  };
  const double most_apart = 4.0 / 3.0 * report.edge_length;
  EXPECT_GE(rim_vertices(t, 0.0), std::floor(2 * M_PI / most_apart));
  EXPECT_GE(rim_vertices(t, 2.0), std::floor(2 * M_PI / most_apart));
  RemeshOptions no_features;
  no_features.feature_angle_deg = 180;
  const TriMesh rounded = remesh_isotropic(cylinder, no_features);
  EXPECT_LT(rim_vertices(rounded, 0.0) + rim_vertices(rounded, 2.0), 10);
  // The remeshing is a clean closed surface already.
  EXPECT_FALSE(clean(t).changed_faces());
}

TEST(Remesh, the_edge_length_follows_the_quads_asked_for) {
  const TriMesh cylinder = one_row_cylinder();
  const double diagonal = std::sqrt(12.0), area = 6 * M_PI;  // less the facets' shortfall
  EXPECT_NEAR(remesh_edge_length(cylinder, 0), 0.01 * diagonal, 1e-12);
  EXPECT_NEAR(remesh_edge_length(cylinder, 100), 0.01 * diagonal, 1e-12);  // 1% gives plenty
  // 20,000 quads asked for: edges for four times as many.
  EXPECT_NEAR(remesh_edge_length(cylinder, 20000), std::sqrt(area / 80000), 2e-4);
  // remesh_isotropic() takes that length for the quads it is told of, or the share given
  // (no rounds run: the length alone is looked at).
  RemeshOptions lengths;
  lengths.iterations = 0;
  lengths.target_quads = 20000;
  RemeshReport report;
  remesh_isotropic(cylinder, lengths, &report);
  EXPECT_EQ(report.edge_length, remesh_edge_length(cylinder, 20000));
  lengths.edge_share = 0.04;
  remesh_isotropic(cylinder, lengths, &report);
  EXPECT_NEAR(report.edge_length, 0.04 * diagonal, 1e-12);
  // A large surface in a small box: no more than about 200,000 triangles. The cylinder
  // wound a hundred times inside itself, as a stack of copies shifted by 1e-4.
  TriMesh stack;
  for (int i = 0; i < 100; ++i) {
    TriMesh copy = cylinder;
    for (Vec3& p : copy.positions) p *= 1 + 1e-4 * i;
    append(stack, copy);
  }
  const double length = remesh_edge_length(stack, 0);
  EXPECT_GT(length, 0.01 * diagonal);
  EXPECT_NEAR(surface_area(stack) / (0.433 * length * length), kMostTriangles, 1);
}

TEST(Remesh, a_cad_cylinder_simplifies_to_even_quads_once_remeshed) {
  const MeshFile file = file_of(one_row_cylinder());
  // As it is, its quads keep the caps' poles and fold (the README's Limits).
  const QuadQuality as_is = simplified(file, {}, 100);
  EXPECT_TRUE(as_is.max_valence > 6 || as_is.folded_faces > 0 || as_is.faces > 100)
      << as_is.max_valence << " " << as_is.folded_faces << " " << as_is.faces;
  const Input in = prepare_input(file, "cylinder", {}, {}, remeshing());
  EXPECT_EQ(in.input_surface.n_faces(), file.triangles.size()) << "the input is kept as it was";
  EXPECT_GT(in.reference.n_faces(), 100 * in.input_surface.n_faces()) << "the remeshing is the reference";
  EXPECT_FALSE(in.was_pure_quad);
  const QuadQuality remeshed = simplified(file, remeshing(), 100);
  EXPECT_EQ(remeshed.faces, 100u);
  EXPECT_LE(remeshed.max_valence, 5);
  EXPECT_GE(remeshed.regular_percent, 70.0);
  EXPECT_EQ(remeshed.folded_faces + remeshed.flipped_faces + remeshed.nonconvex_faces, 0u);
}

TEST(Remesh, a_quad_meshs_triangles_are_remeshed_too) {
  // A quad mesh is taken as it is, unless asked to be remeshed.
  const QuadMesh tube = quad_tube(16, 4, true);
  MeshFile file;
  file.positions = tube.positions();
  file.quads = tube.quads();
  ASSERT_TRUE(file.is_pure_quad());
  EXPECT_TRUE(prepare_input(file, "tube").was_pure_quad);
  const Input in = prepare_input(file, "tube", {}, {}, remeshing());
  EXPECT_FALSE(in.was_pure_quad);
  EXPECT_EQ(in.input_surface.n_faces(), 2 * file.quads.size());
  EXPECT_GT(in.quads.n_faces(), 10 * file.quads.size());
}
