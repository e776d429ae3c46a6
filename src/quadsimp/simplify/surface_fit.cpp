// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/simplify/surface_fit.h"

#include <algorithm>
#include <cmath>

#include "quadsimp/mesh/quad_geometry.h"
#include "quadsimp/metrics/metrics.h"
#include "quadsimp/util/parallel.h"

namespace qs {
namespace {

// Normal equations of one vertex: its step along its normal is num / den.
struct Normal1 {
  double num = 0, den = 0;
  void add(double weight, double corner_weight, double residual) {
    num += weight * corner_weight * residual;
    den += weight * corner_weight * corner_weight;
  }
};

// Points on a triangle mesh: the centroids of a k x k split of each triangle, k chosen
// so that each sample covers about `area_per_sample`.
struct TriangleSamples {
  std::vector<Vec3> points;
  std::vector<double> weight;                // area each one stands for
  std::vector<std::array<double, 3>> bary;  // weights of the triangle's corners
  std::vector<Index> triangle;

  void build(const TriMesh& t, double area_per_sample) {
    points.clear(), weight.clear(), bary.clear(), triangle.clear();
    for (Index f = 0; f < t.n_faces(); ++f) {
      const Vec3 c[3] = {t.positions[t.faces[f][0]], t.positions[t.faces[f][1]], t.positions[t.faces[f][2]]};
      const double a = triangle_area(c[0], c[1], c[2]);
      const int k = std::clamp(int(std::ceil(std::sqrt(a / area_per_sample))), 1, 16);
      for (int i = 0; i < k; ++i)
        for (int j = 0; i + j < k; ++j)
          for (int down = 0; down < (i + j + 1 < k ? 2 : 1); ++down) {
            const double u = (i + (down ? 2.0 : 1.0) / 3) / k, v = (j + (down ? 2.0 : 1.0) / 3) / k;
            bary.push_back({1 - u - v, u, v});
            points.push_back((1 - u - v) * c[0] + u * c[1] + v * c[2]);
            weight.push_back(a / (k * k));
            triangle.push_back(f);
          }
    }
  }
};

}  // namespace

SurfaceFitReport fit_to_surface(QuadMesh& m, const ReferenceSurface& ref, const SurfaceFitOptions& opt) {
  SurfaceFitReport rep;
  std::vector<Index> live;  // compact index (triangulate()'s) -> vertex
  for (Index v = 0; v < m.vertex_capacity(); ++v)
    if (m.is_vertex_live(v)) live.push_back(v);
  const Index n = Index(live.size());
  if (n == 0) return rep;

  const TriMesh& in = ref.mesh();
  std::vector<double> in_weight(in.n_vertices(), 0.0);  // a third of the area around each
  double in_area = 0;
  for (const auto& t : in.faces) {
    const double a = triangle_area(in.positions[t[0]], in.positions[t[1]], in.positions[t[2]]);
    for (Index c : t) in_weight[c] += a / 3;
    in_area += a;
  }
  // Output samples at about the input's vertex density, so that both sides weigh alike.
  const double area_per_sample = in_area / std::max<Index>(in.n_vertices(), 1);

  // A step may not turn a face against its normal at the start, against the input
  // under its centre (the check the quality report makes), make a convex face
  // non-convex, or bend a face past 90 degrees (or further, if it started so); faces
  // that start out that way are not held to the first three.
  struct FaceStart {
    Vec3 normal = Vec3::Zero();
    bool convex = false, agrees = false;
    double fold_cos = 1;
  };
  std::vector<FaceStart> face_start(m.face_capacity());
  std::vector<Index> faces;
  for (Index f = 0; f < m.face_capacity(); ++f)
    if (m.is_face_live(f)) faces.push_back(f);
  auto face_ok = [&](Index f, const FaceStart& s) {
    const auto c = m.face_vertices(f);
    const auto p = m.positions_of(c);
    const Vec3 nf = quad_normal(p[0], p[1], p[2], p[3]);
    if (!keeps_orientation(nf, s.normal) || (s.convex && !quad_is_convex(p[0], p[1], p[2], p[3], nf))) return false;
    if (quad_folds_further(p[0], p[1], p[2], p[3], [&] { return std::min(s.fold_cos, 0.0); })) return false;
    if (!s.agrees) return true;
    const SurfacePoint foot = ref.closest(0.25 * (p[0] + p[1] + p[2] + p[3]));
    return !foot.found() || ref.normal_at(foot).dot(nf) > 0;
  };
  parallel_for_as_here(std::size_t(0), faces.size(), [&](std::size_t i) {
    const Index f = faces[i];
    const auto c = m.face_vertices(f);
    FaceStart& s = face_start[f];
    s.normal = m.face_area_normal(f);
    const auto p = m.positions_of(c);
    s.convex = quad_is_convex(p[0], p[1], p[2], p[3]);
    s.fold_cos = quad_fold_cos(m.positions(), c);
    s.agrees = true;
    s.agrees = face_ok(f, s);
  });
  std::vector<Vec3> start(n), normal(n);
  for (Index i = 0; i < n; ++i) start[i] = m.position(live[i]);
  std::vector<Index> compact(m.vertex_capacity(), kNone);
  for (Index i = 0; i < n; ++i) compact[live[i]] = i;

  std::vector<Normal1> eq(n);
  std::vector<SurfacePoint> hits;
  TriangleSamples samples;
  std::vector<Vec3> feet, from(n), step(n);
  std::vector<double> scale(n);
  std::vector<Index> check, again;
  std::vector<char> bad;
  for (int it = 0; it < opt.iterations; ++it) {
    const ReferenceSurface out_surface(triangulate(m));
    const TriMesh& out = out_surface.mesh();
    for (Index i = 0; i < n; ++i) normal[i] = m.vertex_area_normal(live[i]).normalized();
    std::fill(eq.begin(), eq.end(), Normal1{});

    // Reference -> quads: every input vertex pulls the three corners of its closest
    // output triangle by their barycentric weights.
    hits.resize(in.n_vertices());
    parallel_for_as_here(Index(0), in.n_vertices(), [&](Index i) { hits[i] = out_surface.closest(in.positions[i]); });
    for (Index i = 0; i < in.n_vertices(); ++i) {  // serial: the same sums whatever the threads
      const SurfacePoint& s = hits[i];
      if (!s.found()) continue;
      const auto& t = out.faces[s.face];
      const double w[3] = {1 - s.u - s.v, s.u, s.v};
      for (int k = 0; k < 3; ++k) eq[t[k]].add(in_weight[i], w[k], (in.positions[i] - s.point).dot(normal[t[k]]));
    }

    // Quads -> reference, from regular samples of the output triangles.
    samples.build(out, area_per_sample);
    feet.resize(samples.points.size());
    parallel_for_as_here(std::size_t(0), feet.size(),
                         [&](std::size_t i) { feet[i] = ref.closest(samples.points[i]).point; });
    for (std::size_t i = 0; i < feet.size(); ++i) {
      const auto& t = out.faces[samples.triangle[i]];
      for (int k = 0; k < 3; ++k)
        eq[t[k]].add(samples.weight[i], samples.bary[i][k], (feet[i] - samples.points[i]).dot(normal[t[k]]));
    }

    // All vertices take their damped steps at once. The faces a step spoils have
    // their corners' steps halved, twice, then dropped, until every face passes.
    std::fill(scale.begin(), scale.end(), 1.0);
    for (Index i = 0; i < n; ++i) {
      from[i] = m.position(live[i]);
      double edges = 0;
      int count = 0;
      m.for_each_outgoing(live[i], [&](Index h) {
        edges += (m.position(m.to(h)) - from[i]).norm();
        ++count;
      });
      const double limit = opt.max_step * edges / std::max(count, 1);
      const bool fixed = opt.keep_border && m.is_border_vertex(live[i]);
      const double t = eq[i].den > 0 && !fixed ? std::clamp(opt.damping * eq[i].num / eq[i].den, -limit, limit) : 0.0;
      step[i] = t * normal[i];
    }
    check = faces;
    while (!check.empty()) {
      for (Index i = 0; i < n; ++i) m.position(live[i]) = from[i] + scale[i] * step[i];
      bad.assign(check.size(), 0);
      parallel_for_as_here(std::size_t(0), check.size(),
                           [&](std::size_t j) { bad[j] = !face_ok(check[j], face_start[check[j]]); });
      again.clear();
      for (std::size_t j = 0; j < check.size(); ++j) {
        if (!bad[j]) continue;
        for (Index v : m.face_vertices(check[j])) {
          double& s = scale[compact[v]];
          if (s == 0) continue;
          if (s == 1.0) ++rep.shortened;
          s = s > 0.3 ? 0.5 * s : 0.0;
          m.for_each_outgoing(v, [&](Index h) { again.push_back(QuadMesh::face(h)); });
        }
      }
      std::sort(again.begin(), again.end());
      again.erase(std::unique(again.begin(), again.end()), again.end());
      check.swap(again);
    }
  }
  for (Index i = 0; i < n; ++i) rep.moved_max = std::max(rep.moved_max, (m.position(live[i]) - start[i]).norm());
  rep.moved_max /= ref.bbox_diagonal();
  return rep;
}

}  // namespace qs
