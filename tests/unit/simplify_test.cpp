// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/simplify/simplify.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <numeric>
#include <random>
#include <set>
#include <string_view>
#include <tuple>

#include "fixtures/shapes.h"
#include "quadsimp/convert/tri_to_quad.h"
#include "quadsimp/convert/prepare_input.h"
#include "quadsimp/fitmap/tips.h"
#include "quadsimp/io/load_input.h"
#include "quadsimp/io/mesh_io.h"
#include "quadsimp/mesh/clean.h"
#include "quadsimp/mesh/quad_geometry.h"
#include "quadsimp/metrics/metrics.h"
#include "quadsimp/simplify/pipeline.h"
#include "quadsimp/simplify/surface_fit.h"

using namespace qs;
using namespace qs::fixtures;

namespace {

struct Case {
  TriMesh tri;
  QuadMesh quads;
};

Case prepare(TriMesh t) {
  clean(t);
  QuadMesh q = tri_to_quad(t);
  return {std::move(t), std::move(q)};
}

// A uniform run to `faces` quads, and an adaptive one with automatic halting.
std::array<SimplifyParams, 2> uniform_and_halting(Index faces) {
  SimplifyParams uniform, adaptive;
  uniform.target_faces = faces;
  adaptive.adaptive = adaptive.auto_halt = true;
  return {uniform, adaptive};
}

// The whole job on a file, as the CLI runs it.
Input simplified(const MeshFile& file, const SimplifyParams& params) {
  Input in = prepare_input(file, "mesh");
  const ReferenceSurface ref(in.reference);
  simplify_input(in, ref, params);
  return in;
}

// b is a, quad for quad and vertex for vertex, with every position `scale` times a's.
void expect_scaled_copy(const QuadMesh& a, const QuadMesh& b, double scale) {
  ASSERT_EQ(b.quads(), a.quads());
  for (Index v = 0; v < a.n_vertices(); ++v) ASSERT_EQ(b.position(v), scale * a.position(v)) << v;
}

// t without the faces whose centroid `drop` takes.
template <class Drop>
TriMesh without_faces(TriMesh t, Drop&& drop) {
  std::vector<std::array<Index, 3>> kept;
  for (const auto& f : t.faces)
    if (!drop((t.positions[f[0]] + t.positions[f[1]] + t.positions[f[2]]) / 3)) kept.push_back(f);
  t.faces = std::move(kept);
  return t;
}

// A flat n x n grid whose left and right sides are ragged, like a range scan's outline:
// each row loses 0 to `deepest` cells (drawn) at either end.
TriMesh ragged_grid(int n, unsigned seed, int deepest = 1) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> depth(0, deepest);
  std::vector<int> left(n), right(n);
  for (int j = 0; j < n; ++j) left[j] = depth(rng), right[j] = n - depth(rng);
  return without_faces(tri_grid(n, n), [&](const Vec3& c) {
    const int i = int(c.x() * n), j = int(c.y() * n);
    return i < left[j] || i >= right[j];
  });
}

// The largest distance from a border vertex of q to M0's border.
double border_gap(const QuadMesh& q, const ReferenceSurface& ref) {
  double gap = 0;
  for (Index v = 0; v < q.vertex_capacity(); ++v)
    if (q.is_vertex_live(v) && q.is_border_vertex(v)) gap = std::max(gap, ref.border_distance(q.position(v)));
  return gap;
}

Index count_components(const QuadMesh& m) {
  std::vector<Index> component;
  return connected_components(m, component);
}

// Distance from p to the nearest vertex of m.
double nearest_vertex_distance(const QuadMesh& m, const Vec3& p) {
  double nearest = std::numeric_limits<double>::infinity();
  for (Index v = 0; v < m.n_vertices(); ++v) nearest = std::min(nearest, (m.position(v) - p).norm());
  return nearest;
}

// How many border loops of q do not run once round one border loop of M0, in its
// order. Each border vertex of q is placed at its length along M0's loop (from the
// nearest point of M0's border); the steps from each to the next, taken forwards, add
// up to that loop's length exactly when the order is kept.
Index border_loops_out_of_order(const QuadMesh& q, const ReferenceSurface& ref) {
  const TriMesh& t = ref.mesh();
  const auto adjacency = triangle_adjacency(t);
  std::vector<Index> next(t.positions.size(), kNone);  // along M0's border edges
  for (Index f = 0; f < t.n_faces(); ++f)
    for (int k = 0; k < 3; ++k)
      if (adjacency[f][k] == kNone) next[t.faces[f][k]] = t.faces[f][(k + 1) % 3];
  struct Segment {
    Index loop;
    double start;  // length along the loop at the segment's first end
    Vec3 a, b;
  };
  std::vector<Segment> segments;
  std::vector<double> loop_length;
  std::vector<char> seen(next.size(), 0);
  for (Index v = 0; v < next.size(); ++v) {
    if (next[v] == kNone || seen[v]) continue;
    double length = 0;
    for (Index w = v; !seen[w]; w = next[w]) {
      seen[w] = 1;
      const Vec3 &a = t.positions[w], &b = t.positions[next[w]];
      segments.push_back({Index(loop_length.size()), length, a, b});
      length += (b - a).norm();
    }
    loop_length.push_back(length);
  }
  auto place = [&](const Vec3& p) {  // (loop, length along it) of the nearest border point
    std::pair<Index, double> best{kNone, 0};
    double nearest = std::numeric_limits<double>::infinity();
    for (const Segment& s : segments) {
      const Vec3 ab = s.b - s.a;
      const double u = std::clamp((p - s.a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      const double d = (s.a + u * ab - p).norm();
      if (d < nearest) nearest = d, best = {s.loop, s.start + u * ab.norm()};
    }
    return best;
  };
  Index out_of_order = 0;
  std::vector<char> walked(q.vertex_capacity(), 0);
  for (Index v = 0; v < q.vertex_capacity(); ++v) {
    if (!q.is_vertex_live(v) || !q.is_border_vertex(v) || walked[v]) continue;
    std::vector<std::pair<Index, double>> loop;
    for (Index w = v; !walked[w]; w = q.to(q.out(w))) {
      walked[w] = 1;
      loop.push_back(place(q.position(w)));
    }
    if (segments.empty()) {  // a border where M0 has none
      ++out_of_order;
      continue;
    }
    double turned = 0;
    bool one_loop = true;
    for (size_t i = 0; i < loop.size(); ++i) {
      const auto& [l, at] = loop[i];
      const auto& [l_next, at_next] = loop[(i + 1) % loop.size()];
      one_loop = one_loop && l == l_next;
      turned += std::fmod(at_next - at + loop_length[l], loop_length[l]);
    }
    out_of_order += !one_loop || std::abs(turned - loop_length[loop[0].first]) > 1e-9 * loop_length[loop[0].first];
  }
  return out_of_order;
}

// Simplify to `target` and check what every result must satisfy.
SimplifyReport run_and_check(QuadMesh& quads, Index target, const ReferenceSurface& ref, int passes = 2) {
  SimplifyOptions opt;
  opt.target_faces = target;
  opt.passes = passes;
  const SimplifyReport r = simplify(quads, ref, opt);
  validate(quads);
  EXPECT_TRUE(shared_diagonals(quads).empty());
  EXPECT_LE(quads.n_faces(), target);
  EXPECT_GE(quads.n_faces(), target - target / 50 - 2);  // cleaning may remove a few more
  EXPECT_EQ(r.faces, quads.n_faces());
  const QuadQuality q = quad_quality(quads, &ref);
  EXPECT_EQ(q.flipped_faces, 0u);
  EXPECT_EQ(q.nonconvex_faces, 0u);
  EXPECT_GT(q.regular_percent, 70.0);
  EXPECT_LE(q.max_valence, opt.max_valence);  // neither collapses nor rotations pass the cap
  EXPECT_EQ(border_loops_out_of_order(quads, ref), 0u);
  // Every vertex lies on the reference surface.
  double worst = 0;
  for (Index v = 0; v < quads.n_vertices(); ++v)
    worst = std::max(worst, ref.closest(quads.position(v)).distance);
  EXPECT_LT(worst, 1e-5 * ref.bbox_diagonal());
  return r;
}

// t prepared as the CLI prepares a file and simplified to `target` quads, with the
// border inset off (it moves border vertices inwards on purpose); `gap` is then the
// largest distance from a border vertex of the result to M0's border.
SimplifyReport simplify_open(const TriMesh& t, Index target, bool keep_tips, double& gap) {
  Input in = prepare_input(MeshFile{t.positions, t.faces, {}}, "open");
  const ReferenceSurface ref(in.reference);
  SimplifyOptions opt;
  opt.target_faces = target;
  opt.keep_tips = keep_tips;
  opt.inset_border = false;
  opt.check_invariants = true;
  const SimplifyReport r = simplify(in.quads, ref, opt);
  validate(in.quads);
  gap = border_gap(in.quads, ref) / ref.mean_edge_length();
  return r;
}

}  // namespace

TEST(Simplify, sphere_reaches_target) {
  Case c = prepare(tri_sphere(40, 60));
  const ReferenceSurface ref(c.tri);
  run_and_check(c.quads, 400, ref);
  EXPECT_EQ(count_components(c.quads), 1u);
}

TEST(Simplify, uniform_without_a_target_runs_until_nothing_collapses) {
  // target_faces 0 is "no count limit" in either mode; automatic halting, with its
  // M-fitmap measures, is adaptive only (uniform mode has no fitmaps).
  Case c = prepare(tri_sphere(20, 30));
  const ReferenceSurface ref(c.tri);
  const SimplifyReport r = simplify(c.quads, ref, SimplifyOptions{});
  validate(c.quads);
  EXPECT_GT(r.collapses, 0u);
  EXPECT_LT(c.quads.n_faces(), 20u);
}

TEST(Pipeline, a_target_from_an_edge_length) {
  EXPECT_EQ(faces_for_edge_length(12.0, 0.5), 48u);
  EXPECT_EQ(faces_for_edge_length(1.0, 10.0), 1u);  // at least one quad
  EXPECT_EQ(faces_for_edge_length(1.0, 1e-10), Index(std::numeric_limits<std::int32_t>::max()));
  SimplifyParams p;
  p.target_edge = 0.5;
  EXPECT_EQ(check_params(p), "");
  EXPECT_EQ(target_faces_of(p, 1000, 12.0), 48u);
  p.adaptive = true;
  EXPECT_EQ(check_params(p), "");
  p.auto_halt = true;
  EXPECT_NE(check_params(p).find("automatic halting, not both"), std::string::npos);
  p.auto_halt = false;
  p.target_faces = 100;
  EXPECT_NE(check_params(p).find("a target edge length, not both"), std::string::npos);
  p.target_faces = 0, p.target_share = 0.5;
  EXPECT_NE(check_params(p).find("a target edge length, not both"), std::string::npos);
  p.target_share = 0;
  for (double bad : {-1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    p.target_edge = bad;
    EXPECT_NE(check_params(p), "") << bad;
  }
  p.target_edge = 0, p.target_faces = 7;  // without an edge length the count stands
  EXPECT_EQ(target_faces_of(p, 1000, 12.0), 7u);
}

// simplify_levels(): each level goes on from the quads of the one before, as simplify_input()
// run again on them does, with the fitmaps computed once; a fitted level is a fitted copy,
// the next level going on from the quads on the input; targets must decrease.
TEST(Pipeline, levels_go_on_from_the_one_before) {
  const TriMesh torus = tri_torus(80, 40);
  const auto prepared = [&] { return prepare_input(MeshFile{torus.positions, torus.faces, {}}, "torus"); };
  const auto corners = [](const QuadMesh& m) {
    std::vector<Vec3> out;
    for (Index f = 0; f < m.face_capacity(); ++f)
      if (m.is_face_live(f))
        for (const Vec3& x : m.positions_of(m.face_vertices(f))) out.push_back(x);
    return out;
  };
  const std::vector<Index> targets = {600, 300, 150};
  for (const bool adaptive : {false, true}) {
    SCOPED_TRACE(adaptive ? "adaptive" : "uniform");
    SimplifyParams params;  // no target of its own: the levels give theirs
    params.adaptive = adaptive;
    Input in = prepared();
    const ReferenceSurface ref(in.reference);
    std::vector<std::vector<Vec3>> levels;
    int fitmap_stages = 0;
    simplify_levels(
        in, ref, params, targets,
        [&](std::size_t level, const SimplifyReport& r) {
          EXPECT_EQ(level, levels.size());
          EXPECT_EQ(r.target_faces, targets[level]);
          EXPECT_EQ(in.quads.n_faces(), targets[level]);
          validate(in.quads);
          levels.push_back(corners(in.quads));
        },
        [&](float fraction, std::string_view stage) {
          fitmap_stages += stage == "fitmaps" && fraction == 1.0f;
          return true;
        });
    ASSERT_EQ(levels.size(), targets.size());
    EXPECT_EQ(fitmap_stages, adaptive ? 1 : 0);
    Input again = prepared();
    for (std::size_t i = 0; i < targets.size(); ++i) {
      params.target_faces = targets[i];
      simplify_input(again, ref, params);
      EXPECT_EQ(corners(again.quads), levels[i]) << targets[i];
    }
  }
  SimplifyParams params;
  params.fit_to_input = true;
  Input in = prepared();
  const ReferenceSurface ref(in.reference);
  std::vector<std::vector<Vec3>> fitted;
  simplify_levels(in, ref, params, {600, 300},
                  [&](std::size_t, const SimplifyReport&) { fitted.push_back(corners(in.quads)); });
  params.fit_to_input = false;
  Input on_input = prepared();
  simplify_levels(on_input, ref, params, {600, 300}, [&](std::size_t level, const SimplifyReport&) {
    QuadMesh copy = on_input.quads;
    fit_to_surface(copy, ref);
    EXPECT_NE(corners(copy), corners(on_input.quads));
    EXPECT_EQ(corners(copy), fitted[level]) << level;
  });
  for (const std::vector<Index>& bad : std::vector<std::vector<Index>>{{}, {300, 300}, {300, 600}, {300, 0}, {0}})
    EXPECT_THROW(simplify_levels(in, ref, params, bad, {}), std::invalid_argument) << bad.size();
  params.adaptive = params.auto_halt = true;  // automatic halting is the one level of 0
  EXPECT_THROW(simplify_levels(in, ref, params, {300}, {}), std::invalid_argument);
}

TEST(Simplify, torus_reaches_target) {
  Case c = prepare(tri_torus(80, 40));
  const ReferenceSurface ref(c.tri);
  run_and_check(c.quads, 500, ref);
  // Genus is kept: V - E + F = 0.
  const QuadQuality q = quad_quality(c.quads);
  EXPECT_EQ(long(q.vertices) - 2 * long(q.faces) + long(q.faces), 0);
}

TEST(Simplify, valence_cap_holds_for_collapses_and_rotations) {
  // A tight cap on real meshes, whose conversions leave vertices above it (the
  // pensatore up to 7, the gargoyle 8) for rotations to bring down. Without the
  // rotation check a vertex ends at 6 on both: the energy alone gladly trades a 5 -> 6
  // for two lower deviations elsewhere (also at the pensatore's 1,000 and 8,000, the
  // bunny's and the armadillo's 3,000 and 8,000). The cap only stops collapses and
  // rotations from raising a vertex above it: one the conversion left above it can
  // stay where no rotation of its edges passes the checks (the gargoyle at 8,000 quads
  // keeps a 7, glmark2's bunny at 20,000 too), so the targets here are ones where none does.
  struct Run {
    const char* name;
    Index target;
  };
  int ran = 0;
  for (const Run& run : {Run{"pensatore", 3000}, Run{"gargoyle", 1000}}) {
    const std::string p = shared_dataset(run.name);
    if (p.empty()) continue;
    SCOPED_TRACE(run.name);
    Input in = load_input(p);
    const ReferenceSurface ref(in.reference);
    EXPECT_GT(quad_quality(in.quads).max_valence, 5);
    SimplifyOptions opt;
    opt.target_faces = run.target;
    opt.max_valence = 5;
    simplify(in.quads, ref, opt);
    validate(in.quads);
    EXPECT_LE(quad_quality(in.quads).max_valence, 5);
    ++ran;
  }
  if (ran == 0) GTEST_SKIP() << "../shared/datasets not found";
}

TEST(Simplify, open_grid_keeps_its_border) {
  Case c = prepare(tri_grid(50, 40, 0.3));
  const ReferenceSurface ref(c.tri);
  run_and_check(c.quads, 200, ref);
  // Border vertices stay on the input's border (the unit square's sides).
  for (Index v = 0; v < c.quads.n_vertices(); ++v) {
    if (!c.quads.is_border_vertex(v)) continue;
    const Vec3& p = c.quads.position(v);
    const double side = std::min({std::abs(p.x()), std::abs(p.x() - 1), std::abs(p.y()), std::abs(p.y() - 1)});
    EXPECT_LT(side, 1e-6) << "border vertex " << v << " left the border";
  }
  EXPECT_EQ(count_components(c.quads), 1u);
}

TEST(Simplify, a_small_grid_reaches_a_coarse_target_with_even_quads) {
  // 900 quads to 50: mu, recounted every 256 collapses, lagged so far behind that the
  // border kept most of its edges, the run stopped at 70 quads and some quads spanned the
  // grid (an edge of 9.1 mu).
  Case c = prepare(tri_grid(30, 30, 0.2));
  const ReferenceSurface ref(c.tri);
  SimplifyOptions opt;
  opt.target_faces = 50;
  simplify(c.quads, ref, opt);
  validate(c.quads);
  EXPECT_LE(c.quads.n_faces(), 50u);
  EXPECT_GE(c.quads.n_faces(), 48u);
  const QuadQuality q = quad_quality(c.quads, &ref);
  EXPECT_EQ(q.flipped_faces + q.nonconvex_faces, 0u);
  EXPECT_GT(q.homeometry_min, 0.2);
  EXPECT_LT(q.homeometry_max, 2.5);
}

TEST(Simplify, border_coarsening_keeps_the_valence_cap) {
  // A wavy sheet of cells 50 times longer than wide: border vertices are removed next
  // to the corners, which keep their place and take in each removed vertex's edges.
  // Without the cap on the merged vertex (val(a) + val(c) - 3), a corner ended with
  // valence 11.
  for (double wave : {0.05, 0.1}) {
    SCOPED_TRACE(wave);
    TriMesh t = tri_grid(200, 4);
    for (Vec3& p : t.positions) p.z() = wave * std::sin(6 * p.x()) * std::cos(6 * p.y());
    Case c = prepare(std::move(t));
    const ReferenceSurface ref(c.tri);
    SimplifyOptions opt;
    opt.target_faces = 300;
    const SimplifyReport r = simplify(c.quads, ref, opt);
    validate(c.quads);
    EXPECT_GT(r.border_collapses, 0u);
    EXPECT_LE(quad_quality(c.quads).max_valence, opt.max_valence);
  }
}

TEST(Simplify, flat_square_keeps_its_corners_and_coarsens_its_border) {
  // A straight border: the border ear removal must work where the ear's angle is 180
  // degrees (checking the ear's shape before collapsing it refused every removal here:
  // border edges down to 0.001 mu), and the square's corners, the only sharp turns of
  // the border, stay where they are.
  for (Index target : {300u, 600u}) {
    SCOPED_TRACE(target);
    Case c = prepare(tri_grid(60, 60));
    const ReferenceSurface ref(c.tri);
    EXPECT_EQ(run_and_check(c.quads, target, ref).border_insets, 0u);  // its border edges lie over the input
    EXPECT_GT(quad_quality(c.quads).homeometry_min, 0.3);
    for (const Vec3& corner : {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)}) {
      EXPECT_LT(nearest_vertex_distance(c.quads, corner), 1e-9) << "lost the corner at " << corner.transpose();
    }
  }
}

TEST(Simplify, a_kept_tip_never_pulls_a_border_vertex_off_the_border) {
  // Spikes on a sphere open from its equator down, or on a sphere of 60 spikes open
  // below z = 0.6, asked for a few quads: collapses, or chord collapses, come to join a
  // tip's vertex with a border vertex. Neither may go to the other's place: the tip's
  // would take the border off M0's border.
  double gap;
  for (const double length : {1.0, 2.0}) {
    for (const Index target : {Index(6), Index(10), Index(15), Index(20)}) {
      SCOPED_TRACE(testing::Message() << "length " << length << " target " << target);
      const SimplifyReport r = simplify_open(open_below(spiky_sphere(30, 60, length, 0.25), 0.0), target, true, gap);
      EXPECT_GT(r.tips, 0u);
      EXPECT_LT(gap, 1e-6);
    }
  }
  for (const Index target : {Index(30), Index(80)}) {
    SCOPED_TRACE("60 spikes, target " + std::to_string(target));
    const SimplifyReport r = simplify_open(open_below(bristly_sphere(40, 60, 0.8, 0.1), 0.6), target, true, gap);
    EXPECT_GT(r.chord_collapses, 0u);
    EXPECT_LT(gap, 1e-6);
  }
}

TEST(Simplify, two_kept_tips_never_merge) {
  // Two spikes 0.4 radians apart, their apexes 5% and 12% further apart than the side of
  // the 30 quads asked for: both are tips, and a collapse comes to join their vertices
  // across a quad's diagonal. Neither may go to the other's place: without the refusal,
  // one tip was lost in both runs.
  for (auto [length, half_angle] : {std::pair{0.6, 0.2}, std::pair{0.7, 0.3}}) {
    SCOPED_TRACE(testing::Message() << "length " << length << ", half angle " << half_angle);
    const std::vector<Vec3> axes = {Vec3(std::sin(0.2), 0, std::cos(0.2)), Vec3(-std::sin(0.2), 0, std::cos(0.2))};
    TriMesh t = with_spikes(tri_sphere(40, 80), axes, length, half_angle);
    Input in = prepare_input(MeshFile{t.positions, t.faces, {}}, "two spikes");
    const ReferenceSurface ref(in.reference);
    ASSERT_EQ(find_tips(ref.mesh(), tip_options_for(ref.mesh(), 30)).size(), 2u);
    SimplifyOptions opt;
    opt.target_faces = 30;
    opt.keep_tips = opt.check_invariants = true;
    EXPECT_EQ(simplify(in.quads, ref, opt).tips, 2u);
  }
}

TEST(Simplify, a_chords_open_end_merges_on_the_border) {
  // Spiky spheres open below a latitude, asked for a few quads: chord collapses end on
  // the border, where the two border vertices of the chord's end merge into one. The
  // border bends between them, so M0's point nearest their midpoint lies inside: a vertex
  // left there was off the border for good (here by up to 0.4 input edges).
  struct Run {
    int spikes;
    double length, half_angle, cut;
    Index target;
  };
  for (const Run& run : {Run{60, 0.3, 0.35, 0.2, 8}, Run{60, 0.8, 0.2, 0.2, 15}, Run{12, 0.3, 0.2, 0.6, 8}}) {
    SCOPED_TRACE(std::to_string(run.spikes) + " spikes, target " + std::to_string(run.target));
    double gap;
    const TriMesh t = open_below(bristly_sphere(40, run.spikes, run.length, run.half_angle), run.cut);
    EXPECT_GT(simplify_open(t, run.target, false, gap).chord_collapses, 0u);
    EXPECT_LT(gap, 1e-6);
  }
}

TEST(Simplify, the_inset_comes_after_the_unfolding) {
  // A sphere with small holes, asked for more than its holes let it shrink to: uniform
  // mode unfolds a few quads at the end, and smooths around them. Before the inset came
  // last, that smoothing took border vertices the inset had moved inwards (off M0's
  // border, where they no longer slide along it) further in: 1.75 and 2.4 input edges.
  for (auto [share, seed, target] : {std::tuple{0.005, 2u, Index(100)}, std::tuple{0.02, 1u, Index(300)}}) {
    SCOPED_TRACE(testing::Message() << share << " taken out, seed " << seed << ", target " << target);
    const TriMesh t = with_holes(tri_sphere(40, 80), share, seed);
    Input in = prepare_input(MeshFile{t.positions, t.faces, {}}, "holes");
    const ReferenceSurface ref(in.reference);
    SimplifyParams p;
    p.target_faces = target;
    const SimplifyReport r = simplify_input(in, ref, p);
    EXPECT_GT(r.unfolds, 0u);
    EXPECT_GT(r.border_insets, 0u);
    EXPECT_LT(border_gap(in.quads, ref), 1.05 * ref.mean_edge_length());
  }
}

TEST(Simplify, border_moves_inwards_where_a_ragged_outline_leaves_it_over_nothing) {
  // The border edges of the quads cut across the notches of a ragged outline, and rays
  // cast along the quads' normals there miss the input. Moving the border vertices
  // inwards (by about one input edge at most) must bring most of those points back over it,
  // and leave every interior vertex where it was.
  for (auto [seed, adaptive] : {std::pair{1u, false}, std::pair{2u, false}, std::pair{1u, true}}) {
    SCOPED_TRACE(std::to_string(seed) + (adaptive ? " adaptive" : " uniform"));
    double missed[2];
    QuadMesh result[2];
    for (bool inset : {false, true}) {
      Case c = prepare(ragged_grid(60, seed));
      const ReferenceSurface ref(c.tri);
      SimplifyOptions opt;
      opt.target_faces = 150;
      opt.inset_border = inset;
      opt.check_invariants = true;
      Fitmaps fitmaps;
      if (adaptive) {
        fitmaps = compute_fitmaps(c.tri);
        opt.adaptive = opt.refuse_folds = true;
        opt.fitmaps = &fitmaps;
      }
      const SimplifyReport r = simplify(c.quads, ref, opt);
      EXPECT_EQ(r.border_insets > 0, inset);
      EXPECT_EQ(border_loops_out_of_order(c.quads, ref), 0u);
      const QuadQuality q = quad_quality(c.quads, &ref);
      EXPECT_EQ(q.flipped_faces + q.nonconvex_faces + q.folded_faces, 0u);
      missed[inset] = 1 - surface_distance(c.quads, ref, 200000).projectability;
      if (inset) {
        EXPECT_LE(border_gap(c.quads, ref), ref.mean_edge_length() * (1 + 1e-6));
      }
      result[inset] = std::move(c.quads);
    }
    EXPECT_GT(missed[0], 0.005);  // the outline is ragged enough to matter
    EXPECT_LT(missed[1], 0.3 * missed[0]);
    ASSERT_EQ(result[1].quads(), result[0].quads());
    for (Index v = 0; v < result[0].n_vertices(); ++v) {
      if (!result[0].is_border_vertex(v)) {
        ASSERT_EQ(result[1].position(v), result[0].position(v)) << v;
      }
    }
  }
}

TEST(Simplify, border_inset_folds_no_quad_at_a_scans_holes) {
  // Uniform mode lets smoothing fold quads and unfolds them at the end; the inset comes
  // before that and must not fold one itself, or quads stay folded at small holes.
  const std::string p = shared_dataset("bunny");
  if (p.empty()) GTEST_SKIP() << "../shared/datasets not found";
  TriMesh holed = with_holes(triangles_of(read_mesh(p)), 0.01, 1);
  Index folded[2] = {0, 0};
  for (bool inset : {false, true}) {
    Case c = prepare(holed);
    const ReferenceSurface ref(c.tri);
    SimplifyOptions opt;
    opt.target_faces = 2000;
    opt.inset_border = inset;
    const SimplifyReport r = simplify(c.quads, ref, opt);
    EXPECT_EQ(r.border_insets > 0, inset);
    folded[inset] = quad_quality(c.quads).folded_faces;
  }
  EXPECT_LE(folded[1], folded[0]);
}

// A thin plate: a bumpy sheet and a copy 0.001 above it facing the other way (about 0.05
// of an input edge thick), as two pieces. Each sheet must simplify as it would alone: 200
// quads for the plate come within a quarter of the RMS distance of 100 for one sheet
// (measured 1.09 against 1.32e-3 of the diagonal). The middles of quads this coarse lie
// nearer the other sheet wherever the bump curves them, so a check refusing every quad
// whose middle's closest point of M0 faces away there (tried for pymeshlab's cow.obj,
// whose tail lies along its rear) took this plate to 7.55e-3 (bench/RESULTS.md, "Quads
// over another sheet").
TEST(Simplify, a_thin_plate_simplifies_like_one_of_its_sheets) {
  const TriMesh sheet = tri_grid(60, 60, 0.2);
  TriMesh plate = sheet, upper = sheet;
  for (auto& t : plate.faces) std::swap(t[1], t[2]);  // the lower sheet faces down
  for (Vec3& p : upper.positions) p.z() += 0.001;
  append(plate, upper);
  double rms[2];
  for (int k = 0; k < 2; ++k) {
    const TriMesh& t = k ? plate : sheet;
    SimplifyParams params;
    params.target_faces = k ? 200 : 100;
    const Input in = simplified(MeshFile{t.positions, t.faces, {}}, params);
    const ReferenceSurface ref(in.reference);
    validate(in.quads);
    EXPECT_LE(in.quads.n_faces(), params.target_faces);
    rms[k] = surface_distance(in.quads, ref, 100000).rms / ref.bbox_diagonal();
  }
  EXPECT_LT(rms[1], 1.25 * rms[0]);
}

TEST(Simplify, l_shape_keeps_its_six_corners) {
  // Five convex corners and a concave one. Border ear removals merge three border
  // vertices into one: at the middle one, they cut a corner next to it (by up to a
  // third of mu here).
  for (Index target : {150u, 300u, 600u}) {
    SCOPED_TRACE(target);
    Case c = prepare(without_faces(tri_grid(60, 60), [](const Vec3& c) { return c.x() > 0.5 && c.y() > 0.5; }));
    const ReferenceSurface ref(c.tri);
    run_and_check(c.quads, target, ref);
    for (const Vec3& corner : {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0.5, 0), Vec3(0.5, 0.5, 0), Vec3(0.5, 1, 0),
                               Vec3(0, 1, 0)}) {
      EXPECT_LT(nearest_vertex_distance(c.quads, corner), 1e-9) << "lost the corner at " << corner.transpose();
    }
  }
}

TEST(Simplify, every_change_keeps_the_mesh_valid_and_every_border_vertex_a_candidate) {
  // SimplifyOptions::check_invariants validates after each collapse, ear, chord and the
  // rotations and smoothing after it. Border coarsening visits only the vertices noted
  // as candidates: one an operation brought to the border unnoted would never be
  // coarsened, and no final check would show it. Shapes with borders, holes, a strip
  // (chords), folds (unfolding) and cracks, in both modes.
  TriMesh strip = tri_grid(40, 1);
  for (Vec3& p : strip.positions) p = Vec3(p.x(), p.y() / 40, 0.2 * std::sin(M_PI * p.x()));
  struct Run {
    const char* name;
    TriMesh tri;
    Index target;  // 0: adaptive, automatic halting
  };
  const Run runs[] = {
      {"grid", tri_grid(30, 30, 0.3), 60},
      {"L", without_faces(tri_grid(30, 30), [](const Vec3& c) { return c.x() > 0.5 && c.y() > 0.5; }), 80},
      {"holes", without_faces(tri_sphere(16, 32), [](const Vec3& c) { return std::abs(c.z()) > 0.8 || c.x() > 0.9; }),
       60},
      {"holes, adaptive", without_faces(tri_sphere(16, 32), [](const Vec3& c) { return c.x() > 0.9; }), 0},
      {"torus, adaptive (quads stretched along the tube)", tri_torus(24, 48), 0},
      {"strip", strip, 10},
      {"torus", tri_torus(12, 24), 30},
      {"cylinder of long triangles (folds, unfolding)", cad_cylinder(32, 1, 2.0), 30},
      {"patches meshed apart (cracks zipped)", patches_meshed_apart(3, 0.5), 40},
      {"ragged outline (border inset)", ragged_grid(40, 3), 60},
  };
  Index border_collapses = 0, chord_collapses = 0, unfolds = 0, border_insets = 0;
  for (const Run& run : runs) {
    SCOPED_TRACE(run.name);
    Case c = prepare(run.tri);
    const ReferenceSurface ref(c.tri);
    SimplifyOptions opt;
    opt.check_invariants = true;
    opt.target_faces = run.target;
    Fitmaps fitmaps;
    if (run.target == 0) {
      fitmaps = compute_fitmaps(c.tri);
      opt.adaptive = opt.refuse_folds = true;
      opt.fitmaps = &fitmaps;
      opt.max_aspect = SimplifyParams().max_aspect;
    }
    SimplifyReport r;
    EXPECT_NO_THROW(r = simplify(c.quads, ref, opt));
    EXPECT_LT(r.faces, r.initial_faces * 2 / 3);
    border_collapses += r.border_collapses, chord_collapses += r.chord_collapses, unfolds += r.unfolds;
    border_insets += r.border_insets;
  }
  EXPECT_GT(border_collapses, 20u);  // each kind of change was checked
  EXPECT_GT(border_insets, 0u);
  EXPECT_GT(chord_collapses, 0u);
  EXPECT_GT(unfolds, 0u);
}

TEST(Simplify, table1_rows_meet_the_uniform_targets) {
  // Every row of the paper's Table 1 on the shared models (bench/paper_table1.py): at
  // least 80% regular vertices, valence at most 6 (at most 5 on most rows), homeometry
  // within [0.5, 2], no flipped or non-convex quad, borders in M0's order. Rows an
  // earlier version missed: a face squeezed between neighbours no full smoothing step
  // could move (pensatore 15K), a long interior edge (gargoyle 2K), and bunny.ply's
  // small, jagged holes (border vertices pinned as corners, ears refused on straight
  // borders, concave corners aiming at valence 2, border springs blind to the interior
  // edges).
  struct Model {
    const char* name;
    std::vector<Index> faces;
  };
  const Model models[] = {{"moai", {8200, 3300, 600}},
                          {"pensatore", {15000, 10000, 5000, 2000, 1000}},
                          {"gargoyle", {4000, 2000}},
                          {"bunny", {11000, 5000, 3000}},
                          {"fertility", {22000, 5000, 3300, 2000}}};
  int ran = 0, valence5 = 0;
  for (const Model& model : models) {
    const std::string p = shared_dataset(model.name);
    if (p.empty()) continue;
    const Input in = load_input(p);
    const ReferenceSurface ref(in.reference);
    for (Index target : model.faces) {
      SCOPED_TRACE(std::string(model.name) + " " + std::to_string(target));
      QuadMesh q = in.quads;
      run_and_check(q, target, ref);
      const QuadQuality quality = quad_quality(q, &ref);
      EXPECT_EQ(quality.faces, target);
      EXPECT_GE(quality.regular_percent, 80.0);
      EXPECT_LE(quality.max_valence, 6);
      EXPECT_GE(quality.homeometry_min, 0.5);
      EXPECT_LE(quality.homeometry_max, 2.0);
      EXPECT_EQ(quality.nonconvex_faces + quality.flipped_faces, 0u);
      valence5 += quality.max_valence <= 5;
      ++ran;
    }
  }
  if (ran == 0) GTEST_SKIP() << "../shared/datasets not found";
  EXPECT_GT(2 * valence5, ran) << "max valence 5 on most rows";
}

TEST(Simplify, bunny_border_keeps_its_order_at_a_crack) {
  // One of bunny.ply's holes is thin, and its border comes within 1.0e-3 of itself (the
  // mean edge is 1.5e-3). Border vertices that smoothing slid past a border neighbour,
  // across it, reversed the border's order at every count from 16.5K to 20K quads tried,
  // and the quads between stretched over the hole: at 16.5K one turned non-convex and
  // one folded, at 18K one had homeometry 0.26.
  const std::string p = shared_dataset("bunny");
  if (p.empty()) GTEST_SKIP() << "../shared/datasets not found";
  const Input in = load_input(p);
  const ReferenceSurface ref(in.reference);
  for (Index target : {16500u, 18000u}) {
    SCOPED_TRACE(target);
    QuadMesh q = in.quads;
    run_and_check(q, target, ref);
    const QuadQuality quality = quad_quality(q, &ref);
    EXPECT_EQ(quality.nonconvex_faces + quality.flipped_faces + quality.folded_faces, 0u);
  }
}

TEST(Simplify, two_components_both_survive) {
  Case c = prepare(sphere_beside_sphere(30, 40, 0.7, 3));
  const ReferenceSurface ref(c.tri);
  run_and_check(c.quads, 300, ref);
  EXPECT_EQ(count_components(c.quads), 2u);
}

// Faces of the output whose centroid lies beyond x, or below it.
Index faces_beyond(const QuadMesh& q, double x) {
  Index n = 0;
  for (Index f = 0; f < q.face_capacity(); ++f) n += q.is_face_live(f) && q.face_centroid(f).x() > x;
  return n;
}
Index faces_below(const QuadMesh& q, double x) { return q.n_faces() - faces_beyond(q, x); }

// Scan debris: n flakes (fans of 12 triangles, 0.02 across, a little bumpy) in rows of
// ten from x = x0, beside whatever t holds.
void add_flakes(TriMesh& t, int n, double x0) {
  for (int i = 0; i < n; ++i) {
    TriMesh flake;
    const Vec3 centre(x0 + 0.1 * (i % 10), 0.1 * (i / 10), 0.0);
    flake.positions.push_back(centre);
    for (int k = 0; k < 12; ++k) {
      const double a = 2 * M_PI * k / 12;
      flake.positions.push_back(centre + 0.01 * Vec3(std::cos(a), std::sin(a), 0.001 * (k % 3)));
      flake.faces.push_back({0, Index(1 + k), Index(1 + (k + 1) % 12)});
    }
    append(t, flake);
  }
}

TEST(Simplify, a_small_component_takes_its_fewest_quads_and_the_large_one_its_share) {
  // A sphere a tenth the size of another, beside it: it cannot hold quads of the
  // mesh's mean edge. With one mean edge for both, its springs were longer than itself,
  // its quads crumpled until every collapse there was refused (75 quads left), and the
  // target was met by taking the large sphere down to 8 quads (RMS 57e-3, 38% of the
  // output projectable). Each component's springs now rest at its own mean edge, and
  // the large sphere stops at its share of the target by area (about 49.5 of 50).
  Case c = prepare(sphere_beside_sphere(20, 40, 0.1, 1.5));
  const ReferenceSurface ref(c.tri);
  SimplifyOptions opt;
  opt.target_faces = 50;
  opt.check_invariants = true;  // the pieces' face counts too
  const SimplifyReport r = simplify(c.quads, ref, opt);
  validate(c.quads);
  ASSERT_EQ(count_components(c.quads), 2u);
  const Index small = faces_beyond(c.quads, 1.2);
  EXPECT_LE(small, 10u);  // a cube-like 6 to 8 quads
  EXPECT_GE(c.quads.n_faces() - small, 45u);
  EXPECT_LE(c.quads.n_faces() - small, 50u);
  EXPECT_EQ(r.pieces, 2u);
  EXPECT_EQ(r.pieces_above_share, 1u);
  EXPECT_EQ(r.faces_above_share, small);
  const QuadQuality q = quad_quality(c.quads, &ref);
  EXPECT_EQ(q.folded_faces, 0u);
  const SurfaceDistance d = surface_distance(c.quads, ref, 20000);
  EXPECT_LT(d.rms / ref.bbox_diagonal(), 0.02);  // 50 quads on one sphere: about 0.012
}

TEST(Simplify, pieces_that_cannot_shrink_do_not_take_the_quads_of_the_others) {
  // Scan debris: 100 flakes (fans of 12 triangles, a hundredth of the sphere's radius
  // across) beside a sphere. Each flake holds a quad or more whatever the target; paid
  // for by the sphere, as the count alone asked, a bunny with 300 such flakes asked for
  // 1,000 quads kept 36. The sphere keeps its share by area, and the log says why the
  // run ends above the target.
  TriMesh t = tri_sphere(30, 40);
  add_flakes(t, 100, 3.0);
  Case c = prepare(std::move(t));
  const ReferenceSurface ref(c.tri);
  SimplifyOptions opt;
  opt.target_faces = 300;
  opt.check_invariants = true;
  const SimplifyReport r = simplify(c.quads, ref, opt);
  validate(c.quads);
  const Index flakes = faces_beyond(c.quads, 2.0), sphere = c.quads.n_faces() - flakes;
  EXPECT_GE(sphere, 290u);  // its share: 300 times its part of the area, over 99.9%
  EXPECT_LE(sphere, 300u);
  EXPECT_GE(flakes, 100u);  // a quad at least per flake
  EXPECT_EQ(r.pieces, 101u);
  EXPECT_EQ(r.pieces_above_share, 100u);
  EXPECT_EQ(r.faces_above_share, flakes);
  const std::string why = target_shortfall(r, opt.target_faces);
  EXPECT_NE(why.find("101 pieces"), std::string::npos) << why;
  EXPECT_NE(why.find("Remove Isolated pieces"), std::string::npos) << why;
  const QuadQuality q = quad_quality(c.quads, &ref);
  EXPECT_EQ(q.flipped_faces + q.folded_faces, 0u);
}

TEST(Simplify, an_inputs_own_shared_diagonals_pass_the_invariant_checks) {
  // Quads A and B both have a and b as opposite corners, with no edge a-b; four more
  // quads close the fans around a and b. The pairing of low-poly meshes makes such quads
  // (pyvista's ant has 10 such pairs after cleaning), which the checks refused before
  // the first collapse. They now refuse only new ones, not the input's renamed by merges.
  const MeshFile file = shared_diagonal_quads();
  QuadMesh m = QuadMesh::from_faces(file.positions, file.quads);
  const auto shared = shared_diagonals(m);
  ASSERT_EQ(shared.size(), 3u);  // 0-1, 2-4 and 3-5
  const ReferenceSurface ref(triangles_of(file));
  SimplifyOptions opt;
  opt.target_faces = 4;
  opt.check_invariants = true;
  const SimplifyReport report = simplify(m, ref, opt);
  EXPECT_EQ(report.doublets + report.singlets, 0u);  // the cleaning leaves them
  EXPECT_GT(report.collapses, 0u);
  const auto after = shared_diagonals(m);
  EXPECT_TRUE(std::includes(shared.begin(), shared.end(), after.begin(), after.end()));
}

// The checks themselves: the tests above rely on them to throw. A border is off M0's
// border when the reference surface runs on past it, as it would after a step left a
// border vertex inside.
TEST(Simplify, the_invariant_checks_catch_a_border_off_the_inputs_border) {
  QuadMesh m = quad_grid(8, 8);
  for (Index v = 0; v < m.vertex_capacity(); ++v) m.position(v) = m.position(v) / 16 + Vec3(0.25, 0.25, 0);
  const ReferenceSurface ref(tri_grid(8, 8));  // the unit square; the quads cover its middle
  SimplifyOptions opt;
  opt.target_faces = 20;
  QuadMesh unchecked = m;
  EXPECT_NO_THROW(simplify(unchecked, ref, opt));
  opt.check_invariants = true;
  try {
    simplify(m, ref, opt);
    FAIL() << "a border inside the input passed the checks";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("is off M0's border by "), std::string::npos) << e.what();
  }
}

TEST(Simplify, a_coarse_piece_leaves_the_share_it_cannot_use_to_the_others) {
  // Two spheres of one size, one meshed coarsely (176 quads) and one finely, and debris
  // that holds the run above the target. By area the spheres' shares of 600 are about 300
  // each; the coarse one keeps its 176, and the fine one gets what is left, about 424.
  TriMesh t = tri_sphere(12, 16);
  TriMesh fine = tri_sphere(40, 60);
  for (auto& p : fine.positions) p.x() += 3;
  append(t, fine);
  add_flakes(t, 50, 6.0);
  Case c = prepare(std::move(t));
  const ReferenceSurface ref(c.tri);
  const Index coarse_faces = faces_below(c.quads, 1.5);
  SimplifyOptions opt;
  opt.target_faces = 600;
  opt.check_invariants = true;
  const SimplifyReport r = simplify(c.quads, ref, opt);
  EXPECT_EQ(faces_below(c.quads, 1.5), coarse_faces);
  const Index fine_faces = c.quads.n_faces() - faces_below(c.quads, 1.5) - faces_beyond(c.quads, 5.0);
  EXPECT_GE(fine_faces, 600 - coarse_faces - 10);
  EXPECT_LE(fine_faces, 600 - coarse_faces);
  EXPECT_EQ(r.pieces_above_share, 50u);  // the flakes
}

TEST(Simplify, deterministic) {
  Case a = prepare(tri_sphere(30, 40)), b = prepare(tri_sphere(30, 40));
  const ReferenceSurface ref(a.tri);
  SimplifyOptions opt;
  opt.target_faces = 300;
  simplify(a.quads, ref, opt);
  simplify(b.quads, ref, opt);
  EXPECT_EQ(a.quads.quads(), b.quads.quads());
  EXPECT_EQ(a.quads.positions(), b.quads.positions());
}

TEST(Simplify, fine_phase_smooths_less_for_the_same_quality) {
  // While the mesh is far finer than the target each collapse gets one short pass. A
  // single run's share of regular vertices moves by +-4 points with any change to the
  // loop, so the comparison is over several targets.
  const Case input = prepare(tri_sphere(60, 80));
  const ReferenceSurface ref(input.tri);
  auto run = [&](double fine_phase, double& regular, Index& relaxations) {
    regular = 0;
    relaxations = 0;
    const Index targets[] = {300, 400, 500, 600, 700, 800, 1000};
    for (Index target : targets) {
      QuadMesh q = input.quads;
      SimplifyOptions opt;
      opt.target_faces = target;
      opt.fine_phase = fine_phase;
      relaxations += simplify(q, ref, opt).relaxations;
      validate(q);
      const QuadQuality quality = quad_quality(q, &ref);
      EXPECT_EQ(quality.flipped_faces + quality.nonconvex_faces, 0u);
      regular += quality.regular_percent / std::size(targets);
    }
  };
  double full = 0, phased = 0;
  Index relax_full = 0, relax_phased = 0;
  run(0.0, full, relax_full);
  run(2.0, phased, relax_phased);
  EXPECT_LT(relax_phased, 0.75 * relax_full);
  EXPECT_GT(phased, full - 3);  // measured: 84.9% and 83.7%
}

TEST(Simplify, initial_sweeps_even_out_parts_no_collapse_reaches) {
  // A grid with jittered vertices, simplified by a handful of collapses: most of it is
  // never touched by one, and keeps the converter's uneven quads without the sweeps.
  auto run = [](int sweeps) {
    TriMesh t = tri_grid(30, 30);
    for (Index v = 0; v < t.n_vertices(); ++v) {
      Vec3& p = t.positions[v];
      if (p.x() > 0 && p.x() < 1 && p.y() > 0 && p.y() < 1)
        p += 0.3 / 30 * Vec3(std::sin(12.9898 * v), std::cos(78.233 * v), 0);
    }
    Case c = prepare(std::move(t));
    const ReferenceSurface ref(c.tri);
    SimplifyOptions opt;
    opt.target_faces = c.quads.n_faces() - 10;
    opt.initial_sweeps = sweeps;
    simplify(c.quads, ref, opt);
    validate(c.quads);
    return quad_quality(c.quads, &ref);
  };
  const QuadQuality none = run(0), swept = run(3);
  EXPECT_GT(swept.homeometry_min, none.homeometry_min + 0.1);
  EXPECT_LT(swept.homeometry_max, none.homeometry_max - 0.1);
  EXPECT_EQ(swept.flipped_faces + swept.nonconvex_faces, 0u);
}

TEST(Simplify, progress_and_cancel) {
  Case c = prepare(tri_sphere(40, 60));
  const ReferenceSurface ref(c.tri);
  SimplifyOptions opt;
  opt.target_faces = 100;
  int calls = 0;
  opt.progress = [&](float f, std::string_view) {
    EXPECT_GE(f, 0.f);
    EXPECT_LE(f, 1.f);
    return ++calls < 3;
  };
  const SimplifyReport r = simplify(c.quads, ref, opt);
  EXPECT_TRUE(r.cancelled);
  EXPECT_EQ(calls, 3);
  EXPECT_GT(c.quads.n_faces(), 100u);
  validate(c.quads);
}

TEST(Simplify, bunny_from_glmark2) {
  const std::string p = "/usr/share/glmark2/models/bunny.obj";
  if (!std::ifstream(p)) GTEST_SKIP() << p << " not installed (glmark2-data)";
  Input in = load_input(p);
  Case c{in.reference, std::move(in.quads)};
  const ReferenceSurface ref(c.tri);
  run_and_check(c.quads, 3000, ref);
}

TEST(ReferenceSurface, results_do_not_depend_on_the_cpus_vector_instructions) {
  // Embree's widest kernels (AVX2, AVX-512) hit in other last bits than its SSE2 ones,
  // and those bits decide between near-equal moves: on a CPU with them the bunny comes
  // out otherwise. By default every query runs on the SSE2 kernels, which every x86-64
  // CPU has, so a result is the same whichever CPU runs it.
  const std::string p = "/usr/share/glmark2/models/bunny.obj";
  if (!std::ifstream(p)) GTEST_SKIP() << p << " not installed (glmark2-data)";
  const Input in = load_input(p);
  const auto run = [&](const ReferenceSurface& ref) {
    QuadMesh q = in.quads;
    SimplifyOptions opt;
    opt.target_faces = 5000;
    simplify(q, ref, opt);
    return q;
  };
  const QuadMesh by_default = run(ReferenceSurface(in.reference));
  const QuadMesh sse2 = run(ReferenceSurface(in.reference, EmbreeKernels::Sse2));
  EXPECT_EQ(by_default.quads(), sse2.quads());
  EXPECT_EQ(by_default.positions(), sse2.positions());
  const QuadMesh native = run(ReferenceSurface(in.reference, EmbreeKernels::Native));
  if (native.positions() == sse2.positions())
    GTEST_SKIP() << "this CPU's own kernels give the SSE2 kernels' result here: nothing told apart";
  EXPECT_EQ(native.n_faces(), sse2.n_faces());  // another result, as sound
}

namespace {
// `bunny` split in four twice (1.1M triangles), cleaned, and simplified to 20,000 quads:
// sound quads whose every element is within [0.5, 2] mu.
void expect_sound_when_split(const TriMesh& bunny) {
  Case c = prepare(split_in_four(split_in_four(bunny)));
  const ReferenceSurface ref(c.tri);
  run_and_check(c.quads, 20000, ref);
  const QuadQuality q = quad_quality(c.quads, &ref);
  EXPECT_EQ(q.folded_faces, 0u);
  EXPECT_GE(q.homeometry_min, 0.5);
  EXPECT_LE(q.homeometry_max, 2.0);
}
}  // namespace

TEST(Simplify, a_scan_folded_over_onto_itself_gives_sound_quads) {
  // glmark2's bunny closes a hole with a fan one of whose triangles turns over: a Z-fold,
  // three layers of surface, the middle one facing the other way; it closes another
  // along its base with caps (triangles 1e-4 as high as long). Split in four twice
  // (1.1M triangles, as the fitmap benchmark does) each is 16 triangles wide and the
  // working mesh follows them. clean() now mends both on loading, before the split.
  // Before that, to 20,000 quads: without over_flap(), 2 flipped quads, a non-convex
  // one, a folded one and a diagonal of 0.04 mu at the fold; with it, sound quads on
  // one machine, but on another (AVX2 Embree, not AVX-512) a quad left flipped at the
  // fold and an edge of 0.03 mu at the caps (0.2 mu with the caps mended alone).
  const std::string p = "/usr/share/glmark2/models/bunny.obj";
  if (!std::ifstream(p)) GTEST_SKIP() << p << " not installed (glmark2-data)";
  expect_sound_when_split(load_input(p).reference);
}

TEST(Simplify, a_scan_folded_over_by_several_triangles_gives_sound_quads) {
  // The same bunny split in four twice *before* cleaning: its fold is a patch of 16
  // triangles, which no edge flip mends, and clean() lays it flat. Without that, the
  // simplifier's care over folds (over_flap()) left a flipped quad and homeometry down to
  // 0.18 at 20,000 quads on one machine; with it, it ends as the run above does.
  const std::string p = "/usr/share/glmark2/models/bunny.obj";
  if (!std::ifstream(p)) GTEST_SKIP() << p << " not installed (glmark2-data)";
  expect_sound_when_split(triangles_of(read_mesh(p)));
}

TEST(Simplify, a_patch_folded_back_gives_sound_quads) {
  // Strips of triangles folded back onto a grid (folded_grid()). When only patches
  // under 1e-4 counted as folded (none laid flat, none marked), the first ended with
  // flipped quads over the strip (4 at 1,000, with 2 non-convex and 2 folded); when
  // 1e-3 did, the second, which covers over 5e-3 of its grid (12 flipped at 1,000).
  // Now clean() lays them flat; marking them for over_flap() alone would also pass the
  // first.
  for (const TriMesh& t : {folded_grid(128), folded_grid(64, nullptr, 12, 3.5)}) {
    for (Index target : {1000u, 3000u}) {
      SCOPED_TRACE(std::to_string(t.n_faces()) + " triangles, " + std::to_string(target));
      Case c = prepare(t);
      const ReferenceSurface ref(c.tri);
      run_and_check(c.quads, target, ref);
      EXPECT_EQ(quad_quality(c.quads, &ref).folded_faces, 0u);
    }
  }
}

TEST(Simplify, no_quad_spans_a_fold_facing_away) {
  // Thin, sharply folded parts (the gargoyle's wings, the armadillo's fingers and ears):
  // without the fold check in follows_reference() these runs end with 2 and 3 quads
  // whose middle faces against the surface under it (run_and_check counts them). The
  // single-pass run (--fast) ended with one when the check waited for a corner at 60
  // degrees: that quad stood at 46-54 degrees on every corner.
  struct Run {
    const char* name;
    Index target;
    int passes;
  };
  int ran = 0;
  for (const Run& r : {Run{"gargoyle", 1000, 2}, Run{"armadillo", 3000, 2}, Run{"gargoyle", 2000, 1}}) {
    const std::string p = shared_dataset(r.name);
    if (p.empty()) continue;
    SCOPED_TRACE(std::string(r.name) + " " + std::to_string(r.target));
    Input in = load_input(p);
    Case c{in.reference, std::move(in.quads)};
    const ReferenceSurface ref(c.tri);
    run_and_check(c.quads, r.target, ref, r.passes);
    ++ran;
  }
  if (ran == 0) GTEST_SKIP() << "../shared/datasets not found";
}

TEST(Simplify, uniform_runs_unfold_the_quads_left_bent_over_thin_parts) {
  // The gargoyle's wings and claws: without unfolding these runs end with quads bent past
  // 90 degrees (quad_folds()); with it, none, and the smoothing around the rotations and
  // moves leaves the edge lengths as even as they were (mu moves a little). At 600 quads
  // rotations alone left 2: their corners of valence 3 need the corner moves.
  const std::string p = shared_dataset("gargoyle");
  if (p.empty()) GTEST_SKIP() << "../shared/datasets not found";
  const Input in = load_input(p);
  const ReferenceSurface ref(in.reference);
  for (Index target : {600u, 4000u, 6000u}) {
    SCOPED_TRACE(target);
    QuadMesh kept = in.quads;
    SimplifyOptions off;
    off.target_faces = target;
    off.unfold = false;
    simplify(kept, ref, off);
    const QuadQuality before = quad_quality(kept, &ref);
    EXPECT_GT(before.folded_faces, 0u) << "the case no longer needs unfolding";

    Case c{in.reference, in.quads};
    const SimplifyReport r = run_and_check(c.quads, target, ref);
    const QuadQuality q = quad_quality(c.quads, &ref);
    EXPECT_EQ(q.folded_faces, 0u);
    EXPECT_GT(r.unfolds, 0u);
    EXPECT_GE(q.homeometry_min, before.homeometry_min - 0.02);
    EXPECT_LE(q.homeometry_max, std::max(2.0, before.homeometry_max + 0.02));
  }
}

TEST(ReferenceSurface, projection_lands_on_the_surface) {
  TriMesh s = tri_sphere(30, 40);
  clean(s);
  const ReferenceSurface ref(s);
  for (int i = 0; i < 50; ++i) {
    const Vec3 dir = Vec3(std::cos(i * 0.7) * std::sin(i * 0.3 + 0.2), std::sin(i * 0.7) * std::sin(i * 0.3 + 0.2),
                          std::cos(i * 0.3 + 0.2)).normalized();
    for (double r : {0.8, 1.0, 1.3}) {
      const SurfacePoint hit = ref.project(r * dir, dir, 1.0);
      ASSERT_TRUE(hit.found());
      EXPECT_LT(ref.closest(hit.point).distance, 1e-5 * ref.bbox_diagonal());
      EXPECT_NEAR(hit.point.norm(), 1.0, 0.01);  // on the (faceted) unit sphere
      EXPECT_GT(ref.face_normal(hit.face).dot(dir), 0);
    }
  }
  // Nothing along the line within reach: the closest point is the fallback.
  const SurfacePoint far = ref.project(Vec3(5, 0, 0), Vec3(0, 0, 1), 0.1);
  ASSERT_TRUE(far.found());
  EXPECT_NEAR(far.point.norm(), 1.0, 0.01);
  // Barycentric lookup reproduces a linear field exactly.
  std::vector<float> x(s.n_vertices());
  for (Index v = 0; v < s.n_vertices(); ++v) x[v] = float(s.positions[v].x());
  const SurfacePoint hit = ref.project(Vec3(0.3, 0.2, 2), Vec3(0, 0, 1), 3);
  EXPECT_NEAR(ref.interpolate(x, hit), hit.point.x(), 1e-5);
}

TEST(ReferenceSurface, a_mesh_far_from_the_origin_is_queried_as_precisely) {
  // Embree works in float, which rounds 3e6 to a quarter unit: without the shift to
  // working_origin() these points were off the unit sphere by as much.
  TriMesh s = tri_sphere(30, 40);
  const Vec3 shift(1e6, -2e6, 3e6);
  for (Vec3& p : s.positions) p += shift;
  clean(s);
  const ReferenceSurface ref(s);
  for (int i = 0; i < 20; ++i) {
    const Vec3 dir = Vec3(std::cos(i * 0.7), std::sin(i * 0.7), std::cos(i * 0.3)).normalized();
    const SurfacePoint hit = ref.ray_project(shift + 1.3 * dir, dir, 1.0);
    ASSERT_TRUE(hit.found());
    EXPECT_NEAR((hit.point - shift).norm(), 1.0, 0.01);  // on the (faceted) unit sphere
    EXPECT_NEAR(hit.distance, 0.3, 0.01);
    EXPECT_LT(ref.closest(hit.point).distance, 1e-6);
    EXPECT_NEAR(ref.closest(shift + 1.3 * dir).distance, 0.3, 0.01);
  }
}

TEST(Simplify, a_mesh_far_from_the_origin_simplifies_as_at_it) {
  Case here = prepare(tri_sphere(40, 60));
  TriMesh t = tri_sphere(40, 60);
  for (Vec3& p : t.positions) p += Vec3(1e6, -2e6, 3e6);
  Case far = prepare(t);
  const ReferenceSurface ref_here(here.tri), ref_far(far.tri);
  run_and_check(here.quads, 400, ref_here);
  run_and_check(far.quads, 400, ref_far);  // every vertex on the sphere, none flipped
  EXPECT_NEAR(mean_edge_length(far.quads), mean_edge_length(here.quads), 0.01 * mean_edge_length(here.quads));
}

TEST(ReferenceSurface, project_near_walks_to_the_same_hit) {
  TriMesh s = tri_sphere(30, 40);
  clean(s);
  const ReferenceSurface ref(s);
  // Coordinate fields: barycentric lookup at a hit must give back the hit point.
  std::vector<float> coord[3];
  for (int c = 0; c < 3; ++c)
    for (Index v = 0; v < s.n_vertices(); ++v) coord[c].push_back(float(s.positions[v][c]));
  int same_face = 0;
  for (int i = 0; i < 50; ++i) {
    const Vec3 dir = Vec3(std::cos(i * 0.7) * std::sin(i * 0.3 + 0.2), std::sin(i * 0.7) * std::sin(i * 0.3 + 0.2),
                          std::cos(i * 0.3 + 0.2)).normalized();
    const SurfacePoint expect = ref.project(1.1 * dir, dir, 1.0);
    // Start a few triangles away (the foot of a nearby point), on the far side of the
    // sphere (the walk must give up and the BVH answers), and from no triangle at all.
    const Vec3 side = dir.cross(Vec3(0.3, 0.5, 0.8)).normalized();
    const Index near_start = ref.closest((dir + 0.15 * side).normalized()).face;
    const Index far_start = ref.closest(-dir).face;
    for (Index start : {near_start, far_start, kNone}) {
      const SurfacePoint hit = ref.project_near(start, 1.1 * dir, dir, 1.0);
      ASSERT_TRUE(hit.found());
      EXPECT_LT((hit.point - expect.point).norm(), 1e-6);  // Embree intersects in single precision
      EXPECT_NEAR(hit.distance, expect.distance, 1e-6);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(ref.interpolate(coord[c], hit), hit.point[c], 1e-6);
      same_face += start == near_start && hit.face == expect.face;
    }
  }
  EXPECT_EQ(same_face, 50);
  // Off the border of an open grid the walk stops and the closest-point fallback answers.
  const TriMesh grid = tri_grid(4, 4);
  const ReferenceSurface flat(grid);
  const SurfacePoint out = flat.project_near(0, Vec3(9, 9, 1), Vec3(0, 0, 1), 0.5);
  ASSERT_TRUE(out.found());
  EXPECT_LT((out.point - flat.closest(Vec3(9, 9, 1)).point).norm(), 1e-12);
}

// The bounded search must find exactly what the unbounded one does: the centres of
// chords between two vertices (a quad's corners), the vertices themselves (hint 0), and
// with a hint too small to reach M0 (it widens).
TEST(ReferenceSurface, closest_within_finds_the_closest_point) {
  TriMesh s = tri_sphere(30, 40);
  clean(s);
  const ReferenceSurface ref(s);
  for (Index v = 0; v + 37 < s.n_vertices(); v += 7) {
    const Vec3 &a = s.positions[v], &b = s.positions[v + 37];
    const Vec3 mid = 0.5 * (a + b);
    const SurfacePoint expect = ref.closest(mid), got = ref.closest_within(mid, (a - mid).norm());
    ASSERT_TRUE(got.found());
    EXPECT_EQ(got.face, expect.face);
    EXPECT_EQ(got.point, expect.point);
    const SurfacePoint at = ref.closest_within(a, 0.0), at_expect = ref.closest(a);
    EXPECT_EQ(at.face, at_expect.face);
    EXPECT_LT(at.distance, 1e-6);
    // A quad of four surface points: its centre's closest point, with the nearest corner as hint.
    const Vec3 q[4] = {a, s.positions[v + 1], b, s.positions[v + 38]};
    const Vec3 centre = 0.25 * (q[0] + q[1] + q[2] + q[3]);
    const SurfacePoint quad = ref.closest_to_quad_centre(q), quad_expect = ref.closest(centre);
    EXPECT_EQ(quad.face, quad_expect.face);
    EXPECT_EQ(quad.point, quad_expect.point);
  }
  const SurfacePoint far = ref.closest_within(Vec3(3, 0, 0), 0.1);
  ASSERT_TRUE(far.found()) << "a hint that reaches nothing falls back to the unbounded search";
  EXPECT_NEAR(far.distance, ref.closest(Vec3(3, 0, 0)).distance, 1e-12);
}

// A closed, flattened box: its top faces up and its bottom down, 1/8 of its width
// apart. Asked for the closest point facing up, from just under the bottom, the answer is
// on the top at any size; the orientation passed is a quad's area normal, which on the
// box written 2^20 times smaller is 1e-13 long (Eigen's fuzzy isZero() took it for "any
// orientation", and the bottom was found).
TEST(ReferenceSurface, closest_facing_a_way_does_not_depend_on_the_unit_of_length) {
  for (const double scale : {1.0, std::ldexp(1.0, -20)}) {
    SCOPED_TRACE(scale);
    TriMesh box = tri_cube(4);
    for (Vec3& p : box.positions) p = scale * Vec3(p.x(), p.y(), p.z() / 8);
    clean(box);
    const ReferenceSurface ref(box);
    const Vec3 below = scale * Vec3(0.3, 0.4, -0.01), up = scale * scale * Vec3(0, 0, 0.25);
    const SurfacePoint any = ref.closest(below);
    const SurfacePoint facing_up = ref.closest(below, std::numeric_limits<double>::infinity(), up);
    ASSERT_TRUE(any.found() && facing_up.found());
    EXPECT_LT(ref.face_normal(any.face).z(), -0.99);
    EXPECT_GT(ref.face_normal(facing_up.face).z(), 0.99);
  }
}

// A vertex pushed past its neighbour turns two triangles over onto the grid: a flap,
// with the triangles around its corners. A flattened sphere (two sides alike, meeting
// at a sharp rim) has no flap, nor has the grid before the push.
TEST(ReferenceSurface, is_flap_marks_a_patch_folded_over_and_its_ring) {
  const int n = 128;  // the flap must be under 1e-3 of the area
  TriMesh grid = tri_grid(n, n);
  const ReferenceSurface plain(grid);
  const Index v = Index(40 * (n + 1) + 40);
  grid.positions[v].x() += 1.5 / n;
  const ReferenceSurface pushed(grid);
  std::set<Index> flipped, ring;
  for (Index f = 0; f < grid.n_faces(); ++f) {
    EXPECT_FALSE(plain.is_flap(f));
    if (pushed.face_normal(f).z() < 0) flipped.insert(f);
  }
  ASSERT_EQ(flipped.size(), 2u);
  for (Index f = 0; f < grid.n_faces(); ++f)
    for (Index g : flipped)
      for (Index a : grid.faces[f])
        for (Index b : grid.faces[g])
          if (a == b) ring.insert(f);
  for (Index f = 0; f < grid.n_faces(); ++f) EXPECT_EQ(pushed.is_flap(f), ring.count(f) == 1) << "triangle " << f;

  TriMesh sheet = tri_sphere(30, 40);  // flattened: its halves meet at the rim at ~180 degrees
  for (Vec3& x : sheet.positions) x.z() *= 1e-3;
  const ReferenceSurface folded(sheet);
  int turned = 0;
  for (Index f = 0; f < sheet.n_faces(); ++f) turned += folded.face_normal(f).z() < 0;
  EXPECT_GT(turned, int(sheet.n_faces()) / 3);
  int rim = 0;  // edges turning back by over 120 degrees: the two sides are apart
  const auto adjacency = triangle_adjacency(sheet);
  for (Index f = 0; f < sheet.n_faces(); ++f)
    for (Index g : adjacency[f]) rim += g != kNone && folded.face_normal(f).dot(folded.face_normal(g)) < -0.5;
  EXPECT_GT(rim, 0);
  for (Index f = 0; f < sheet.n_faces(); ++f) ASSERT_FALSE(folded.is_flap(f)) << "triangle " << f;

  // A leaf's top (1e-2 of its surface, which clean() tries and puts back) is not marked:
  // marked, 12 of 2,000 quads ended turned over it.
  const TriMesh leaf = leaf_on_stalk(0.5);
  const ReferenceSurface on_stalk(leaf);
  for (Index f = 0; f < leaf.n_faces(); ++f) ASSERT_FALSE(on_stalk.is_flap(f)) << "triangle " << f;
}

TEST(ReferenceSurface, closest_on_border_stays_on_the_border) {
  // The grid's border bends in z with the bump; the closest point of the whole surface
  // to a point just inside lands off the border, the border search must not.
  TriMesh t = tri_grid(40, 40, 0.3);
  clean(t);
  const ReferenceSurface ref(t);
  const auto& P = ref.mesh().positions;
  Index start = kNone, inner = kNone;  // a triangle on the side y = 0 near x = 0.5, and one far inside
  for (Index f = 0; f < ref.mesh().n_faces(); ++f) {
    Vec3 c = Vec3::Zero();
    for (Index v : ref.mesh().faces[f]) c += P[v] / 3;
    if (c.y() < 0.02 && std::abs(c.x() - 0.5) < 0.02) start = f;
    if ((c.head<2>() - Vec3(0.5, 0.5, 0).head<2>()).norm() < 0.02) inner = f;
  }
  ASSERT_NE(start, kNone);
  ASSERT_NE(inner, kNone);
  std::vector<float> x(P.size()), y(P.size());
  for (Index v = 0; v < P.size(); ++v) x[v] = float(P[v].x()), y[v] = float(P[v].y());
  // From a corner of `start` on the side, with the arc's ends off the border: unbounded.
  Vec3 from = Vec3::Zero();
  for (Index v : ref.mesh().faces[start])
    if (P[v].y() == 0) from = P[v];
  const ReferenceSurface::BorderArc open{from, Vec3(0.5, 0.5, 1), Vec3(0.5, 0.5, 1)};
  for (double dx : {-0.08, -0.01, 0.0, 0.03, 0.09}) {
    const Vec3 p(0.5 + dx, 0.01, 0.01);
    const SurfacePoint s = ref.closest_on_border(start, p, 0.2, open);
    ASSERT_TRUE(s.found());
    EXPECT_NEAR(s.point.y(), 0.0, 1e-12);            // on the side
    EXPECT_NEAR(s.point.x(), 0.5 + dx, 0.03);        // near p along it
    EXPECT_NEAR(ref.interpolate(x, s), s.point.x(), 1e-6);  // barycentrics match the point
    EXPECT_NEAR(ref.interpolate(y, s), 0.0, 1e-6);
    // The nearest of all border edges within reach.
    double best = std::numeric_limits<double>::infinity();
    for (Index v = 0; v < P.size(); ++v)
      if (P[v].y() == 0 && std::abs(P[v].x() - 0.5) < 0.15)
        for (Index w = 0; w < P.size(); ++w)
          if (P[w].y() == 0 && std::abs(P[w].x() - P[v].x() - 1.0 / 40) < 1e-9) {
            const Vec3 e = P[w] - P[v];
            const double u = std::clamp((p - P[v]).dot(e) / e.squaredNorm(), 0.0, 1.0);
            best = std::min(best, (P[v] + u * e - p).norm());
          }
    EXPECT_NEAR(s.distance, best, 1e-12);
    EXPECT_GT(ref.closest(p).point.y(), 1e-4);  // what a plain closest point does here
  }
  EXPECT_FALSE(ref.closest_on_border(inner, Vec3(0.5, 0.5, 0.3), 0.2, open).found());
}

TEST(ReferenceSurface, closest_on_border_stays_within_its_arc) {
  // A point on the side y = 0 of a flat grid slides between x = 0.035 (behind) and
  // 0.07 (ahead). Backward the border turns the corner (0, 0) and runs up the side
  // x = 0, which is nearest to a target past the corner.
  TriMesh t = tri_grid(40, 40);
  clean(t);
  const ReferenceSurface ref(t);
  Index start = kNone;  // a triangle with a corner at (0.05, 0)
  for (Index f = 0; f < ref.mesh().n_faces(); ++f)
    for (Index v : ref.mesh().faces[f])
      if ((ref.mesh().positions[v] - Vec3(0.05, 0, 0)).norm() < 1e-12) start = f;
  ASSERT_NE(start, kNone);
  const Vec3 from(0.0625, 0, 0), past_corner(-0.01, 0.03, 0);
  const ReferenceSurface::BorderArc arc{from, Vec3(0.07, 0, 0), Vec3(0.035, 0, 0)};
  const ReferenceSurface::BorderArc open{from, Vec3(0.5, 0.5, 1), Vec3(0.5, 0.5, 1)};  // ends off the border
  EXPECT_LT((ref.closest_on_border(start, past_corner, 0.2, open).point - Vec3(0, 0.03, 0)).norm(), 1e-12);
  EXPECT_LT((ref.closest_on_border(start, past_corner, 0.2, arc).point - arc.behind).norm(), 1e-12);
  EXPECT_LT((ref.closest_on_border(start, Vec3(0.5, 0.01, 0), 0.2, arc).point - arc.ahead).norm(), 1e-12);
  EXPECT_LT((ref.closest_on_border(start, Vec3(0.04, 0.01, 0), 0.2, arc).point - Vec3(0.04, 0, 0)).norm(), 1e-12);
  // Ends a few edges away (in the middle of an edge), past the corner and along the side.
  const ReferenceSurface::BorderArc wide{from, Vec3(0.21, 0, 0), Vec3(0, 0.04, 0)};
  EXPECT_LT((ref.closest_on_border(start, past_corner, 0.2, wide).point - Vec3(0, 0.03, 0)).norm(), 1e-12);
  EXPECT_LT((ref.closest_on_border(start, Vec3(-0.01, 0.5, 0), 0.2, wide).point - wide.behind).norm(), 1e-12);
  EXPECT_LT((ref.closest_on_border(start, Vec3(0.5, 0.01, 0), 0.2, wide).point - wide.ahead).norm(), 1e-12);
}

TEST(ReferenceSurface, border_distance_tries_every_border_edge) {
  // The unit square's grid: the distance to the nearest of its four sides, from inside,
  // above it and beyond a corner; a closed sphere has no border at all.
  TriMesh t = tri_grid(40, 40);
  clean(t);
  const ReferenceSurface ref(t);
  EXPECT_NEAR(ref.border_distance(Vec3(0.3, 0.1, 0)), 0.1, 1e-12);
  EXPECT_NEAR(ref.border_distance(Vec3(0.5, 0.5, 0)), 0.5, 1e-12);
  EXPECT_NEAR(ref.border_distance(Vec3(0.9, 0.5, 0.3)), 0.5 * std::sqrt(0.4), 1e-12);  // hypot(0.1, 0.3)
  EXPECT_NEAR(ref.border_distance(Vec3(1.3, -0.4, 0)), 0.5, 1e-12);                  // from the corner (1, 0)
  EXPECT_EQ(ref.border_distance(Vec3(1, 0, 0)), 0.0);
  const ReferenceSurface sphere(tri_sphere(10, 20));
  EXPECT_EQ(sphere.border_distance(Vec3::Zero()), std::numeric_limits<double>::infinity());
}

TEST(ReferenceSurface, closest_on_border_takes_points_rounded_off_the_border) {
  // closest() searches from a float copy of its point, so a border vertex lies off the
  // border by up to about 1e-7 of the diagonal (here 5e-6 input edges). Its arc must
  // still start and end where it does: matched within 1e-9 input edges, the walk started
  // on another edge of the triangle and slid past the arc's ends.
  TriMesh t = tri_grid(40, 40);
  clean(t);
  const ReferenceSurface ref(t);
  const Vec3 off(0, 1e-7, 1e-7);  // inside the grid and above it
  for (const Vec3& corner : {Vec3(0.05, 0, 0), Vec3(0.075, 0, 0)}) {
    Index start = kNone;  // a triangle with a corner there
    for (Index f = 0; f < ref.mesh().n_faces() && start == kNone; ++f)
      for (Index v : ref.mesh().faces[f])
        if ((ref.mesh().positions[v] - corner).norm() < 1e-12) start = f;
    ASSERT_NE(start, kNone);
    const ReferenceSurface::BorderArc arc{Vec3(0.0625, 0, 0) + off, Vec3(0.07, 0, 0) + off, Vec3(0.035, 0, 0) + off};
    const Vec3 past_corner(-0.01, 0.03, 0);
    EXPECT_LT((ref.closest_on_border(start, past_corner, 0.2, arc).point - Vec3(0.035, 0, 0)).norm(), 1e-6);
    EXPECT_LT((ref.closest_on_border(start, Vec3(0.5, 0.01, 0), 0.2, arc).point - Vec3(0.07, 0, 0)).norm(), 1e-6);
    EXPECT_LT((ref.closest_on_border(start, Vec3(0.04, 0.01, 0), 0.2, arc).point - Vec3(0.04, 0, 0)).norm(), 1e-12);
  }
}

TEST(Simplify, a_strip_one_quad_wide_shortens_by_chord_collapses) {
  // 60 square quads in a row, bent: no diagonal collapse can thin it without a pinch.
  TriMesh t = tri_grid(60, 1);
  for (Vec3& p : t.positions) p = Vec3(p.x(), p.y() / 60, 0.2 * std::sin(M_PI * p.x()));
  Case c = prepare(t);
  ASSERT_EQ(c.quads.n_faces(), 60u);
  const ReferenceSurface ref(c.tri);
  const SimplifyReport r = run_and_check(c.quads, 15, ref);
  EXPECT_GT(r.chord_collapses, 0u);
  EXPECT_EQ(count_components(c.quads), 1u);
  // The strip keeps its ends (border corners stay where they are) ...
  double x_lo = 1, x_hi = 0;
  for (Index v = 0; v < c.quads.n_vertices(); ++v)
    x_lo = std::min(x_lo, c.quads.position(v).x()), x_hi = std::max(x_hi, c.quads.position(v).x());
  EXPECT_NEAR(x_lo, 0.0, 1e-9);
  EXPECT_NEAR(x_hi, 1.0, 1e-9);
  // ... and the quads grew evenly along it (across it they keep its width).
  for (Index f = 0; f < c.quads.n_faces(); ++f) {
    double lo = 1, hi = 0;
    for (Index k = 0; k < 4; ++k) lo = std::min(lo, c.quads.position(c.quads.vertex(f, k)).x()),
                                   hi = std::max(hi, c.quads.position(c.quads.vertex(f, k)).x());
    const double share = (hi - lo) * double(c.quads.n_faces());
    EXPECT_GT(share, 0.5);
    EXPECT_LT(share, 2.0);
  }

  Case without = prepare(t);
  SimplifyOptions opt;
  opt.target_faces = 15;
  opt.chord_collapses = false;
  EXPECT_GT(simplify(without.quads, ref, opt).faces, 50u);
}

TEST(Simplify, border_coarsening_stops_at_the_target) {
  // Cells four times as tall as wide: the borders along x have edges short enough to
  // coarsen from the start, and one pass of border coarsening (after the first 64
  // collapses) took its ears all along them: asked for 1,530 of the 1,600 quads, the run
  // ended at 1,484.
  Case c = prepare(tri_grid(80, 20));  // the unit square
  ASSERT_EQ(c.quads.n_faces(), 1600u);
  const ReferenceSurface ref(c.tri);
  SimplifyOptions opt;
  opt.target_faces = 1530;
  opt.check_invariants = true;
  const SimplifyReport r = simplify(c.quads, ref, opt);
  EXPECT_GT(r.border_collapses, 0u);
  EXPECT_EQ(c.quads.n_faces(), 1530u);
}

TEST(Simplify, a_strip_keeps_its_last_quad_and_its_corners) {
  // The strip above asked for one quad: chord collapses across it leave one, the whole
  // piece, whose corners all turn alike. The springs then slid two of them together (the
  // last quad a triangle: bottom corners at x = 0.466 and 0.535).
  TriMesh t = tri_grid(12, 1);
  for (Vec3& p : t.positions) p.y() /= 12;
  Case c = prepare(t);
  const ReferenceSurface ref(c.tri);
  SimplifyOptions opt;
  opt.target_faces = 1;
  opt.check_invariants = true;
  const SimplifyReport r = simplify(c.quads, ref, opt);
  validate(c.quads);
  EXPECT_GT(r.chord_collapses, 0u);
  ASSERT_EQ(c.quads.n_faces(), 1u);
  std::vector<Vec3> corners;
  for (Index k = 0; k < 4; ++k) corners.push_back(c.quads.position(c.quads.vertex(0, k)));
  for (const Vec3& corner : {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1.0 / 12, 0), Vec3(0, 1.0 / 12, 0)}) {
    const auto at = [&](const Vec3& x) { return (x - corner).norm() < 1e-9; };
    EXPECT_TRUE(std::any_of(corners.begin(), corners.end(), at)) << corner.transpose();
  }
}

TEST(Metrics, regular_grid_and_cube) {
  const QuadQuality g = quad_quality(quad_grid(6, 5));
  EXPECT_DOUBLE_EQ(g.regular_percent, 100.0 * (42 - 4) / 42);  // only the 4 corners are irregular
  EXPECT_EQ(g.max_valence, 4);
  EXPECT_DOUBLE_EQ(g.homeometry_min, 1.0);
  EXPECT_DOUBLE_EQ(g.homeometry_max, 1.0);
  EXPECT_EQ(g.nonconvex_faces, 0u);
  const QuadQuality c = quad_quality(cube());
  EXPECT_EQ(c.faces, 6u);
  EXPECT_EQ(c.max_valence, 3);
  EXPECT_DOUBLE_EQ(c.regular_percent, 0.0);
}

TEST(Metrics, a_quad_bent_past_90_degrees_is_folded) {
  // p3 below the edge p0-p1 and raised: 120 degrees between the triangles' normals,
  // whichever diagonal splits it. Pulled back into the plane, it is a flat square.
  const Vec3 p0(0, 0, 0), p1(1, 0, 0), p2(1, 1, 0), bent(0, -1, 1), flat(0, 1, 0);
  EXPECT_TRUE(quad_folds(p0, p1, p2, bent));
  EXPECT_NEAR(quad_fold_cos(p0, p1, p2, bent), -0.5, 1e-12);
  EXPECT_FALSE(quad_folds(p0, p1, p2, flat));
  EXPECT_DOUBLE_EQ(quad_fold_cos(p0, p1, p2, flat), 1.0);
  EXPECT_FALSE(quad_folds(p0, p1, p2, Vec3(0, 0, 1)));  // bent along one diagonal only
  EXPECT_EQ(quad_quality(QuadMesh::from_faces({p0, p1, p2, bent}, {{0, 1, 2, 3}})).folded_faces, 1u);
  EXPECT_EQ(quad_quality(QuadMesh::from_faces({p0, p1, p2, flat}, {{0, 1, 2, 3}})).folded_faces, 0u);
  EXPECT_EQ(quad_quality(quad_grid(6, 5)).folded_faces, 0u);
}

// A quad counts as flipped when the input nearest its centre faces against it, and so does
// the input nearest two of its corners or more. Over a thin curved shell (two sheets 0.02
// apart, like a wing's) a quad with its corners on the outer sheet bulges 0.09 below
// them: its centre is nearest the inner sheet, which faces the other way, yet the quad
// faces like the sheet its corners are on.
TEST(Metrics, a_quad_is_flipped_by_the_input_under_its_centre_and_corners) {
  auto sheet = [](double radius, bool outwards) {
    TriMesh t = tri_grid(20, 20);
    for (Vec3& p : t.positions) {
      const double angle = (p.y() - 0.5) * M_PI / 3;
      p = Vec3(p.x(), radius * std::sin(angle), radius * std::cos(angle));
    }
    if (!outwards)
      for (auto& f : t.faces) std::swap(f[1], f[2]);
    return t;
  };
  TriMesh shell = sheet(1.0, true);
  append(shell, sheet(0.98, false));
  const ReferenceSurface ref(shell);
  const double a = 25 * M_PI / 180;
  const std::vector<Vec3> corners = {{0.2, -std::sin(a), std::cos(a)},
                                     {0.8, -std::sin(a), std::cos(a)},
                                     {0.8, std::sin(a), std::cos(a)},
                                     {0.2, std::sin(a), std::cos(a)}};
  const QuadMesh up = QuadMesh::from_faces(corners, {{0, 1, 2, 3}});
  const auto q = up.positions_of(up.face_vertices(0));
  const SurfacePoint centre = ref.closest_to_quad_centre(q.data());
  ASSERT_TRUE(centre.found());
  ASSERT_LT(ref.normal_at(centre).z(), 0);  // the inner sheet: the centre alone said flipped
  EXPECT_EQ(quad_quality(up, &ref).flipped_faces, 0u);
  // Over a plane, the same quad a little above it counts as flipped when turned over.
  const ReferenceSurface plane(tri_grid(4, 4));
  const std::vector<Vec3> square = {{0.2, 0.2, 0.01}, {0.8, 0.2, 0.01}, {0.8, 0.8, 0.01}, {0.2, 0.8, 0.01}};
  EXPECT_EQ(quad_quality(QuadMesh::from_faces(square, {{0, 1, 2, 3}}), &plane).flipped_faces, 0u);
  EXPECT_EQ(quad_quality(QuadMesh::from_faces(square, {{3, 2, 1, 0}}), &plane).flipped_faces, 1u);
}

// A coarse CAD cone (33 segments, its base a fan from one rim vertex) has vertex normals
// that mix its rim's two sides over its long triangles: by the rim its base's interpolated
// normal faces up. A quad lying flat on the base there, facing down like it, follows the
// triangles under it and is not flipped; turned over, it is. By the interpolated normals
// alone it was the other way round.
TEST(Metrics, a_quad_flat_on_a_coarse_triangle_follows_it_whatever_the_vertex_normals) {
  const ReferenceSurface ref(cad_cone(33, true));
  auto at = [](double radius, double degrees) {
    const double a = degrees * M_PI / 180;
    return Vec3(radius * std::cos(a), radius * std::sin(a), 0);
  };
  const std::vector<Vec3> corners = {at(0.90, -54), at(0.90, -46), at(0.97, -46), at(0.97, -54)};
  const QuadMesh down = QuadMesh::from_faces(corners, {{0, 1, 2, 3}});
  const auto q = down.positions_of(down.face_vertices(0));
  ASSERT_LT(down.face_area_normal(0).z(), 0);
  // The interpolated normals under its centre and two corners or more face up: by them
  // alone, flipped.
  ASSERT_GT(ref.normal_at(ref.closest_to_quad_centre(q.data())).z(), 0);
  int up = 0;
  for (const Vec3& x : q) up += ref.normal_at(ref.closest(x)).z() > 0;
  ASSERT_GE(up, 2);
  EXPECT_EQ(quad_quality(down, &ref).flipped_faces, 0u);
  EXPECT_EQ(quad_quality(QuadMesh::from_faces(corners, {{3, 2, 1, 0}}), &ref).flipped_faces, 1u);
}

// The filters select the quads the quality counts as flawed, so quad_quality() lists them:
// over a plane, one sound quad, then one folded, one turned over (flipped) and one with a
// reflex corner, each listed once, by id.
TEST(Metrics, flawed_quads_are_listed_by_id) {
  const ReferenceSurface plane(tri_grid(4, 4));
  std::vector<Vec3> positions;
  std::vector<std::array<Index, 4>> faces;
  auto add = [&](double x0, std::array<Vec3, 4> corners, bool turned) {
    const Index first = Index(positions.size());
    for (const Vec3& c : corners) positions.push_back(Vec3(x0, 0.4, 0.01) + 0.2 * c);
    faces.push_back(turned ? std::array<Index, 4>{first + 3, first + 2, first + 1, first}
                           : std::array<Index, 4>{first, first + 1, first + 2, first + 3});
  };
  const Vec3 p0(0, 0, 0), p1(1, 0, 0), p2(1, 1, 0);
  add(0.0, {p0, p1, p2, Vec3(0, 1, 0)}, false);    // sound
  add(0.25, {p0, p1, p2, Vec3(0, -1, 1)}, false);  // folded
  add(0.5, {p0, p1, p2, Vec3(0, 1, 0)}, true);     // flipped
  add(0.75, {p0, p1, p2, Vec3(0.8, 0.2, 0)}, false);  // non-convex
  const QuadMesh m = QuadMesh::from_faces(positions, faces);
  std::vector<Index> flawed;
  const QuadQuality q = quad_quality(m, &plane, &flawed);
  EXPECT_EQ(q.folded_faces, 1u);
  EXPECT_EQ(q.flipped_faces, 1u);
  EXPECT_EQ(q.nonconvex_faces, 1u);
  EXPECT_EQ(flawed, (std::vector<Index>{1, 2, 3}));
  flawed.clear();
  quad_quality(quad_grid(6, 5), nullptr, &flawed);
  EXPECT_TRUE(flawed.empty());
}

// A tetrahedron floating beside a scan (debris) converts to two quads on its four corners,
// back to back: folded, and the least a closed quad mesh has. The quality counts such
// pieces and the log's note names them, so that a user knows where the folds are.
TEST(Metrics, closed_pieces_of_two_quads_are_counted_and_named) {
  QuadMesh grid = quad_grid(6, 5);
  std::vector<Vec3> positions = grid.positions();
  std::vector<std::array<Index, 4>> quads;
  for (Index f = 0; f < grid.n_faces(); ++f) quads.push_back(grid.face_vertices(f));
  EXPECT_EQ(quad_quality(grid).two_quad_pieces, 0u);
  EXPECT_EQ(defects_note(quad_quality(grid)), "");
  for (int piece = 0; piece < 2; ++piece) {
    const Index o = Index(positions.size());
    for (const Vec3& c : {Vec3(1, 1, 1), Vec3(1, -1, -1), Vec3(-1, 1, -1), Vec3(-1, -1, 1)})
      positions.push_back(0.05 * c + Vec3(0.5 + piece, 0.5, 1));
    quads.push_back({o, o + 1, o + 2, o + 3});
    quads.push_back({o + 3, o + 2, o + 1, o});
    const QuadMesh m = QuadMesh::from_faces(positions, quads);
    const QuadQuality q = quad_quality(m);
    EXPECT_EQ(q.two_quad_pieces, Index(piece + 1));
    // Their diagonals are shared by nature, not by an operator (shared_diagonals() leaves them out).
    EXPECT_TRUE(shared_diagonals(m).empty());
    EXPECT_EQ(q.folded_faces, Index(2 * (piece + 1)));
    const std::string pieces = piece == 0 ? "; 1 closed piece is two quads on the same four corners, "
                                          : "; 2 closed pieces are two quads on the same four corners, ";
    EXPECT_NE(defects_note(q).find(pieces), std::string::npos) << defects_note(q);
  }
}

// Border loops and the note on crowded holes: a patch's outline is one loop and gets no
// note; holes add a loop each, and a result whose border holds a fifth of its vertices
// and under 70% regular ones gets the note.
TEST(Metrics, border_loops_are_counted_and_crowded_holes_noted) {
  const QuadMesh grid = quad_grid(6, 5);
  QuadQuality q = quad_quality(grid);
  EXPECT_EQ(q.border_loops, 1u);
  EXPECT_EQ(q.border_vertices, 22u);
  EXPECT_EQ(holes_note(q), "");
  std::vector<std::array<Index, 4>> quads;
  for (Index f = 0; f < grid.n_faces(); ++f)
    if (f != 7 && f != 15) quads.push_back(grid.face_vertices(f));  // two inner quads apart
  q = quad_quality(QuadMesh::from_faces(grid.positions(), quads));
  EXPECT_EQ(q.border_loops, 3u);
  EXPECT_EQ(q.border_vertices, 30u);
  q.regular_percent = 69;  // 30 of 42 vertices on the border: crowded, if irregular
  EXPECT_EQ(holes_note(q).rfind("30 of the result's 42 vertices lie on its border, round 3 holes or outlines, "
                                "and 69% are regular", 0), 0u) << holes_note(q);
  q.regular_percent = 70;
  EXPECT_EQ(holes_note(q), "");
  q.regular_percent = 69, q.border_vertices = 8;
  EXPECT_EQ(holes_note(q), "");
}

TEST(Metrics, offset_sphere_distance_is_the_offset) {
  TriMesh inner = tri_sphere(60, 80, 1.0);
  clean(inner);
  const ReferenceSurface ref(inner);
  TriMesh outer = tri_sphere(60, 80, 1.05);
  clean(outer);
  const QuadMesh q = tri_to_quad(outer);
  const SurfaceDistance d = surface_distance(q, ref, 100000);
  const double expected = 0.05 / ref.bbox_diagonal();
  EXPECT_NEAR(d.hausdorff, expected, 0.05 * expected);
  EXPECT_NEAR(d.rms, expected, 0.05 * expected);
  EXPECT_NEAR(d.mean_to_ref, expected, 0.05 * expected);
  EXPECT_DOUBLE_EQ(d.projectability, 1.0);
  // A planar patch against itself: 0 up to the float32 rounding of the BVH.
  TriMesh plane = tri_grid(20, 20);
  clean(plane);
  const ReferenceSurface plane_ref(plane);
  const SurfaceDistance zero = surface_distance(tri_to_quad(plane), plane_ref, 100000);
  EXPECT_LT(zero.hausdorff, 1e-6);
}

TEST(Simplify, results_do_not_depend_on_the_unit_of_length) {
  // The same wavy grid with a strip folded back onto it (laid flat on loading), written
  // in units 2^20, 2^40, 2^60 and 2^96 times smaller and larger: a power of two scales
  // every product and quotient exactly, so every step must give the same mesh, scaled,
  // unless it compares a length, area or normal to an absolute constant, or a float under-
  // or overflows. Three comparisons did: Eigen's isZero(), fuzzy by 1e-12 (in units 2^15
  // smaller the fold was left, and the search for the closest point facing a quad's way
  // took any face), and the springs' test for coincident ends, 1e-30 (2^-96). And Embree,
  // in float, answered otherwise at 2^-60 (bunny.ply: from 2^-30) until its coordinates
  // were scaled to a diagonal between 1 and 2. Beyond 1e-30 and 1e30 across, meshes are
  // refused (PrepareInput.refuses_a_mesh_too_small_or_too_large_to_compute_with).
  const TriMesh base = folded_grid(48, nullptr, 5, 1.5, 0.15);
  const auto run = [&](double scale, const SimplifyParams& params) {
    MeshFile file{base.positions, base.faces, {}};
    for (Vec3& p : file.positions) p *= scale;
    const Input in = simplified(file, params);
    EXPECT_EQ(in.clean.unfolded_patches, 1u) << "scale " << scale;
    validate(in.quads);
    return in.quads;
  };
  for (const SimplifyParams& params : uniform_and_halting(150)) {
    const QuadMesh unit = run(1.0, params);
    for (const int exponent : {-96, -60, -40, -20, 20, 40, 60, 96}) {
      const double scale = std::ldexp(1.0, exponent);
      SCOPED_TRACE(std::string(params.adaptive ? "adaptive" : "uniform") + ", scale 2^" + std::to_string(exponent));
      expect_scaled_copy(unit, run(scale, params), scale);
    }
  }
}

TEST(Simplify, results_do_not_depend_on_the_order_of_faces_and_vertices_in_the_file) {
  // Loading renumbers faces along a Morton curve and vertices by first use
  // (sort_spatially()), so a file written in another order gives the same quads, vertex
  // for vertex. Not tested, because they do count: the order of the corners within each
  // triangle (rounding differs), and, where folds are laid flat on loading, the order in
  // which their vertices are solved for (the file's).
  const TriMesh base = tri_grid(40, 40, 0.3);
  std::mt19937 rng(7);
  std::vector<Index> vertex_order(base.n_vertices()), new_id(base.n_vertices());
  std::iota(vertex_order.begin(), vertex_order.end(), Index(0));
  std::shuffle(vertex_order.begin(), vertex_order.end(), rng);
  MeshFile shuffled;
  for (Index i = 0; i < base.n_vertices(); ++i) {
    shuffled.positions.push_back(base.positions[vertex_order[i]]);
    new_id[vertex_order[i]] = i;
  }
  for (const auto& f : base.faces) shuffled.triangles.push_back({new_id[f[0]], new_id[f[1]], new_id[f[2]]});
  std::shuffle(shuffled.triangles.begin(), shuffled.triangles.end(), rng);
  for (const SimplifyParams& params : uniform_and_halting(150)) {
    SCOPED_TRACE(params.adaptive ? "adaptive" : "uniform");
    expect_scaled_copy(simplified(MeshFile{base.positions, base.faces, {}}, params).quads,
                       simplified(shuffled, params).quads, 1.0);
  }
}
