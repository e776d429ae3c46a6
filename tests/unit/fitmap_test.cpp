// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/fitmap/fitmap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iostream>

#include <tbb/task_arena.h>

#include "fixtures/shapes.h"
#include "quadsimp/convert/tri_to_quad.h"
#include "quadsimp/fitmap/anisotropy.h"
#include "quadsimp/io/load_input.h"
#include "quadsimp/mesh/clean.h"
#include "quadsimp/metrics/metrics.h"
#include "quadsimp/simplify/pipeline.h"

using namespace qs;
using namespace qs::fixtures;

namespace {

// A square grid over [-h, h]^2 lifted by z(x, y).
template <class Height>
TriMesh height_field(int n, double h, Height z) {
  TriMesh t = tri_grid(n, n);
  for (Vec3& p : t.positions) {
    p.x() = (2 * p.x() - 1) * h;
    p.y() = (2 * p.y() - 1) * h;
    p.z() = z(p.x(), p.y());
  }
  clean(t);
  return t;
}

// A sphere flattened to a fifth of its height, with bumps: it fails the M test at every
// radius, soonest near its rim, and no two vertices are alike.
TriMesh flat_bumpy_ellipsoid(int rings, int segments) {
  TriMesh t = tri_sphere(rings, segments);
  for (Vec3& p : t.positions) {
    p *= 1 + 0.1 * std::sin(17 * p.x()) * std::cos(13 * p.y());
    p.z() *= 0.2;
  }
  return t;
}

Index centre_vertex(const TriMesh& t) {
  Index best = 0;
  for (Index v = 0; v < t.n_vertices(); ++v)
    if (t.positions[v].head<2>().norm() < t.positions[best].head<2>().norm()) best = v;
  return best;
}

// A sphere and, far away, a small triangle that enlarges the bounding box so that the
// largest fitmap radius exceeds the sphere.
TriMesh sphere_with_far_triangle(int rings, int segments) {
  TriMesh t = tri_sphere(rings, segments);
  TriMesh far;
  far.positions = {{20, 0, 0}, {20.1, 0, 0}, {20, 0.1, 0}};
  far.faces = {{0, 1, 2}};
  append(t, far);
  clean(t);
  return t;
}

// The fitmaps of a unit sphere with F_M from 1 mu at its bottom to 5 mu at its top: as
// its faces grow, the M-fitmap blocks them from the bottom up.
Fitmaps graded_m(const TriMesh& sphere, double mu) {
  Fitmaps f = compute_fitmaps(sphere);
  for (Index v = 0; v < sphere.n_vertices(); ++v) f.m[v] = float((3 + 2 * sphere.positions[v].z()) * mu);
  return f;
}

// Adaptive mode driven by f.
SimplifyOptions adaptive_options(const Fitmaps& f, Index target = 0) {
  SimplifyOptions opt;
  opt.adaptive = true;
  opt.fitmaps = &f;
  opt.target_faces = target;
  return opt;
}

// t's conversion simplified into q with opt, and checked.
SimplifyReport simplify_conversion(const TriMesh& t, const ReferenceSurface& ref, const SimplifyOptions& opt,
                                   QuadMesh& q) {
  q = tri_to_quad(t);
  const SimplifyReport r = simplify(q, ref, opt);
  validate(q);
  return r;
}

// Adaptive simplification of t (fitmaps computed on t).
SimplifyReport simplify_adaptive(const TriMesh& t, QuadMesh& q, Index target = 0) {
  const ReferenceSurface ref(t);
  const Fitmaps f = compute_fitmaps(t);
  const SimplifyReport r = simplify_conversion(t, ref, adaptive_options(f, target), q);
  EXPECT_TRUE(shared_diagonals(q).empty());
  return r;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// d^T G d / |d|^2 for the metric a stores at vertex v.
double metric_along(const Anisotropy& a, Index v, const Vec3& d) {
  const auto& g = a.g[v];
  const Vec3 u = d.normalized();
  return g[0] * u.x() * u.x() + g[3] * u.y() * u.y() + g[5] * u.z() * u.z() +
         2 * (g[1] * u.x() * u.y() + g[2] * u.x() * u.z() + g[4] * u.y() * u.z());
}

}  // namespace

TEST(Fitmaps, radii_are_exponential_from_mean_edge_to_quarter_diagonal) {
  const TriMesh t = height_field(20, 1.0, [](double, double) { return 0.0; });
  const auto r = fitmap_radii(t, 8);
  ASSERT_EQ(r.size(), 9u);
  EXPECT_NEAR(r.back(), bbox_diagonal(t.positions) / 4, 1e-12);
  for (std::size_t i = 1; i + 1 < r.size(); ++i) EXPECT_NEAR(r[i] / r[i - 1], r[i + 1] / r[i], 1e-9);
}

TEST(Fitmaps, plane_has_zero_s_and_the_largest_m) {
  const TriMesh t = height_field(40, 1.0, [](double, double) { return 0.0; });
  const Fitmaps f = compute_fitmaps(t);
  const double rh = fitmap_radii(t, 8).back();
  // F_S = sqrt(a) with a ~ E / r^2 turns double round-off in E (~1e-9) into ~1e-4;
  // a unit sphere gives 0.54 at this scale.
  for (Index v = 0; v < t.n_vertices(); ++v) {
    EXPECT_LT(f.s[v], 1e-3);
    EXPECT_NEAR(f.m[v], rh, 1e-6 * rh);
  }
}

TEST(Fitmaps, sphere_cap_s_matches_the_analytic_growth) {
  // On a sphere of radius R a disc of radius r deviates from its plane by
  // rho^2 / 2R; its RMS is r^2 / (4 sqrt(3) R), so F_S = sqrt(1 / (4 sqrt(3) R)).
  for (double R : {1.0, 2.0}) {
    const TriMesh t = height_field(80, 0.4 * R, [R](double x, double y) { return std::sqrt(R * R - x * x - y * y); });
    const Fitmaps f = compute_fitmaps_unsmoothed(t);
    const double expected = std::sqrt(1.0 / (4 * std::sqrt(3.0) * R));
    EXPECT_NEAR(f.s[centre_vertex(t)], expected, 0.1 * expected) << "R = " << R;
  }
}

TEST(Fitmaps, sphere_cap_s_does_not_depend_on_the_grid) {
  // A ball takes the triangles whose centroid lies in it. Taking only those with every
  // corner inside shrank the small balls by about an edge, so F_S fell with coarser grids:
  // 0.82 of the analytic value on a 40 x 40 grid, 1.03 on 80 x 80 (1.01 and 1.03 now).
  const double expected = std::sqrt(1.0 / (4 * std::sqrt(3.0)));
  for (int n : {40, 80, 160}) {
    const TriMesh t = height_field(n, 0.4, [](double x, double y) { return std::sqrt(1 - x * x - y * y); });
    EXPECT_NEAR(compute_fitmaps_unsmoothed(t).s[centre_vertex(t)], expected, 0.05 * expected) << n << " x " << n;
  }
}

TEST(Fitmaps, do_not_depend_on_where_the_mesh_is) {
  // A million units out (survey coordinates), the moments' covariance cancelled every
  // digit: the plane fits, so both fitmaps, were noise.
  const TriMesh t = height_field(60, 0.4, [](double x, double y) { return std::sqrt(1.0 - x * x - y * y); });
  TriMesh far = t;
  for (Vec3& p : far.positions) p += Vec3(1e6, -2e6, 3e6);
  const Fitmaps a = compute_fitmaps_unsmoothed(t), b = compute_fitmaps_unsmoothed(far);
  const Index c = centre_vertex(t);
  EXPECT_NEAR(b.s[c], a.s[c], 1e-3 * a.s[c]);
  EXPECT_EQ(b.m[c], a.m[c]);
}

TEST(Fitmaps, do_not_depend_on_the_number_of_threads) {
  // Each vertex's balls are its own work, with per-thread scratch: one thread and two
  // must give the same bits, exact and cell levels alike.
  const TriMesh t = flat_bumpy_ellipsoid(60, 90);
  Fitmaps one, two;
  tbb::task_arena(1).execute([&] { one = compute_fitmaps(t); });
  tbb::task_arena(2).execute([&] { two = compute_fitmaps(t); });
  EXPECT_EQ(one.s, two.s);
  EXPECT_EQ(one.m, two.m);
}

TEST(Fitmaps, cylinder_s_is_lower_than_the_sphere) {
  // Bent in one direction only: RMS r^2 / (8R), F_S = sqrt(1 / (8R)).
  const TriMesh t = height_field(80, 0.4, [](double x, double) { return std::sqrt(1.0 - x * x); });
  const Fitmaps f = compute_fitmaps_unsmoothed(t);
  const double expected = std::sqrt(1.0 / 8.0);
  EXPECT_NEAR(f.s[centre_vertex(t)], expected, 0.1 * expected);
}

TEST(Fitmaps, sphere_m_stops_where_the_cap_passes_tau) {
  // Triangles past 90 degrees from p face against the plane; they reach 5% of the cap
  // at a chord of 1.4507 R.
  const TriMesh t = sphere_with_far_triangle(60, 90);
  const Fitmaps f = compute_fitmaps_unsmoothed(t);
  const auto r = fitmap_radii(t, 8);
  const double chord = 1.4507;
  double expected = r[0];
  for (double ri : r)
    if (ri < chord) expected = ri;
  std::vector<double> m;
  for (Index v = 0; v + 3 < t.n_vertices(); ++v) m.push_back(f.m[v]);
  EXPECT_NEAR(median(m), expected, 1e-6 * expected);  // F_M is stored as float
}

TEST(Fitmaps, fast_method_matches_brute_force) {
  // Within 1% (median relative difference) and 5% (90th percentile) at a sample of
  // vertices, on the bunny if available, otherwise on a bumpy sphere.
  TriMesh t;
  const std::string bunny = "/usr/share/glmark2/models/bunny.obj";
  if (std::ifstream(bunny)) {
    t = load_input(bunny).reference;
  } else {
    t = tri_sphere(80, 120);
    for (Vec3& p : t.positions) p *= 1 + 0.05 * std::sin(7 * p.x()) * std::cos(5 * p.y());
  }
  const Fitmaps fast = compute_fitmaps_unsmoothed(t);
  std::vector<Index> sample;
  for (Index v = 0; v < t.n_vertices(); v += 97) sample.push_back(v);
  const Fitmaps ref = fitmaps_brute_force(t, sample);
  std::vector<double> ds, dm;
  for (std::size_t j = 0; j < sample.size(); ++j) {
    if (ref.s[j] > 0) ds.push_back(std::abs(fast.s[sample[j]] - ref.s[j]) / ref.s[j]);
    dm.push_back(std::abs(fast.m[sample[j]] - ref.m[j]) / ref.m[j]);
  }
  // The cells take triangles by their centroids, as the exact balls do: with the exact
  // balls taking only triangles with every corner inside, S was 4.1% off at the median
  // and 13% at the 90th percentile on the bunny (0.15% and 1.2% since).
  EXPECT_LT(median(ds), 0.01);
  EXPECT_LT(median(dm), 0.01);
  std::sort(ds.begin(), ds.end());
  EXPECT_LT(ds[ds.size() * 9 / 10], 0.05);
}

TEST(Fitmaps, radii_past_a_vertexs_failure_are_skipped_without_changing_anything) {
  // The fast method leaves out the balls summarise() would not read; with every radius
  // evaluated exactly it must then give brute force's values to the bit. On the flat
  // ellipsoid the share of triangles facing against the plane rises and falls with the
  // bumps, so a vertex settled too early would show. The paper's S (local_s off) reads
  // every radius, so nothing may be skipped for it.
  const TriMesh t = flat_bumpy_ellipsoid(40, 60);
  std::vector<Index> all(t.n_vertices());
  for (Index v = 0; v < t.n_vertices(); ++v) all[v] = v;
  for (bool local_s : {true, false}) {
    SCOPED_TRACE(local_s);
    FitmapOptions opt;
    opt.exact_up_to = 1e9;
    opt.local_s = local_s;
    const Fitmaps fast = compute_fitmaps_unsmoothed(t, opt);
    const Fitmaps ref = fitmaps_brute_force(t, all, opt);
    const std::vector<double> radii = fitmap_radii(t, opt.levels);
    Index early = 0, earliest = 0;
    for (Index v = 0; v < t.n_vertices(); ++v) {
      EXPECT_EQ(fast.s[v], ref.s[v]) << v;
      EXPECT_EQ(fast.m[v], ref.m[v]) << v;
      early += fast.m[v] < float(radii[opt.levels - 1]);
      earliest += fast.m[v] < float(radii[2]);
    }
    EXPECT_GT(early, t.n_vertices() / 4);  // these fail before the largest ball
    EXPECT_GT(earliest, 0u);               // and these before the three radii S needs
  }
}

TEST(Fitmaps, vertices_sharing_a_cell_search_get_their_own_balls) {
  // The vertices that start from one cell share the cells every one of their balls
  // holds; each must still get its own ball. The sums are added in another order, so
  // the values may differ in their last bits only. On the flat ellipsoid the share of
  // triangles facing against the plane rises and falls with the bumps, so a ball
  // holding one cell too many or too few shows in M as well as in S.
  const TriMesh t = flat_bumpy_ellipsoid(120, 180);
  FitmapOptions each;
  each.share_cell_searches = false;
  const Fitmaps shared = compute_fitmaps_unsmoothed(t), own = compute_fitmaps_unsmoothed(t, each);
  Index differ = 0;
  for (Index v = 0; v < t.n_vertices(); ++v) {
    EXPECT_NEAR(shared.s[v], own.s[v], 1e-6 * own.s[v]) << v;
    EXPECT_EQ(shared.m[v], own.m[v]) << v;
    differ += shared.s[v] != own.s[v];
  }
  EXPECT_LT(differ, t.n_vertices() / 100);
}

TEST(Adaptive, m_fitmap_refuses_collapses_that_grow_faces_past_it) {
  TriMesh t = tri_grid(30, 30, 0.2);
  clean(t);
  const ReferenceSurface ref(t);
  QuadMesh q = tri_to_quad(t);
  const Index before = q.n_faces();
  Fitmaps f = compute_fitmaps(t);
  // F_M below the radius of every face now: no collapse may go through.
  const double tiny = 0.1 * ref.mean_edge_length();
  std::fill(f.m.begin(), f.m.end(), float(tiny));
  SimplifyOptions opt = adaptive_options(f);
  const SimplifyReport r = simplify(q, ref, opt);
  EXPECT_EQ(r.collapses, 0u);
  EXPECT_GT(r.refused_fitmap, 0u);
  EXPECT_EQ(q.n_faces(), before);
  EXPECT_TRUE(r.ran_out);  // blocked from the start: no share was added, nothing was left
  validate(q);
}

TEST(Adaptive, m_fitmap_refuses_chord_collapses_too) {
  // A bent strip one quad wide shortens only by chord collapses (see Simplify's strip
  // test); the faces beside a chord grow, so F_M must be able to refuse it.
  TriMesh t = tri_grid(60, 1);
  for (Vec3& p : t.positions) p = Vec3(p.x(), p.y() / 60, 0.2 * std::sin(M_PI * p.x()));
  clean(t);
  const ReferenceSurface ref(t);
  Fitmaps f = compute_fitmaps(t);
  SimplifyOptions opt = adaptive_options(f, 15);
  auto run = [&](double fm) {
    std::fill(f.m.begin(), f.m.end(), float(fm));
    QuadMesh q = tri_to_quad(t);
    const SimplifyReport r = simplify(q, ref, opt);
    validate(q);
    return r;
  };
  const SimplifyReport free_run = run(1.0);  // the strip's length: F_M refuses nothing
  EXPECT_GT(free_run.chord_collapses, 0u);
  EXPECT_LE(free_run.faces, 15u);
  const SimplifyReport r = run(0.1 * ref.mean_edge_length());
  EXPECT_EQ(r.chord_collapses, 0u);
  EXPECT_GT(r.refused_fitmap, 0u);
  EXPECT_EQ(r.faces, 60u);
}

TEST(Adaptive, auto_halt_terminates) {
  QuadMesh q;
  const SimplifyReport r = simplify_adaptive(sphere_with_far_triangle(30, 40), q);  // until nothing is feasible
  EXPECT_GT(r.collapses, 0u);
  EXPECT_FALSE(r.cancelled);
  EXPECT_LT(q.n_faces(), r.initial_faces);
  EXPECT_GE(q.n_faces(), 6u + 1u);  // the sphere keeps a closed mesh, the far triangle its quad
}

TEST(Adaptive, auto_halt_takes_debris_down_to_its_share_of_the_count) {
  // A sphere and, beside it, a strip of 0.1 by 2.4 (24 squares): scan debris, which no
  // diagonal collapse shrinks (each would pinch it). Halted by the sphere's measure, it
  // kept all its quads; its share of the count reached is under one quad, and chords
  // take it down to the last.
  TriMesh t = tri_sphere(30, 40);
  TriMesh strip = tri_grid(24, 1);
  for (Vec3& p : strip.positions) p = Vec3(3 + 2.4 * p.x(), 0.1 * p.y(), 0);
  append(t, strip);
  clean(t);
  const ReferenceSurface ref(t);
  const Fitmaps f = compute_fitmaps(t);
  auto run = [&](bool chords, QuadMesh& q) {
    SimplifyOptions opt = adaptive_options(f);
    opt.chord_collapses = chords;
    opt.check_invariants = true;  // the pieces' face counts too
    return simplify_conversion(t, ref, opt, q);
  };
  auto on_strip = [](const QuadMesh& q) {
    Index n = 0;
    for (Index g = 0; g < q.face_capacity(); ++g) n += q.is_face_live(g) && q.face_centroid(g).x() > 2;
    return n;
  };
  QuadMesh q, kept;
  const SimplifyReport r = run(true, q);
  EXPECT_EQ(r.pieces, 2u);
  EXPECT_GT(r.chord_collapses, 0u);
  EXPECT_EQ(on_strip(q), 1u);
  EXPECT_EQ(r.pieces_above_share, 1u);  // the strip's last quad
  // Without chords the strip keeps its quads, and the sphere, under its share, is the same.
  const SimplifyReport without = run(false, kept);
  EXPECT_EQ(on_strip(kept), 24u);
  EXPECT_EQ(kept.n_faces() - on_strip(kept), q.n_faces() - on_strip(q));
  EXPECT_EQ(without.collapses, r.collapses);
}

TEST(Adaptive, auto_halt_shares_its_count_by_the_faces_the_sizes_ask_for) {
  // Two spheres alike but for F_S, twice as large on the second, whose sizes so ask for
  // four times the quads. Both have the same F_M (graded as graded_m()'s): the first
  // sphere's larger quads meet it first, and its blocked faces halt the run while the
  // second still has collapses left. Shared by the sizes, the count leaves the second its
  // quads and takes the first on down until F_M holds it (measured: 261 and 795 quads);
  // shared by area, as a face target is (share_target()), the second was taken down to
  // about half of the count instead (393 and 596; a scratch build).
  TriMesh t = tri_sphere(30, 40);
  TriMesh other = t;
  for (Vec3& p : other.positions) p.x() += 3;
  append(t, other);
  clean(t);
  const ReferenceSurface ref(t);
  Fitmaps f{std::vector<float>(t.n_vertices()), std::vector<float>(t.n_vertices())};  // both set below
  const double mu = ref.mean_edge_length();
  for (Index v = 0; v < t.n_vertices(); ++v) {
    f.s[v] = t.positions[v].x() > 1.5 ? 2.f : 1.f;
    f.m[v] = float((3 + 2 * t.positions[v].z()) * mu);
  }
  QuadMesh q;
  const SimplifyReport r = simplify_conversion(t, ref, adaptive_options(f), q);
  Index second = 0;
  for (Index g = 0; g < q.face_capacity(); ++g) second += q.is_face_live(g) && q.face_centroid(g).x() > 1.5;
  const Index first = q.n_faces() - second;
  EXPECT_EQ(r.pieces, 2u);
  EXPECT_FALSE(r.ran_out);
  EXPECT_GT(second, 2 * first) << first << " and " << second << " quads";
  EXPECT_EQ(r.pieces_above_share, 1u);  // the first, held above its share by F_M
}

TEST(Adaptive, auto_halt_stops_once_the_m_fitmap_blocks_its_share) {
  // F_M graded up the sphere (graded_m()): the blocked share rises steadily.
  TriMesh t = tri_sphere(30, 40);
  clean(t);
  const ReferenceSurface ref(t);
  const Fitmaps f = graded_m(t, ref.mean_edge_length());
  auto run = [&](double share, Index target, QuadMesh& q) {
    SimplifyOptions opt = adaptive_options(f);
    opt.halt_share = share;
    opt.target_faces = target;
    opt.fine_phase = 0;  // the same smoothing with and without a target: the same run
    return simplify_conversion(t, ref, opt, q);
  };
  QuadMesh paper, halted, before, same;
  const SimplifyReport until_nothing = run(1.0, 0, paper);  // the paper's rule
  const SimplifyReport at_share = run(0.3, 0, halted);
  EXPECT_GE(at_share.blocked_share, 0.3);
  EXPECT_GT(halted.n_faces(), paper.n_faces());
  EXPECT_GT(until_nothing.blocked_share, at_share.blocked_share);
  // Halted by the share; the paper's rule ends when nothing is left, which is its halt.
  EXPECT_FALSE(at_share.ran_out);
  EXPECT_FALSE(until_nothing.ran_out);
  // The same run stopped by a face target 10% above the halting count had not reached
  // the share (it is measured at steps down to 1% of the faces; near 0.3 it wavers by
  // about 1%: measured 0.284 at 373 quads, 0.303 at 350, 0.3015 at 339 where it halted),
  // and one stopped at the halting count is the same mesh.
  const SimplifyReport early = run(0.3, Index(std::ceil(1.1 * halted.n_faces())), before);
  const SimplifyReport at = run(0.3, halted.n_faces(), same);
  EXPECT_LT(early.blocked_share, 0.3);
  EXPECT_NEAR(at.blocked_share, at_share.blocked_share, 1e-12);
}

TEST(Adaptive, auto_halt_counts_only_the_share_the_collapses_block) {
  // F_M below the input's own faces on the cap above z = 0.6 (a fifth of the sphere):
  // blocked from the start, so that share does not count towards the halt, and the
  // rest coarsens until it too is blocked.
  TriMesh t = tri_sphere(30, 40);
  clean(t);
  const ReferenceSurface ref(t);
  Fitmaps f = compute_fitmaps(t);
  const double mu = ref.mean_edge_length();
  for (Index v = 0; v < t.n_vertices(); ++v)
    f.m[v] = float(t.positions[v].z() > 0.6 ? 0.1 * mu : (3 + 2 * t.positions[v].z()) * mu);
  QuadMesh q = tri_to_quad(t);
  const Index before = q.n_faces();
  SimplifyOptions opt = adaptive_options(f);
  opt.halt_share = 0.1;
  opt.fine_phase = 0;  // the share is measured from the first collapse on
  const SimplifyReport r = simplify(q, ref, opt);
  validate(q);
  // Measured: 1,160 -> 872 quads, blocked share 0.33 at the end. Counting the cap, the
  // run stopped after its first collapse.
  EXPECT_GT(r.collapses, before / 10);
  EXPECT_GT(r.blocked_share, 0.25);
}

TEST(Adaptive, auto_halt_measures_a_height_field_before_it_runs_out) {
  // Nothing in a height field faces away from its fitted planes: F_M is the largest
  // radius everywhere, and the count predicted from it a few faces, far below where the
  // reach blocks the halting share. The measure must not wait for the predicted count
  // (9): waiting, this field ran out of collapses at 119 quads (the share, measured only
  // then, 0.47); measured at the halvings before it, it halts by the share at 225.
  TriMesh t = tri_grid(60, 60);
  for (Vec3& p : t.positions) p.z() = 0.1 * std::sin(6 * M_PI * p.x()) * std::sin(6 * M_PI * p.y());
  const ReferenceSurface ref(t);
  const Fitmaps f = compute_fitmaps(t);
  QuadMesh q = tri_to_quad(t);
  SimplifyOptions opt = adaptive_options(f);
  opt.refuse_folds = true;  // as the pipeline runs it
  opt.max_aspect = SimplifyParams().max_aspect;
  opt.reach = SimplifyParams().reach;
  const SimplifyReport r = simplify(q, ref, opt);
  validate(q);
  EXPECT_LT(r.predicted_faces, 0.1 * double(r.faces));
  EXPECT_FALSE(r.ran_out);
  EXPECT_GE(r.blocked_share, opt.halt_share);
  EXPECT_GT(r.faces, 160u);
}

TEST(Adaptive, slack_loosens_the_loop_but_halting_measures_the_bound_itself) {
  // The sphere of auto_halt_stops_once_the_m_fitmap_blocks_its_share. A slack of 1.25
  // over F_M and a bound of F_M / 0.8 without slack refuse the same collapses, so to a
  // face target they give the same mesh; halted automatically, the first measures the
  // blocked share at F_M, which its faces reach first, and stops with more quads.
  TriMesh t = tri_sphere(30, 40);
  clean(t);
  const ReferenceSurface ref(t);
  const Fitmaps f = graded_m(t, ref.mean_edge_length());
  auto run = [&](double m_factor, double m_slack, Index target, QuadMesh& q) {
    q = tri_to_quad(t);
    SimplifyOptions opt = adaptive_options(f, target);
    opt.m_factor = m_factor;
    opt.m_slack = m_slack;
    opt.reach = 1;  // every face under the reach, where the slack applies, and no ray cast
    opt.halt_share = 0.3;
    opt.fine_phase = 0;
    const SimplifyReport r = simplify(q, ref, opt);
    validate(q);
    return r;
  };
  QuadMesh slack, looser, paper;
  const SimplifyReport with_slack = run(1.0, 1.25, 0, slack);
  const SimplifyReport with_looser_bound = run(0.8, 1.0, 0, looser);
  run(1.0, 1.0, 0, paper);
  EXPECT_FALSE(with_slack.ran_out);
  EXPECT_FALSE(with_looser_bound.ran_out);
  EXPECT_GE(with_slack.blocked_share, 0.3);
  EXPECT_GT(slack.n_faces(), looser.n_faces());
  // Past the bound: the slack's faces are larger than the paper's bound lets them be.
  EXPECT_LT(slack.n_faces(), paper.n_faces());
  QuadMesh a, b;
  run(1.0, 1.25, slack.n_faces(), a);
  run(0.8, 1.0, slack.n_faces(), b);
  ASSERT_EQ(a.n_faces(), b.n_faces());
  ASSERT_EQ(a.vertex_capacity(), b.vertex_capacity());
  for (Index v = 0; v < a.vertex_capacity(); ++v) EXPECT_EQ(a.position(v), b.position(v));
}

TEST(Adaptive, no_quad_bends_over_the_gargoyles_thin_parts) {
  // Automatic halting on the gargoyle, as the CLI and the filters run it: without
  // refuse_folds 11 quads ended bent past 90 degrees over its thin parts.
  const std::string path = shared_dataset("gargoyle");
  if (path.empty()) GTEST_SKIP() << "../shared/datasets not found";
  const Input in = load_input(path);
  const ReferenceSurface ref(in.reference);
  SimplifyParams params;
  params.adaptive = params.auto_halt = true;
  Input run = in;
  simplify_input(run, ref, params);
  validate(run.quads);
  const QuadQuality q = quad_quality(run.quads, &ref);
  EXPECT_EQ(q.folded_faces, 0u);
  EXPECT_EQ(q.flipped_faces + q.nonconvex_faces, 0u);
  EXPECT_GE(q.regular_percent, 70.0);
  EXPECT_LE(q.max_valence, 6);
}

TEST(Adaptive, no_quad_folds_at_the_holes_of_a_damaged_scan) {
  // A sphere, a torus and a bumpy grid with a tenth of their triangles taken out at
  // random. While smoothing moves of border vertices were not held to refuse_folds, each of
  // these runs ended with folded quads at the holes (5 and 3, 6 and 7, 1 and 5; 38 of 48
  // such runs with 2 to 10% taken out).
  struct Case {
    TriMesh mesh;
    unsigned seed;
  };
  for (const Case& c : {Case{tri_sphere(60, 120), 2}, Case{tri_torus(120, 48), 2}, Case{tri_grid(80, 80, 0.3), 1}}) {
    SCOPED_TRACE(c.mesh.n_faces());
    const TriMesh holey = with_holes(c.mesh, 0.1, c.seed);
    const Input in = prepare_input(MeshFile{holey.positions, holey.faces, {}}, "holes");
    const ReferenceSurface ref(in.reference);
    for (const Index target : {300u, 0u}) {
      SimplifyParams params;
      params.adaptive = true;
      params.target_faces = target;
      params.auto_halt = target == 0;
      Input run = in;
      simplify_input(run, ref, params);
      validate(run.quads);
      EXPECT_EQ(quad_quality(run.quads, &ref).folded_faces, 0u) << "target " << target;
    }
  }
}

TEST(Adaptive, faces_are_smaller_around_a_bump) {
  // A flat square with one narrow bump in its middle: F_S is ~0 on the flat part, so
  // it is coarsened first.
  const TriMesh t =
      height_field(80, 1.0, [](double x, double y) { return 0.15 * std::exp(-(x * x + y * y) / 0.02); });
  QuadMesh q;
  simplify_adaptive(t, q, 400);
  double near = 0, far = 0;
  int n_near = 0, n_far = 0;
  for (Index fc = 0; fc < q.n_faces(); ++fc) {
    const Vec3 c = q.face_centroid(fc);
    const double size = std::sqrt(0.5 * q.face_area_normal(fc).norm());
    const double d = c.head<2>().norm();
    if (d < 0.2) near += size, ++n_near;
    else if (d > 0.6) far += size, ++n_far;
  }
  ASSERT_GT(n_near, 0);
  ASSERT_GT(n_far, 0);
  EXPECT_LT(near / n_near, 0.8 * far / n_far) << "faces on the bump should be smaller";
  // The sized smoothing keeps the quads sound across the size change (with sizes
  // unbounded on the flat part: 71% regular and a smallest edge of 0.001 mu).
  const QuadQuality quality = quad_quality(q);
  EXPECT_GT(quality.regular_percent, 75.0);
  EXPECT_GT(quality.homeometry_min, 0.01);
}

// input_fitmaps() before the ReferenceSurface is built (as the CLI and the filters do, to
// keep the fitmaps' memory and the surface's apart) gives the run simplify_input() makes
// with its own; the fitmaps given are the ones it runs with, and must be of its vertices.
TEST(Adaptive, fitmaps_computed_before_the_reference_surface_give_the_same_run) {
  const TriMesh t =
      height_field(40, 1.0, [](double x, double y) { return 0.15 * std::exp(-(x * x + y * y) / 0.02); });
  const Input in = prepare_input(MeshFile{t.positions, t.faces, {}}, "bump");
  SimplifyParams params;
  params.adaptive = true;
  params.target_faces = 150;
  const Fitmaps fitmaps = input_fitmaps(in, params);
  ASSERT_EQ(fitmaps.s.size(), in.reference.n_vertices());
  ASSERT_EQ(fitmaps.m.size(), in.reference.n_vertices());
  const ReferenceSurface ref(in.reference);
  Input own = in, given = in, flat = in;
  simplify_input(own, ref, params);
  simplify_input(given, ref, params, {}, &fitmaps);
  ASSERT_EQ(own.quads.n_faces(), 150u);
  ASSERT_EQ(given.quads.vertex_capacity(), own.quads.vertex_capacity());
  for (Index v = 0; v < own.quads.vertex_capacity(); ++v) EXPECT_EQ(given.quads.position(v), own.quads.position(v));

  // One S everywhere sizes the quads alike: another run, so the given fitmaps were read.
  Fitmaps even = fitmaps;
  std::fill(even.s.begin(), even.s.end(), fitmaps.s[fitmaps.s.size() / 2]);
  simplify_input(flat, ref, params, {}, &even);
  int moved = 0;
  for (Index v = 0; v < own.quads.vertex_capacity(); ++v)
    moved += own.quads.is_vertex_live(v) != flat.quads.is_vertex_live(v) ||
             (own.quads.is_vertex_live(v) && own.quads.position(v) != flat.quads.position(v));
  EXPECT_GT(moved, 0);

  Fitmaps short_one = fitmaps;
  short_one.m.pop_back();
  Input run = in;
  EXPECT_THROW(simplify_input(run, ref, params, {}, &short_one), std::invalid_argument);
  SimplifyParams uniform;
  uniform.target_faces = 150;
  EXPECT_TRUE(input_fitmaps(in, uniform).s.empty());
  params.tau = 1.5;
  EXPECT_THROW(input_fitmaps(in, params), std::invalid_argument);
}

// A cube of flat sides and sharp edges, as CAD solids are: F_S is near 0 far from the
// edges and large at them, its 20% and 80% quantiles thousands of times apart (2e-4 and
// 1.0 against a median of 0.14 on a remeshed cube of 45,056 triangles). Clamped to
// them alone, the priority coarsened the sides while the edges kept their small quads:
// that cube at 300 quads came out with 1.5 times the uniform RMS distance, 56% regular
// vertices and 4.5 valence refusals per collapse; this one with 1.9 times (15.2e-3
// against 8.1e-3). F_S is clamped to [1/2, 2] of its median too, the sizes' own bound:
// 3.6e-3, 70.5% regular.
TEST(Adaptive, a_cube_comes_out_closer_than_uniform) {
  const TriMesh t = tri_cube(30);
  const ReferenceSurface ref(t);
  const Fitmaps f = compute_fitmaps(t);
  constexpr Index kTarget = 300;
  auto run = [&](bool adaptive) {
    QuadMesh q = tri_to_quad(t);
    SimplifyOptions opt = adaptive ? adaptive_options(f) : SimplifyOptions();
    opt.target_faces = kTarget;
    opt.refuse_folds = adaptive;
    simplify(q, ref, opt);
    validate(q);
    EXPECT_EQ(q.n_faces(), kTarget) << (adaptive ? "adaptive" : "uniform");
    return q;
  };
  const QuadMesh adaptive = run(true), uniform = run(false);
  const double rms_adaptive = surface_distance(adaptive, ref, 100000).rms;
  const double rms_uniform = surface_distance(uniform, ref, 100000).rms;
  EXPECT_LT(rms_adaptive, 0.9 * rms_uniform);
  EXPECT_GT(quad_quality(adaptive).regular_percent, 60.0);
}

TEST(Adaptive, auto_halt_smooths_lightly_until_near_the_predicted_count) {
  // Automatic halting has no target; the count predicted from the fitmaps stands in for
  // it, so the early collapses get one light pass as in runs with a target. A sphere
  // with bumps all over.
  TriMesh t = tri_sphere(60, 90);
  for (Vec3& p : t.positions) p *= 1 + 0.04 * std::sin(12 * p.x()) * std::cos(10 * p.y()) * std::sin(9 * p.z());
  const ReferenceSurface ref(t);
  const Fitmaps f = compute_fitmaps(t);
  auto run = [&](double fine_phase, QuadMesh& q) {
    SimplifyOptions opt = adaptive_options(f);
    opt.fine_phase = fine_phase;
    return simplify_conversion(t, ref, opt, q);
  };
  QuadMesh light, full;
  const SimplifyReport a = run(2.0, light), b = run(0.0, full);
  // The light passes end at 2 x 3 times the prediction: for the last halving to get the
  // full passes it must be above a third of the count reached. Measured: 9.6 predicted,
  // 21 quads halted with the light passes; the smoothing visited a sixth of the vertices.
  for (const SimplifyReport* r : {&a, &b}) {
    EXPECT_GT(3 * r->predicted_faces, double(r->faces));
    EXPECT_LT(r->predicted_faces, 2.0 * double(r->faces));
  }
  EXPECT_LT(a.relaxations, b.relaxations / 3);
}

TEST(Adaptive, the_predicted_halting_count_is_the_runs_and_scales_with_the_m_factor) {
  // predicted_halting_faces() is what a run reports (and what `fitmap --metric auto`
  // takes). Faces reach F_M / m_factor at a key level m_factor times lower, so of sides
  // m_factor times smaller: m_factor^2 times the count.
  TriMesh t = tri_sphere(40, 60);
  for (Vec3& p : t.positions) p *= 1 + 0.04 * std::sin(12 * p.x()) * std::cos(10 * p.y()) * std::sin(9 * p.z());
  const ReferenceSurface ref(t);
  const Fitmaps f = compute_fitmaps(t);
  SimplifyOptions opt = adaptive_options(f);
  const double predicted = predicted_halting_faces(t, opt);
  EXPECT_GT(predicted, 5.0);
  QuadMesh q = tri_to_quad(t);
  EXPECT_EQ(simplify(q, ref, opt).predicted_faces, predicted);
  opt.m_factor = 2;
  EXPECT_NEAR(predicted_halting_faces(t, opt), 4 * predicted, 1e-9 * predicted);
  // simplify() refuses adaptive mode without fitmaps of its reference surface.
  for (const Fitmaps* wrong : {static_cast<const Fitmaps*>(nullptr), &f}) {
    const TriMesh other = tri_sphere(10, 12);
    QuadMesh o = tri_to_quad(other);
    const ReferenceSurface other_ref(other);
    SimplifyOptions bad = adaptive_options(f);
    bad.fitmaps = wrong;  // none, or the sphere's
    EXPECT_THROW(simplify(o, other_ref, bad), std::invalid_argument);
  }
  // Nothing to go by: uniform mode, fitmaps of another mesh.
  SimplifyOptions uniform;
  uniform.fitmaps = &f;
  EXPECT_EQ(predicted_halting_faces(t, uniform), 0.0);
  EXPECT_EQ(predicted_halting_faces(tri_grid(10, 10), opt), 0.0);
  // F_S 0 (exactly planar) on over 80% of the surface: the clamp still bounds it to
  // [1/2, 2] of its median (raised to kLeastS), curved parts included, and the count
  // follows F_M. It made the curved parts' F_S 0 (std::clamp's bounds the wrong way
  // round), and the count 0.
  Fitmaps planar = f;
  for (std::size_t v = 0; v < planar.s.size(); ++v) planar.s[v] = v % 10 < 9 ? 0.f : 1.f;
  opt.fitmaps = &planar;
  EXPECT_GT(predicted_halting_faces(t, opt), 0.0);
}

TEST(Adaptive, keys_take_f_s_over_the_face_so_fine_noise_does_not_scatter_sizes) {
  // A flat square whose F_S is noise at the scale of M0's triangles (0.2 to 1.8, a hash
  // per vertex). Each key averages F_S under the face's centre and corners: one point
  // would give neighbouring faces of the same size keys as scattered as the noise, and
  // the collapses would follow it. Measured, 50 x 50 grid to 300 quads: the face areas'
  // spread (standard deviation over mean) 0.267 and 81.8% regular vertices with the
  // average, 0.362 and 70.8% from the centre alone (other hashes and targets of 150 and
  // 600 quads: 0.27-0.34 against 0.36-0.43).
  TriMesh t = tri_grid(50, 50);
  clean(t);
  const ReferenceSurface ref(t);
  Fitmaps f = compute_fitmaps(t);
  for (Index v = 0; v < t.n_vertices(); ++v) {
    std::uint32_t h = v * 2654435761u;
    h ^= h >> 15;
    h *= 2246822519u;
    h ^= h >> 13;
    f.s[v] = float(0.2 + 1.6 * (h % 1000) / 999.0);
  }
  QuadMesh q = tri_to_quad(t);
  SimplifyOptions opt = adaptive_options(f, 300);
  simplify(q, ref, opt);
  validate(q);
  double sum = 0, sum2 = 0;
  for (Index fc = 0; fc < q.face_capacity(); ++fc) {
    if (!q.is_face_live(fc)) continue;
    const double a = 0.5 * q.face_area_normal(fc).norm();
    sum += a, sum2 += a * a;
  }
  const double n = q.n_faces(), mean = sum / n;
  const double spread = std::sqrt(std::max(0.0, sum2 / n - mean * mean)) / mean;
  EXPECT_LT(spread, 0.31);
  EXPECT_GT(quad_quality(q).regular_percent, 76.0);
}

TEST(Anisotropy, a_plane_keeps_square_quads) {
  TriMesh t = tri_grid(20, 20);
  clean(t);
  const Anisotropy a = compute_anisotropy(t, triangle_adjacency(t), 0.2, 3.0);
  for (Index v = 0; v < t.n_vertices(); ++v)
    for (const Vec3& d : {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)}) ASSERT_NEAR(metric_along(a, v, d), 1.0, 1e-6);
}

TEST(Anisotropy, a_cylinder_stretches_along_its_axis_up_to_the_bound) {
  // Bent across x only: k2 = 0, so the stretch is the bound; the axis (y) is the long side.
  const TriMesh t = height_field(60, 0.4, [](double x, double) { return std::sqrt(1.0 - x * x); });
  const Anisotropy a = compute_anisotropy(t, triangle_adjacency(t), 0.1, 3.0);
  const Index c = centre_vertex(t);
  EXPECT_NEAR(metric_along(a, c, Vec3(0, 1, 0)), 1 / 3.0, 1e-3);
  EXPECT_NEAR(metric_along(a, c, Vec3(1, 0, 0)), 3.0, 1e-2);
  // Areas are kept: the two sides' factors multiply to one.
  const Anisotropy b = compute_anisotropy(t, triangle_adjacency(t), 0.1, 2.0);
  EXPECT_NEAR(metric_along(b, c, Vec3(0, 1, 0)) * metric_along(b, c, Vec3(1, 0, 0)), 1.0, 1e-2);
}

TEST(Anisotropy, a_torus_gets_the_aspect_of_its_curvatures_and_a_sphere_none) {
  // On the torus's outer equator k1 = 1/r around the tube and k2 = 1/(R + r) along it:
  // the stretch is sqrt(k1 / k2) = sqrt((R + r) / r), 2.08 for R = 1, r = 0.3.
  const double R = 1, r = 0.3;
  const TriMesh torus = tri_torus(240, 80, R, r);
  const Anisotropy a = compute_anisotropy(torus, triangle_adjacency(torus), 0.1, 3.0);
  const Index outer = 0;  // (R + r, 0, 0)
  ASSERT_NEAR(torus.positions[outer].x(), R + r, 1e-12);
  const double stretch = std::sqrt((R + r) / r);
  EXPECT_NEAR(metric_along(a, outer, Vec3(0, 0, 1)), stretch, 0.1 * stretch);  // around the tube
  EXPECT_NEAR(metric_along(a, outer, Vec3(0, 1, 0)), 1 / stretch, 0.1 / stretch);  // along it
  const TriMesh sphere = tri_sphere(60, 90);
  const Anisotropy s = compute_anisotropy(sphere, triangle_adjacency(sphere), 0.3, 3.0);
  double most = 1;
  for (Index v = 0; v < sphere.n_vertices(); ++v) {
    const Vec3 p = sphere.positions[v];
    if (std::abs(p.z()) > 0.8) continue;  // the poles' fans
    const Vec3 east = Vec3(-p.y(), p.x(), 0).normalized(), north = p.cross(east).normalized();
    most = std::max({most, metric_along(s, v, east), metric_along(s, v, north)});
  }
  EXPECT_LT(most, 1.1);
}

TEST(Anisotropy, stretch_at_reads_the_aspect_and_the_long_side) {
  // G = s t1 t1^T + t2 t2^T / s + n n^T with s = 2, t1 and t2 at 30 degrees to x and y.
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  const Vec3 t1(c, s, 0), t2(-s, c, 0), n(0, 0, 1);
  const Eigen::Matrix3d G = 2 * t1 * t1.transpose() + t2 * t2.transpose() / 2 + n * n.transpose();
  Anisotropy a;
  a.g = {{float(G(0, 0)), float(G(0, 1)), float(G(0, 2)), float(G(1, 1)), float(G(1, 2)), float(G(2, 2))},
         {1.f, 0.f, 0.f, 1.f, 0.f, 1.f}};
  const Stretch stretched = stretch_at(a, 0), square = stretch_at(a, 1);
  EXPECT_NEAR(stretched.aspect, 2.0, 1e-6);
  EXPECT_NEAR(std::abs(stretched.along.dot(t2)), 1.0, 1e-6);
  EXPECT_EQ(square.aspect, 1.0);
  EXPECT_EQ(square.along, Vec3::Zero());
  EXPECT_EQ(stretch_at(Anisotropy{}, 0).aspect, 1.0);  // no metric: square everywhere
}

TEST(Anisotropy, does_not_depend_on_the_number_of_threads) {
  // Each vertex's ball is its own work, summed in the order of its search.
  const TriMesh t = flat_bumpy_ellipsoid(60, 90);
  Anisotropy one, two;
  tbb::task_arena(1).execute([&] { one = compute_anisotropy(t, triangle_adjacency(t), 0.2, 3.0); });
  tbb::task_arena(2).execute([&] { two = compute_anisotropy(t, triangle_adjacency(t), 0.2, 3.0); });
  EXPECT_EQ(one.g, two.g);
  std::size_t stretched = 0;  // and the bumps do stretch it somewhere
  for (Index v = 0; v < t.n_vertices(); ++v) stretched += one.g[v][0] + one.g[v][3] + one.g[v][5] != 3.f;
  EXPECT_GT(stretched, t.n_vertices() / 2);
}

TEST(Adaptive, quads_grow_long_along_a_torus_and_come_out_closer) {
  // At the same count, quads stretched along the tube (max_aspect 3) against square ones.
  const TriMesh t = tri_torus(240, 80, 1.0, 0.3);
  const ReferenceSurface ref(t);
  const Fitmaps f = compute_fitmaps(t);
  struct Result {
    double along_over_around, rms, regular;
  };
  auto run = [&](double max_aspect) {
    QuadMesh q = tri_to_quad(t);
    SimplifyOptions opt = adaptive_options(f, 300);
    opt.refuse_folds = true;
    opt.max_aspect = max_aspect;
    simplify(q, ref, opt);
    validate(q);
    EXPECT_EQ(q.n_faces(), 300u);
    double along = 0, around = 0;
    for (Index fc = 0; fc < q.face_capacity(); ++fc) {
      if (!q.is_face_live(fc)) continue;
      for (Index k = 0; k < 4; ++k) {
        const Vec3 a = q.position(q.vertex(fc, k)), b = q.position(q.vertex(fc, k + 1));
        const Vec3 m = 0.5 * (a + b), ring = Vec3(-m.y(), m.x(), 0).normalized();
        const double l = (b - a).norm(), c = std::abs((b - a).dot(ring)) / l;
        (c > 0.7 ? along : around) += l;
      }
    }
    return Result{along / around, surface_distance(q, ref, 100000).rms, quad_quality(q).regular_percent};
  };
  const Result square = run(1.0), stretched = run(3.0);
  EXPECT_GT(stretched.along_over_around, 1.3 * square.along_over_around);
  EXPECT_LT(stretched.rms, 0.9 * square.rms);
  EXPECT_GT(stretched.regular, 70.0);
  std::cout << "along/around " << square.along_over_around << " -> " << stretched.along_over_around << ", rms "
            << square.rms << " -> " << stretched.rms << ", regular " << square.regular << " -> " << stretched.regular
            << "\n";
}

TEST(Adaptive, m_fitmap_bounds_stretched_quads_across_and_halting_by_the_papers_radius) {
  // A torus with F_M 3 mu everywhere. Stretched (max_aspect 3), the loop bounds a face's
  // extent across the tube by F_M and lets it reach s times as far along it; square quads
  // keep the paper's radius. Automatic halting measures the paper's radius for both, so
  // the stretched faces, longer for their area, count as blocked sooner.
  TriMesh t = tri_torus(160, 54, 1.0, 0.3);
  clean(t);
  const ReferenceSurface ref(t);
  Fitmaps f = compute_fitmaps(t);
  const double fm = 3 * ref.mean_edge_length();
  std::fill(f.m.begin(), f.m.end(), float(fm));
  struct Extent {
    Index faces, past_fm;
    double radius, across;
  };
  auto run = [&](double max_aspect, double halt_share) {
    QuadMesh q = tri_to_quad(t);
    SimplifyOptions opt = adaptive_options(f);
    opt.max_aspect = max_aspect;
    opt.halt_share = halt_share;
    opt.refuse_folds = true;
    simplify(q, ref, opt);
    validate(q);
    Extent e{0, 0, 0, 0};
    for (Index g = 0; g < q.face_capacity(); ++g) {
      if (!q.is_face_live(g)) continue;
      const auto p = q.positions_of(q.face_vertices(g));
      const Vec3 centre = 0.25 * (p[0] + p[1] + p[2] + p[3]);
      const Vec3 along = Vec3(-centre.y(), centre.x(), 0).normalized();
      double radius = 0;
      for (const Vec3& c : p) {
        const Vec3 d = c - centre;
        radius = std::max(radius, d.norm());
        e.across = std::max(e.across, (d - d.dot(along) * along).norm() / fm);
      }
      ++e.faces;
      e.past_fm += radius > 1.2 * fm;
      e.radius = std::max(e.radius, radius / fm);
    }
    return e;
  };
  // The paper's rule (run until nothing is feasible). Measured: square 840 quads, largest
  // radius 1.02 F_M; stretched 377 quads, 249 of them past 1.2 F_M (largest 2.29 F_M),
  // none wider across the tube than 0.92 F_M.
  const Extent square = run(1.0, 1.0), stretched = run(3.0, 1.0);
  EXPECT_LT(square.radius, 1.2);
  EXPECT_GT(stretched.past_fm, stretched.faces / 3);
  EXPECT_LT(stretched.across, 1.2);
  EXPECT_LT(stretched.faces, square.faces);
  // Halted at the default share. Measured: square 1,154 quads, stretched 2,008; with the
  // halting measure taken along the stretch too, the stretched run went on to 580.
  EXPECT_GT(run(3.0, 0.15).faces, run(1.0, 0.15).faces);
}

TEST(Adaptive, reach_refuses_faces_that_would_leave_the_input) {
  // A sphere with an M-fitmap that refuses nothing: asked for 6 quads, the loop would make
  // a cube, whose faces' centres lie 0.42 r inside the sphere, beyond a reach of 0.045
  // of the diagonal (0.16 r). The reach must hold the run above the target, and the result
  // must be projectable where the cube was not.
  const TriMesh t = tri_sphere(30, 60);
  const ReferenceSurface ref(t);
  Fitmaps f = compute_fitmaps(t);
  std::fill(f.m.begin(), f.m.end(), 1e3f);
  auto run = [&](double reach) {
    QuadMesh q = tri_to_quad(t);
    SimplifyOptions opt = adaptive_options(f, 6);
    opt.reach = reach;
    opt.check_invariants = true;
    const SimplifyReport r = simplify(q, ref, opt);
    const double projectable = surface_distance(q, ref, 100000).projectability;
    std::cout << "reach " << reach << ": " << r.faces << " quads, " << r.refused_reach << " refused, projectable "
              << projectable << "\n";
    return std::make_pair(r, projectable);
  };
  const auto [free_run, free_projectable] = run(0.0);
  EXPECT_EQ(free_run.refused_reach, 0u);
  EXPECT_LE(free_run.faces, 8u);
  EXPECT_LT(free_projectable, 0.9);
  const auto [r, projectable] = run(0.045);
  EXPECT_GT(r.refused_reach, 0u);
  EXPECT_GT(r.faces, 8u);
  EXPECT_GE(projectable, 0.995);
}

TEST(Adaptive, automatic_halting_keeps_the_moai_projectable) {
  // The moai is smooth: its M-fitmap blocks little, and without the reach automatic
  // halting stopped at 63 quads at the paper's bound, parts of which were more than 5% of
  // the diagonal off it (97.3% projectable). With the pipeline's stretched quads the file
  // itself was 98.91% projectable without the reach (66 quads), and is 99.68% since the
  // fitmaps' balls take triangles by their centroids (71 quads; bench/RESULTS.md); the
  // check is shown at the paper's bound (no slack, and square quads, whose bound is the
  // paper's radius in the loop too).
  const std::string path = shared_dataset("moai");
  if (path.empty()) GTEST_SKIP() << "../shared/datasets not found";
  const Input in = load_input(path);
  const ReferenceSurface ref(in.reference);
  const SimplifyParams defaults;
  auto run = [&](double reach, double halt_share, bool at_bound) {
    SimplifyParams params;
    params.adaptive = params.auto_halt = true;
    params.reach = reach;
    params.halt_share = halt_share;
    if (at_bound) params.m_slack = params.max_aspect = 1.0;
    Input out = in;
    const SimplifyReport r = simplify_input(out, ref, params);
    const double projectable = surface_distance(out.quads, ref, 300000).projectability;
    std::cout << "reach " << reach << ", halting share " << halt_share << (at_bound ? ", at the bound" : "") << ": "
              << r.faces << " quads, " << r.beyond_reach_faces.size() << " beyond the reach, projectable "
              << projectable << "\n";
    return std::make_pair(r, projectable);
  };
  const auto [r, projectable] = run(defaults.reach, defaults.halt_share, false);
  EXPECT_GE(projectable, 0.995);
  const auto [at_bound, at_bound_projectable] = run(defaults.reach, defaults.halt_share, true);
  EXPECT_GE(at_bound_projectable, 0.995);
  // The check refuses collapses; the rotations and smoothing after them can still take a
  // face or two out of reach (counted, and said in the log's note).
  EXPECT_LE(at_bound.beyond_reach_faces.size(), 2u);
  // The check is what keeps the run at the bound projectable.
  EXPECT_LT(run(0.0, defaults.halt_share, true).second, 0.99);
  // Run on by the paper's rule, more faces are let through (rotations and smoothing after
  // the collapses are not checked); they are counted, and the log's note says so.
  const SimplifyReport paper = run(defaults.reach, 1.0, false).first;
  ASSERT_GT(paper.beyond_reach_faces.size(), 0u);  // ids.front() below
  EXPECT_GT(paper.beyond_reach_faces.size(), r.beyond_reach_faces.size());
  EXPECT_NE(defects_note(QuadQuality{}, Index(paper.beyond_reach_faces.size())).find(" beyond the reach "),
            std::string::npos);
  // Listed by their ids in the result (the filters select them with the flawed quads), as
  // many as the log's note counts.
  const auto& ids = paper.beyond_reach_faces;
  const std::vector<std::string> notes = result_notes(paper, QuadQuality{}, 0);
  const std::string counted = "quads, " + std::to_string(ids.size()) + " beyond the reach ";
  EXPECT_TRUE(std::any_of(notes.begin(), notes.end(),
                          [&](const std::string& n) { return n.find(counted) != std::string::npos; }))
      << ::testing::PrintToString(notes);
  EXPECT_TRUE(std::is_sorted(ids.begin(), ids.end()) && std::adjacent_find(ids.begin(), ids.end()) == ids.end());
  EXPECT_TRUE(ids.empty() || ids.back() < paper.faces);
  const std::vector<Index> flawed = {ids.front(), paper.faces};  // one shared, one not
  const std::vector<Index> noted = noted_faces(flawed, paper);
  EXPECT_EQ(noted.size(), ids.size() + 1);
  EXPECT_TRUE(std::is_sorted(noted.begin(), noted.end()));
}

TEST(Adaptive, reach_checks_faces_beside_holes_but_not_from_their_border_edges) {
  // A plane with a round hole, no M-fitmap bound: only the reach holds faces back. Faces
  // beside the hole are checked from their centre and inner edges, so they do not grow far
  // across it; their border edges' midpoints hang over the hole wherever the border's
  // chords cut it, and are not checked, or no face there could grow.
  const TriMesh t = tri_grid(60, 60);
  const auto run = [&](double hole, Index target, double reach) {
    MeshFile file{t.positions, {}, {}};
    for (const auto& f : t.faces)
      if (((t.positions[f[0]] + t.positions[f[1]] + t.positions[f[2]]) / 3 - Vec3(0.5, 0.5, 0)).norm() >= hole)
        file.triangles.push_back(f);
    const Input in = prepare_input(file, "hole");
    const ReferenceSurface ref(in.reference);
    Fitmaps f = compute_fitmaps(in.reference);
    std::fill(f.m.begin(), f.m.end(), 1e3f);
    QuadMesh q = in.quads;
    SimplifyOptions opt = adaptive_options(f, target);
    opt.reach = reach;
    simplify(q, ref, opt);
    validate(q);
    return std::pair(q.n_faces(), surface_distance(q, ref, 100000));
  };
  // Skipping the faces beside holes, as the check once did, left the small hole's faces
  // as they are without it: 97.5% projectable, RMS 2.5e-3.
  const auto [n_free, free] = run(0.1, 40, 0.0);
  const auto [n_held, held] = run(0.1, 40, 0.045);
  EXPECT_LE(n_free, 42u);
  EXPECT_LE(n_held, 42u);
  EXPECT_GT(held.projectability, free.projectability + 0.005);
  EXPECT_LT(held.rms, 0.8 * free.rms);
  // Checked from its border edges too, the large hole's run stopped at 76 quads.
  EXPECT_LE(run(0.2, 40, 0.045).first, 42u);
}
