// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// Creases kept: their curves on M0 (reference/creases.h), the conversion that pairs no
// triangles across them, and the simplifier that keeps them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>

#include "fixtures/shapes.h"
#include "quadsimp/convert/tri_to_quad.h"
#include "quadsimp/fitmap/fitmap.h"
#include "quadsimp/mesh/clean.h"
#include "quadsimp/metrics/metrics.h"
#include "quadsimp/reference/creases.h"
#include "quadsimp/simplify/pipeline.h"
#include "quadsimp/simplify/simplify.h"

using namespace qs;
using namespace qs::fixtures;

namespace {

Creases creases_of(const TriMesh& t, double angle) { return Creases(t, triangle_adjacency(t), angle); }

// The number of coordinates of p at 0 or 1: 2 on an edge of the unit cube, 3 at a corner.
int on_cube_sides(const Vec3& p) {
  int n = 0;
  for (int k = 0; k < 3; ++k) n += std::abs(p[k]) < 1e-12 || std::abs(p[k] - 1) < 1e-12;
  return n;
}

// A roof: tri_grid(n, n) raised to `height` along its diagonal x + y = 1, which for an
// odd n runs along the diagonals its cells are split at.
TriMesh roof(int n, double height) {
  TriMesh t = tri_grid(n, n);
  for (Vec3& p : t.positions) p.z() = height * (1 - std::abs(p.x() + p.y() - 1));
  return t;
}

bool on_ridge(const Vec3& a, const Vec3& b) {
  return std::abs(a.x() + a.y() - 1) < 1e-12 && std::abs(b.x() + b.y() - 1) < 1e-12;
}

// Every edge of M0 whose ends both satisfy `on` (and are not the same) is an edge of a quad.
template <class On>
::testing::AssertionResult crease_edges_are_quad_edges(const TriMesh& t, const QuadMesh& q, On&& on) {
  std::set<std::pair<Index, Index>> quad_edges;
  std::map<std::array<long long, 3>, Index> id;
  auto key = [](const Vec3& p) {
    return std::array<long long, 3>{std::llround(p.x() * 1e9), std::llround(p.y() * 1e9), std::llround(p.z() * 1e9)};
  };
  for (Index v = 0; v < q.vertex_capacity(); ++v)
    if (q.is_vertex_live(v)) id[key(q.position(v))] = v;
  for (Index f = 0; f < q.face_capacity(); ++f)
    for (Index k = 0; k < 4 && q.is_face_live(f); ++k)
      quad_edges.insert(std::minmax(q.vertex(f, k), q.vertex(f, k + 1)));
  int missing = 0, seen = 0;
  for (const auto& f : t.faces)
    for (int k = 0; k < 3; ++k) {
      const Vec3 &a = t.positions[f[k]], &b = t.positions[f[(k + 1) % 3]];
      if (!on(a, b)) continue;
      ++seen;
      const auto ia = id.find(key(a)), ib = id.find(key(b)), im = id.find(key(0.5 * (a + b)));
      if (ia == id.end() || ib == id.end()) {
        ++missing;
        continue;
      }
      // A crease edge split at its midpoint (the conversion's parity fix) is two quad edges.
      const bool whole = quad_edges.count(std::minmax(ia->second, ib->second)) > 0;
      const bool halves = im != id.end() && quad_edges.count(std::minmax(ia->second, im->second)) > 0 &&
                          quad_edges.count(std::minmax(im->second, ib->second)) > 0;
      missing += !whole && !halves;
    }
  if (seen == 0) return ::testing::AssertionFailure() << "no crease edge in the input";
  if (missing > 0)
    return ::testing::AssertionFailure() << missing << " of " << seen << " crease edges are no quad edges";
  return ::testing::AssertionSuccess();
}

bool on_cube_edge(const Vec3& a, const Vec3& b) {
  // Both ends on one edge of the cube: two coordinates at 0 or 1, the same for both.
  int shared = 0;
  for (int k = 0; k < 3; ++k)
    shared += (std::abs(a[k]) < 1e-12 && std::abs(b[k]) < 1e-12) ||
              (std::abs(a[k] - 1) < 1e-12 && std::abs(b[k] - 1) < 1e-12);
  return shared >= 2;
}

// Splits the M0 edge between positions pa and pb at its midpoint, in its triangles.
void split_edge(TriMesh& t, const Vec3& pa, const Vec3& pb) {
  Index a = kNone, b = kNone;
  for (Index v = 0; v < t.n_vertices(); ++v) {
    if ((t.positions[v] - pa).norm() < 1e-12) a = v;
    if ((t.positions[v] - pb).norm() < 1e-12) b = v;
  }
  ASSERT_NE(a, kNone);
  ASSERT_NE(b, kNone);
  const Index m = t.n_vertices();
  t.positions.push_back(0.5 * (pa + pb));
  const Index n = t.n_faces();
  int split = 0;
  for (Index f = 0; f < n; ++f)
    for (int k = 0; k < 3; ++k) {
      const Index u = t.faces[f][k], w = t.faces[f][(k + 1) % 3], c = t.faces[f][(k + 2) % 3];
      if (!((u == a && w == b) || (u == b && w == a))) continue;
      t.faces[f] = {u, m, c};
      t.faces.push_back({m, w, c});
      ++split;
      break;
    }
  ASSERT_GE(split, 1);
}

// t's quads with creases at `angle`, checked whole: valid, every triangle paired, no
// refinement, and every edge `on` tells a crease of is one of theirs.
template <class On>
QuadMesh converted_apart(const TriMesh& t, double angle, ConvertReport& report, On&& on) {
  ConvertOptions o;
  o.crease_angle_deg = angle;
  QuadMesh q = tri_to_quad(t, o, &report);
  validate(q);
  EXPECT_FALSE(report.refined);
  EXPECT_EQ(report.pairing_rate(), 1.0);
  EXPECT_TRUE(crease_edges_are_quad_edges(t, q, on));
  return q;
}

}  // namespace

TEST(Creases, a_cube_has_twelve_curves_between_eight_corners) {
  const TriMesh t = tri_cube(4);
  const Creases c = creases_of(t, 30);
  EXPECT_EQ(c.n_curves(), 12u);
  EXPECT_EQ(c.n_corners(), 8u);
  EXPECT_EQ(c.n_edges(), 48u);
  for (Index i = 0; i < c.n_curves(); ++i) {
    EXPECT_FALSE(c.closed(i));
    const auto& v = c.vertices(i);
    ASSERT_EQ(v.size(), 5u);
    EXPECT_EQ(c.span(i), 4.0);
    EXPECT_EQ(on_cube_sides(t.positions[v.front()]), 3);
    EXPECT_EQ(on_cube_sides(t.positions[v.back()]), 3);
    for (std::size_t k = 1; k + 1 < v.size(); ++k) EXPECT_EQ(on_cube_sides(t.positions[v[k]]), 2);
  }
}

TEST(Creases, a_noisy_cube_still_has_twelve_curves_between_eight_corners) {
  // A scanned machined part: the cube's vertices moved by noise of 5% and 7% of an edge.
  // One triangle's normal against its neighbour's then gives sharp edges off the cube's
  // edges and gaps along them, and the creases zigzag: the normals are filtered first, and
  // a turn must hold a few edges on, so the creases are the cube's twelve edges again.
  // Without the filtering 16 and 31 curves; without the turn's reach 12 and 33.
  for (const auto& [share, angle] : {std::pair(0.05, 45.0), std::pair(0.07, 60.0)}) {
    TriMesh t = tri_cube(24);
    std::mt19937 rng(1);
    std::normal_distribution<double> noise(0, share * 2.0 / 24);
    for (Vec3& p : t.positions) p += Vec3(noise(rng), noise(rng), noise(rng));
    const Creases c = creases_of(t, angle);
    EXPECT_EQ(c.n_curves(), 12u) << share;
    EXPECT_EQ(c.n_corners(), 8u) << share;
    EXPECT_EQ(c.n_edges(), 12u * 24) << share;
  }
}

TEST(Creases, none_below_the_angle_or_without_one) {
  EXPECT_TRUE(creases_of(tri_cube(4), 0).empty());
  EXPECT_TRUE(creases_of(tri_cube(4), 95).empty());  // a cube's edges turn by 90 degrees
  EXPECT_EQ(creases_of(tri_cube(4), 85).n_curves(), 12u);
  EXPECT_TRUE(creases_of(tri_sphere(20, 40), 30).empty());
  EXPECT_TRUE(creases_of(tri_grid(6, 6), 1).empty());
}

TEST(Creases, a_cylinder_has_two_closed_rims) {
  const int around = 32;
  const TriMesh t = cad_cylinder(around, 4, 2.0);
  const Creases c = creases_of(t, 30);
  ASSERT_EQ(c.n_curves(), 2u);
  EXPECT_EQ(c.n_corners(), 0u);
  for (Index i = 0; i < 2; ++i) {
    EXPECT_TRUE(c.closed(i));
    EXPECT_EQ(c.span(i), double(around));
    for (Index v : c.vertices(i)) {
      const Vec3& p = t.positions[v];
      EXPECT_NEAR(std::hypot(p.x(), p.y()), 1.0, 1e-12);
      EXPECT_TRUE(p.z() == 0.0 || p.z() == 2.0);
    }
  }
}

TEST(Creases, closest_stays_within_its_arc) {
  const TriMesh t = tri_cube(4);
  const Creases c = creases_of(t, 30);
  for (Index i = 0; i < c.n_curves(); ++i) {
    const auto& v = c.vertices(i);
    const Vec3 a = t.positions[v.front()], b = t.positions[v.back()];
    // A point off the middle of the curve comes back onto it, at its parameter.
    const Vec3 mid = 0.5 * (a + b), off = mid + 0.1 * Vec3(1, 1, 1);
    const Creases::CurvePoint x = c.closest(t, i, off, 2.0, 2.0, 2.0);
    ASSERT_TRUE(x.foot.found());
    EXPECT_NEAR(x.s, 2.0, 0.41);
    EXPECT_LT((x.foot.point - (mid + 0.1 * (b - a).normalized().dot(Vec3(1, 1, 1)) * (b - a).normalized())).norm(),
              1e-12);
    // Bounded ahead by half a segment, a point at the curve's end stops there.
    const Creases::CurvePoint y = c.closest(t, i, b, 1.0, 1.0, 0.5);
    EXPECT_NEAR(y.s, 1.5, 1e-12);
    EXPECT_LT((y.foot.point - c.at(t, i, 1.5).foot.point).norm(), 1e-12);
    // The foot is a point of M0: its triangle's corners give it back.
    const auto& f = t.faces[y.foot.face];
    const Vec3 p = (1 - y.foot.u - y.foot.v) * t.positions[f[0]] + y.foot.u * t.positions[f[1]] +
                   y.foot.v * t.positions[f[2]];
    EXPECT_LT((p - y.foot.point).norm(), 1e-12);
  }
  // Round a closed rim the arc wraps past parameter 0.
  const TriMesh cyl = cad_cylinder(32, 4, 2.0);
  const Creases r = creases_of(cyl, 30);
  const Vec3 behind = r.at(cyl, 0, 30.5).foot.point;
  const Creases::CurvePoint w = r.closest(cyl, 0, behind, 0.5, 2.0, 2.0);
  EXPECT_NEAR(w.s, 30.5, 1e-9);
  EXPECT_NEAR(r.ahead_of(0, 31.0, 1.0), 2.0, 1e-12);
  EXPECT_NEAR(r.ahead_of(0, 1.0, 31.0), 30.0, 1e-12);
}

TEST(Creases, place_of_tells_corners_curves_and_the_rest) {
  const TriMesh t = tri_cube(4);
  const Creases c = creases_of(t, 30);
  int corners = 0, curve_vertices = 0, midpoints = 0, plain = 0;
  for (Index f = 0; f < t.n_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Vec3 &a = t.positions[t.faces[f][k]], &b = t.positions[t.faces[f][(k + 1) % 3]];
      const Creases::Place pa = c.place_of(t, f, a, 1e-9);
      const int sides = on_cube_sides(a);
      if (sides == 3) corners += pa.corner;
      if (sides == 2) curve_vertices += pa.curve != kNone && !pa.corner;
      if (sides < 2) plain += pa.curve == kNone && !pa.corner;
      const Creases::Place pm = c.place_of(t, f, 0.5 * (a + b), 1e-9);
      if (on_cube_edge(a, b)) {
        ASSERT_NE(pm.curve, kNone);
        EXPECT_NEAR(pm.s - std::floor(pm.s), 0.5, 1e-9);
        EXPECT_LT((c.at(t, pm.curve, pm.s).foot.point - 0.5 * (a + b)).norm(), 1e-12);
        ++midpoints;
      } else {
        EXPECT_EQ(pm.curve, kNone);
      }
    }
  EXPECT_GT(corners, 0);
  EXPECT_GT(curve_vertices, 0);
  EXPECT_GT(plain, 0);
  EXPECT_EQ(midpoints, 2 * 48);  // each crease edge seen from both its triangles
}

TEST(Creases, the_conversion_pairs_no_triangles_across_a_crease) {
  // A roof whose sides meet at 24 degrees: the greedy pairing takes pairs bent up to 60,
  // and pairs the two triangles of each cell along the ridge. 81 triangles lie on either
  // side: one ridge edge is split so that each side pairs up on its own.
  const TriMesh t = roof(9, 0.15);
  ConvertReport report;
  converted_apart(t, 15, report, on_ridge);
  EXPECT_EQ(report.crease_splits, 1u);
  EXPECT_EQ(report.parity_splits, 0u);
  EXPECT_FALSE(crease_edges_are_quad_edges(t, tri_to_quad(t), on_ridge));
  // An angle above the roof's turns nothing into a crease.
  ConvertOptions blunt;
  blunt.crease_angle_deg = 30;
  EXPECT_EQ(tri_to_quad(t, blunt).quads(), tri_to_quad(t).quads());
}

TEST(Creases, parts_between_creases_are_made_even_across_them) {
  // Splitting one segment of an edge of the cube adds a triangle to both sides at it. Two
  // such splits, x = 1 | y = 1 and y = 1 | x = 0, leave the opposite sides x = 1 and x = 0
  // odd: the parity fix hands the oddness across y = 1.
  TriMesh t = tri_cube(4);
  split_edge(t, Vec3(1, 1, 0.25), Vec3(1, 1, 0.5));
  split_edge(t, Vec3(0, 1, 0.5), Vec3(0, 1, 0.75));
  ConvertReport report;
  converted_apart(t, 30, report, on_cube_edge);
  EXPECT_EQ(report.crease_splits, 2u);
  EXPECT_EQ(report.parity_splits, 0u);
  // Even, two sides still have no pairing of their own (their cells are split alike, and
  // a triangle was added to each at one end): a few pairs across creases are split.
  EXPECT_GT(report.crease_midpoints, 0u);

  // Open and odd: a roof with a border edge split has 82 triangles on one side and 81 on
  // the other. The side with the longest border edge takes the oddness, whichever it is,
  // and the parity fix splits that edge.
  TriMesh open = roof(9, 0.15);
  split_edge(open, open.positions[0], open.positions[1]);
  ASSERT_EQ(open.n_faces() % 2, 1u);
  converted_apart(open, 15, report, on_ridge);
  EXPECT_EQ(report.crease_splits, 1u);
  EXPECT_EQ(report.crease_midpoints, 0u);
  EXPECT_EQ(report.parity_splits, 1u);
}

TEST(Creases, a_large_part_with_no_pairing_of_its_own_is_not_searched_whole_at_every_move) {
  // The cube's two split edges above, on a finer grid: two sides have no pairing of their
  // own. The searches from their leftovers reach 800 to over 2,000 triangles, and ran again
  // at each of a leftover's 64 moves, though none could succeed: five times the
  // conversion's time on a 1.1M-triangle scan at 30 degrees (bench/RESULTS.md). The moves
  // share one breadth, and Edmonds' algorithm pairs what is left.
  TriMesh t = tri_cube(40);
  split_edge(t, Vec3(1, 1, 0.25), Vec3(1, 1, 0.275));
  split_edge(t, Vec3(0, 1, 0.5), Vec3(0, 1, 0.525));
  ConvertOptions opt;
  opt.crease_angle_deg = 30;
  opt.max_search = 2000;
  ConvertReport report;
  validate(tri_to_quad(t, opt, &report));
  EXPECT_GT(report.crease_midpoints, 0u);
  EXPECT_EQ(report.pairing_rate(), 1.0);
  EXPECT_FALSE(report.refined);
  // Each triangle the greedy pass left is searched from in three rounds at most: within its
  // part, then across creases away from their ends, then across any crease.
  const std::size_t leftovers = report.input_triangles - 2 * report.crease_midpoints - report.paired_greedy;
  EXPECT_GT(leftovers, 0u);
  EXPECT_LE(report.searched, 3 * leftovers * opt.max_search);
}

namespace {

// The quads of ref's mesh converted and simplified to `target` keeping its creases at `angle`
// (none for 0), with every invariant checked after each change.
QuadMesh simplified(const ReferenceSurface& ref, Index target, double angle,
                    SimplifyReport* report = nullptr, const Fitmaps* fitmaps = nullptr) {
  ConvertOptions co;
  co.crease_angle_deg = angle;
  QuadMesh q = tri_to_quad(ref.mesh(), co);
  const Creases creases(ref.mesh(), ref.adjacency(), angle);
  SimplifyOptions opt;
  if (fitmaps) {
    opt.adaptive = true;
    opt.fitmaps = fitmaps;
    opt.refuse_folds = true;
  }
  opt.target_faces = target;
  opt.creases = &creases;
  opt.check_invariants = true;
  const SimplifyReport r = simplify(q, ref, opt);
  if (report) *report = r;
  validate(q);
  return q;
}

// How many of q's edges join two vertices on the unit cube's edges without running along
// one: a quad across a side from edge to edge, which no crease vertex may have.
int shortcuts(const QuadMesh& q) {
  int n = 0;
  for (Index f = 0; f < q.face_capacity(); ++f)
    for (Index k = 0; k < 4 && q.is_face_live(f); ++k) {
      const Vec3 &a = q.position(q.vertex(f, k)), &b = q.position(q.vertex(f, k + 1));
      n += on_cube_sides(a) >= 2 && on_cube_sides(b) >= 2 && !on_cube_edge(a, b);
    }
  return n;
}

// How many of the unit cube's corners are vertices of q.
int cube_corners_kept(const QuadMesh& q) {
  int n = 0;
  for (Index v = 0; v < q.vertex_capacity(); ++v) n += q.is_vertex_live(v) && on_cube_sides(q.position(v)) == 3;
  return n;
}

}  // namespace

TEST(Creases, a_cube_keeps_its_edges_and_corners) {
  const TriMesh t = tri_cube(16);
  const ReferenceSurface ref(t);
  SimplifyReport r;
  const QuadMesh q = simplified(ref, 150, 30, &r);
  EXPECT_LE(q.n_faces(), 150u);
  EXPECT_GT(r.crease_collapses, 0u);
  EXPECT_EQ(cube_corners_kept(q), 8);
  EXPECT_EQ(shortcuts(q), 0);
  const QuadQuality quality = quad_quality(q, &ref);
  EXPECT_EQ(quality.nonconvex_faces + quality.flipped_faces + quality.folded_faces, 0u);
  EXPECT_GT(quality.regular_percent, 60.0);
  // Down to a few quads a side, where a quad could reach from edge to edge.
  for (Index target : {60u, 30u}) {
    const QuadMesh coarse = simplified(ref, target, 30);
    EXPECT_EQ(cube_corners_kept(coarse), 8) << target;
    EXPECT_EQ(shortcuts(coarse), 0) << target;
  }
  // Every vertex on the cube and every quad flat on one side: no distance either way.
  // Without creases the smoothing rounds the edges off.
  const double kept = surface_distance(q, ref, 20000).hausdorff;
  const double rounded = surface_distance(simplified(ref, 150, 0), ref, 20000).hausdorff;
  EXPECT_LT(kept, 1e-6 * ref.bbox_diagonal()) << "rounded off: " << rounded;  // Embree's floats
  EXPECT_GT(rounded, 1e-2 * ref.bbox_diagonal());
}

TEST(Creases, flat_quads_split_at_a_crease_are_taken_out) {
  // The cube whose sides have no pairing of their own (above): the converter's flat quads
  // on either side of a crease midpoint go with the crease coarsening.
  TriMesh t = tri_cube(8);
  split_edge(t, Vec3(1, 1, 0.25), Vec3(1, 1, 0.375));
  split_edge(t, Vec3(0, 1, 0.5), Vec3(0, 1, 0.625));
  const ReferenceSurface ref(t);
  ConvertOptions co;
  co.crease_angle_deg = 30;
  ConvertReport cr;
  const QuadQuality converted = quad_quality(tri_to_quad(ref.mesh(), co, &cr));
  ASSERT_GT(cr.crease_midpoints, 0u);
  EXPECT_GT(converted.nonconvex_faces, 0u);
  const QuadMesh q = simplified(ref, 100, 30);
  EXPECT_LE(q.n_faces(), 100u);
  EXPECT_EQ(cube_corners_kept(q), 8);
  EXPECT_EQ(quad_quality(q, &ref).nonconvex_faces, 0u);
  EXPECT_LT(surface_distance(q, ref, 20000).hausdorff, 1e-6 * ref.bbox_diagonal());
}

TEST(Creases, a_cylinder_keeps_its_rims) {
  const TriMesh t = cad_cylinder(48, 24, 2.0);
  const ReferenceSurface ref(t);
  const QuadMesh q = simplified(ref, 200, 30);
  EXPECT_LE(q.n_faces(), 200u);
  // The rims' vertices stay on M0's rims (polygons of 48 sides); the quads' rims are
  // polygons of fewer sides, so M0's lie off the quads by at most a chord's sagitta.
  auto off_rims = [](const Vec3& p) {
    double d = std::numeric_limits<double>::infinity();
    for (double z : {0.0, 2.0})
      for (int k = 0; k < 48; ++k) {
        const Vec3 a(std::cos(2 * M_PI * k / 48), std::sin(2 * M_PI * k / 48), z);
        const Vec3 b(std::cos(2 * M_PI * (k + 1) / 48), std::sin(2 * M_PI * (k + 1) / 48), z);
        const double x = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
        d = std::min(d, (a + x * (b - a) - p).norm());
      }
    return d;
  };
  int on_rim = 0;
  for (Index v = 0; v < q.vertex_capacity(); ++v)
    if (q.is_vertex_live(v)) on_rim += off_rims(q.position(v)) < 1e-9;
  EXPECT_GE(on_rim, 2 * 8);
  const QuadQuality quality = quad_quality(q, &ref);
  EXPECT_EQ(quality.nonconvex_faces + quality.flipped_faces + quality.folded_faces, 0u);
  const double kept = surface_distance(q, ref, 20000).hausdorff;
  const double rounded = surface_distance(simplified(ref, 200, 0), ref, 20000).hausdorff;
  EXPECT_LT(kept, 0.5 * rounded);
}

TEST(Creases, adaptive_runs_keep_them_too) {
  const TriMesh t = tri_cube(16);
  const ReferenceSurface ref(t);
  const Fitmaps f = compute_fitmaps(t);
  SimplifyReport r;
  const QuadMesh q = simplified(ref, 150, 30, &r, &f);
  EXPECT_LE(q.n_faces(), 150u);
  EXPECT_EQ(cube_corners_kept(q), 8);
  EXPECT_LT(surface_distance(q, ref, 20000).hausdorff, 1e-6 * ref.bbox_diagonal());
}

TEST(Creases, a_sheet_touching_a_crease_at_one_vertex_keeps_its_border) {
  // A square sheet outside the cube, leaning along its edge y = z = 0, touches it at one
  // vertex, the middle of the sheet's border edge x = 0: cleaning splits that vertex into a
  // copy for the cube (on its crease) and one for the sheet (on its border), at one place.
  // Told apart by place alone, the sheet's copy was taken for a crease vertex, slid along
  // the cube's edge after the sheet and left the sheet's border.
  TriMesh t = tri_cube(8);
  TriMesh sheet = tri_grid(4, 4);
  const Vec3 along = Vec3(0, -1, 1).normalized(), in = Vec3(1, -1, -1).normalized();
  for (Vec3& p : sheet.positions) p = Vec3(0.5, 0, 0) + (p.y() - 0.5) * along + p.x() * in;
  for (auto& f : sheet.faces) std::swap(f[1], f[2]);
  append(t, sheet);
  CleanReport cr = clean(t);
  ASSERT_GT(cr.split_nonmanifold_vertices, 0u);
  const ReferenceSurface ref(t);
  for (Index target : {60u, 20u}) {
    SimplifyReport r;
    EXPECT_NO_THROW(simplified(ref, target, 30, &r)) << target;
  }
}

TEST(Creases, coarse_shapes_at_low_angles_keep_every_invariant) {
  // Where most edges are creases (a coarse sphere, torus or spiky ball at 10 to 45
  // degrees): the conversion's flat quads, its shared diagonals and crease doublets
  // everywhere. Every change is checked (simplified()).
  const std::vector<TriMesh> shapes = {tri_sphere(6, 10), tri_torus(8, 12), spiky_sphere(10, 16, 0.6, 0.3),
                                       cad_cylinder(12, 3, 1.0), roof(9, 0.15)};
  int runs = 0;
  for (const TriMesh& t : shapes) {
    const ReferenceSurface ref(t);
    const Index quads = tri_to_quad(ref.mesh()).n_faces();
    for (double angle : {10.0, 20.0, 45.0})
      for (Index target : {quads / 3, quads / 10}) {
        SimplifyReport r;
        ASSERT_NO_THROW(simplified(ref, std::max<Index>(target, 1), angle, &r)) << runs << " angle " << angle;
        ++runs;
      }
  }
  EXPECT_EQ(runs, 30);
}

TEST(Creases, noisy_scans_keep_every_invariant) {
  // Spheres, tori and an open half sphere with noise, at 20 and 30 degrees: many short
  // creases, and the conversion's shared diagonals where their parts pair up on their own,
  // which collapses beside them rename (new_shared_diagonal()): a crease vertex's place
  // kept under the other end's id (the spheres and the torus of seed 6), a doublet
  // collapse keeping a corner's place (the half sphere, seed 0, and the torus of seed 2).
  int runs = 0;
  for (unsigned seed : {0u, 1u, 2u, 5u, 6u}) {
    std::mt19937 rng(seed);
    TriMesh t = seed == 0 ? open_below(tri_sphere(16, 24), 0.0) : seed % 2 ? tri_sphere(16, 24) : tri_torus(16, 24);
    std::normal_distribution<double> noise(0, 0.01 + 0.005 * (seed % 6));
    for (Vec3& p : t.positions) p += Vec3(noise(rng), noise(rng), noise(rng));
    const ReferenceSurface ref(t);
    const Index quads = tri_to_quad(ref.mesh()).n_faces();
    for (double angle : {20.0, 30.0})
      for (Index target : {quads / 4, quads / 10}) {
        SimplifyReport r;
        ASSERT_NO_THROW(simplified(ref, target, angle, &r)) << "seed " << seed << " angle " << angle;
        EXPECT_GT(r.crease_vertices, 0u);
        ++runs;
      }
  }
  EXPECT_EQ(runs, 20);
}

TEST(Creases, a_run_creases_hold_short_of_its_target_says_so) {
  // A coarse sphere at 10 degrees: nearly every edge a crease, nearly every vertex pinned.
  const TriMesh t = tri_sphere(10, 16);
  const ReferenceSurface ref(t);
  SimplifyReport r;
  const QuadMesh q = simplified(ref, 10, 10, &r);
  const QuadQuality quality = quad_quality(q, &ref);
  ASSERT_GT(q.n_faces(), 10u);
  const std::string note = creases_note(r, quality, 10);
  EXPECT_EQ(note.rfind(std::to_string(r.crease_vertices) + " of the result's " + std::to_string(quality.vertices) +
                           " vertices lie on creases",
                       0),
            0u)
      << note;
  const auto notes = result_notes(r, quality, 10);
  EXPECT_NE(std::find(notes.begin(), notes.end(), note), notes.end());
  // Not when the run reached its target, nor with few crease vertices.
  EXPECT_EQ(creases_note(r, quality, q.n_faces()), "");
  SimplifyReport few = r;
  few.crease_vertices = quality.vertices / 2 - 1;
  EXPECT_EQ(creases_note(few, quality, 10), "");
}

TEST(Creases, a_crease_turning_sharply_has_a_corner_there) {
  // The rims of a hexagonal prism at 75 degrees (its sides meet at 60, its caps at 90): each
  // rim is a crease loop that turns by 60 degrees at each vertex with no other crease
  // meeting it, so every rim vertex is a corner and each side of the hexagon a curve. A
  // twelve-sided prism's rims turn by 30 degrees: two closed curves without corners.
  const Creases hexagon = creases_of(cad_cylinder(6, 2, 1.0), 75);
  EXPECT_EQ(hexagon.n_corners(), 12u);
  ASSERT_EQ(hexagon.n_curves(), 12u);
  for (Index i = 0; i < 12; ++i) {
    EXPECT_FALSE(hexagon.closed(i));
    EXPECT_EQ(hexagon.span(i), 1.0);
  }
  const Creases twelve = creases_of(cad_cylinder(12, 2, 1.0), 75);
  EXPECT_EQ(twelve.n_corners(), 0u);
  ASSERT_EQ(twelve.n_curves(), 2u);
  EXPECT_TRUE(twelve.closed(0) && twelve.closed(1));
}

TEST(Creases, short_networks_of_a_scan_are_dropped) {
  // A noisy sphere at 30 degrees: noise makes short creases, loose or meeting a few
  // others at corners. Kept, their vertices would stay at the input's spacing; every
  // network (curves meeting at corners) shorter than four mean edges in all is dropped,
  // and short curves within longer networks stay.
  std::mt19937 rng(3);
  TriMesh t = tri_sphere(24, 36);
  std::normal_distribution<double> noise(0, 0.02);
  for (Vec3& p : t.positions) p += Vec3(noise(rng), noise(rng), noise(rng));
  const Creases c = creases_of(t, 30);
  ASSERT_GT(c.n_curves(), 0u);
  double mean_edge = 0;
  for (const auto& f : t.faces)
    for (int k = 0; k < 3; ++k) mean_edge += (t.positions[f[k]] - t.positions[f[(k + 1) % 3]]).norm();
  mean_edge /= 3.0 * t.n_faces();
  // Networks by a flood over the curves' shared ends.
  std::multimap<Index, Index> at_end;  // end vertex -> curve
  for (Index i = 0; i < c.n_curves(); ++i)
    if (!c.closed(i)) at_end.emplace(c.vertices(i).front(), i), at_end.emplace(c.vertices(i).back(), i);
  auto length_of = [&](Index i) {
    const auto& v = c.vertices(i);
    double length = c.closed(i) ? (t.positions[v.front()] - t.positions[v.back()]).norm() : 0.0;
    for (std::size_t k = 0; k + 1 < v.size(); ++k) length += (t.positions[v[k + 1]] - t.positions[v[k]]).norm();
    return length;
  };
  std::vector<char> seen(c.n_curves(), 0);
  int networks = 0, short_networks = 0, short_curves = 0;
  for (Index i = 0; i < c.n_curves(); ++i) {
    if (seen[i]) continue;
    double length = 0;
    std::vector<Index> todo = {i};
    seen[i] = 1;
    while (!todo.empty()) {
      const Index j = todo.back();
      todo.pop_back();
      length += length_of(j);
      short_curves += length_of(j) < mean_edge;
      if (c.closed(j)) continue;
      for (Index end : {c.vertices(j).front(), c.vertices(j).back()})
        for (auto [it, last] = at_end.equal_range(end); it != last; ++it)
          if (!seen[it->second]) seen[it->second] = 1, todo.push_back(it->second);
    }
    ++networks;
    short_networks += length < 4 * mean_edge;
  }
  EXPECT_GT(networks, 1);
  EXPECT_EQ(short_networks, 0);
  EXPECT_GT(short_curves, 0);  // short curves within longer networks stay
}
