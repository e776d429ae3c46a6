// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/fitmap/tips.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "fixtures/shapes.h"
#include "quadsimp/convert/prepare_input.h"
#include "quadsimp/fitmap/fitmap.h"
#include "quadsimp/io/load_input.h"
#include "quadsimp/mesh/clean.h"
#include "quadsimp/metrics/metrics.h"
#include "quadsimp/reference/reference_surface.h"
#include "quadsimp/simplify/pipeline.h"

using namespace qs;
using namespace qs::fixtures;

namespace {

constexpr double kSpikeLength = 1.0, kSpikeAngle = 0.25;
const Vec3 kApexes[3] = {{0, 0, 2}, {0, 0, -2}, {2, 0, 0}};

TriMesh spiky(int rings = 60) {
  TriMesh t = spiky_sphere(rings, 2 * rings, kSpikeLength, kSpikeAngle);
  clean(t);
  return t;
}

std::vector<Vec3> tips_of(const TriMesh& t, double radius) {
  TipOptions o;
  o.radius = radius;
  std::vector<Vec3> p;
  for (Index v : find_tips(t, o)) p.push_back(t.positions[v]);
  return p;
}

// How far p is from the quads (each quad as the four triangles of its two splits).
double distance_to_quads(const QuadMesh& q, const Vec3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (Index f = 0; f < q.face_capacity(); ++f) {
    if (!q.is_face_live(f)) continue;
    const auto c = q.positions_of(q.face_vertices(f));
    double u, v;
    for (int k = 0; k < 4; ++k)
      best = std::min(best, (closest_on_triangle(p, c[k], c[(k + 1) % 4], c[(k + 2) % 4], u, v) - p).norm());
  }
  return best;
}

}  // namespace

TEST(Tips, a_spiky_sphere_has_its_three_apexes_and_nothing_else) {
  const TriMesh t = spiky();
  // From under one input edge along the spikes (about 0.2) to half a spike.
  for (double radius : {0.1, 0.3, 0.5}) {
    const std::vector<Vec3> tips = tips_of(t, radius);
    ASSERT_EQ(tips.size(), 3u) << "radius " << radius;
    for (const Vec3& apex : kApexes)
      EXPECT_TRUE(std::any_of(tips.begin(), tips.end(), [&](const Vec3& p) { return (p - apex).norm() < 1e-9; }))
          << "radius " << radius << ": no tip at " << apex.transpose();
  }
}

TEST(Tips, the_steepest_are_kept_first) {
  TipOptions o;
  o.radius = 0.3;
  o.max_tips = 1;
  const TriMesh t = spiky();
  ASSERT_EQ(find_tips(t, o).size(), 1u);
}

TEST(Tips, smooth_ridged_and_saddle_shapes_have_none) {
  // A sphere falls away at radius / (2 R): under the slope of 0.5 below its diameter.
  TriMesh sphere = tri_sphere(40, 80);
  clean(sphere);
  EXPECT_TRUE(tips_of(sphere, 0.3).empty());
  EXPECT_TRUE(tips_of(sphere, 0.8).empty());
  // A torus's outer equator is a ridge at the scale of its tube: it does not fall away
  // along the ring. Its inner half is saddle-shaped.
  TriMesh torus = tri_torus(120, 40);
  clean(torus);
  EXPECT_TRUE(tips_of(torus, 0.2).empty());
  EXPECT_TRUE(tips_of(torus, 0.5).empty());
}

TEST(Tips, a_tip_needs_the_surface_closed_around_it) {
  // The spiky sphere without its lower part: the border at z = -0.5 is 1.24 from the +x
  // apex, 2.5 from the +z one.
  TriMesh t = open_below(spiky(), -0.5);
  clean(t);
  EXPECT_EQ(tips_of(t, 0.3).size(), 2u);
  EXPECT_EQ(tips_of(t, 1.1).size(), 2u);
  EXPECT_EQ(tips_of(t, 1.3).size(), 1u);
}

TEST(Tips, a_cubes_eight_corners_whatever_their_triangles) {
  // At the scale of 150 quads each corner of a cube is a tip (its sides fall away from
  // it at a slope of 0.58), however its sides are split into triangles.
  TriMesh cube = tri_cube(20);
  clean(cube);
  const std::vector<Index> tips = find_tips(cube, tip_options_for(cube, 150));
  ASSERT_EQ(tips.size(), 8u);
  for (Index v : tips) {
    const Vec3 d = cube.positions[v] - Vec3(0.5, 0.5, 0.5);
    EXPECT_EQ(d.cwiseAbs(), Vec3(0.5, 0.5, 0.5)) << cube.positions[v].transpose();
  }
}

TEST(Simplify, kept_tips_stay_at_the_apexes_in_both_modes) {
  // Uniform mode at 100 quads also leaves an apex's vertex with three edges, which losing
  // one more would make a doublet for the cleaning to remove.
  for (Index target : {Index(0), Index(100), Index(200)}) {  // 0: adaptive, automatic halting
    double lost[2] = {0, 0};
    for (bool keep : {false, true}) {
      // Prepared as the CLI prepares a file. check_invariants is linear in the mesh per
      // change: a coarse sphere.
      const TriMesh t = spiky(30);
      Input in = prepare_input(MeshFile{t.positions, t.faces, {}}, "spiky");
      QuadMesh& q = in.quads;
      const ReferenceSurface ref(in.reference);
      SimplifyOptions opt;
      opt.keep_tips = keep;
      opt.check_invariants = true;
      opt.target_faces = target;
      Fitmaps fitmaps;
      if (target == 0) {  // the tips' scale comes from the predicted count
        fitmaps = compute_fitmaps(ref.mesh());
        opt.adaptive = opt.refuse_folds = true;
        opt.fitmaps = &fitmaps;
      }
      const SimplifyReport r = simplify(q, ref, opt);
      validate(q);
      EXPECT_EQ(r.tips, keep ? 3u : 0u) << "target " << target;
      for (const Vec3& apex : kApexes) lost[keep] = std::max(lost[keep], distance_to_quads(q, apex));
      const QuadQuality quality = quad_quality(q, &ref);
      EXPECT_EQ(quality.flipped_faces + quality.nonconvex_faces, 0u) << "target " << target << " keep " << keep;
    }
    EXPECT_GT(lost[0], 0.1) << "target " << target << ": the smoothing no longer cuts the spikes back";
    EXPECT_LT(lost[1], 1e-9) << "target " << target;
  }
}

TEST(Simplify, kept_tips_hold_a_vertex_on_each_of_the_armadillos_claws) {
  // The armadillo's claws and toes: collapses reach their vertices here (a spiky sphere's
  // apexes are never on a collapsed diagonal), and the survivor must stay on the tip. No
  // quad folds round a held tip: with tips kept, folds are refused in uniform mode too
  // (3 folded quads here when they were not).
  const std::string path = shared_dataset("armadillo");
  if (path.empty()) GTEST_SKIP() << "../shared/datasets not found";
  constexpr Index kFaces = 2000;
  for (bool adaptive : {false, true}) {
    double lost[2] = {0, 0};
    for (bool keep : {false, true}) {
      if (adaptive && !keep) continue;
      Input in = load_input(path);
      const ReferenceSurface ref(in.reference);
      SimplifyParams p;
      p.target_faces = kFaces;
      p.adaptive = adaptive;
      p.keep_tips = keep;
      const SimplifyReport r = simplify_input(in, ref, p);
      const std::vector<Index> tips = find_tips(ref.mesh(), tip_options_for(ref.mesh(), kFaces));  // as the loop
      ASSERT_GE(tips.size(), 10u);
      for (Index t : tips) lost[keep] = std::max(lost[keep], distance_to_quads(in.quads, ref.mesh().positions[t]));
      if (!keep) continue;
      EXPECT_EQ(r.tips, tips.size()) << "adaptive " << adaptive;
      EXPECT_EQ(quad_quality(in.quads, &ref).folded_faces, 0u) << "adaptive " << adaptive;
      for (Index t : tips) {
        bool on = false;
        for (Index v = 0; v < in.quads.n_vertices() && !on; ++v) on = in.quads.position(v) == ref.mesh().positions[t];
        EXPECT_TRUE(on) << "adaptive " << adaptive << ": no vertex on tip " << t;
      }
    }
    if (!adaptive) {
      EXPECT_GT(lost[0], 1.0) << "the smoothing no longer cuts the claws back";  // diagonal 229
    }
    EXPECT_EQ(lost[1], 0.0) << "adaptive " << adaptive;
  }
}

TEST(Simplify, kept_tips_stay_through_chord_collapses) {
  // Long spikes asked down to 20 quads: no diagonal collapse is left above the target,
  // and a chord collapse runs through an apex's vertex, which must stay on the apex.
  const TriMesh t = spiky_sphere(30, 60, 2.0, kSpikeAngle);
  Input in = prepare_input(MeshFile{t.positions, t.faces, {}}, "spiky");
  const ReferenceSurface ref(in.reference);
  SimplifyOptions opt;
  opt.target_faces = 20;
  opt.keep_tips = true;
  opt.check_invariants = true;
  const SimplifyReport r = simplify(in.quads, ref, opt);
  validate(in.quads);
  EXPECT_GT(r.chord_collapses, 0u);
  EXPECT_EQ(r.tips, 2u);  // the count allows two tips (one per twenty quads, and one)
  int on = 0;
  for (const Vec3& apex : {Vec3(0, 0, 3), Vec3(0, 0, -3), Vec3(3, 0, 0)})
    on += distance_to_quads(in.quads, apex) == 0.0;
  EXPECT_EQ(on, 2);
}
