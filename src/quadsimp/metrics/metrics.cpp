// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/metrics/metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>

#include "quadsimp/mesh/mesh_file.h"
#include "quadsimp/mesh/quad_geometry.h"
#include "quadsimp/simplify/simplify.h"
#include "quadsimp/util/parallel.h"

namespace qs {
namespace {

// Counter-based random numbers: sample i is the same whatever thread draws it.
double uniform01(std::uint64_t i, std::uint64_t stream) {
  std::uint64_t z = i * 0x9E3779B97F4A7C15ull + stream * 0xD1B54A32D192ED03ull + 0x632BE59BD9B4E019ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return double(z >> 11) * (1.0 / 9007199254740992.0);
}

// `n` area-weighted points on a triangle mesh, then its vertices.
std::vector<Vec3> sample_surface(const TriMesh& t, Index n, std::uint64_t stream) {
  std::vector<double> cdf(t.n_faces());
  double total = 0;
  for (Index f = 0; f < t.n_faces(); ++f) {
    const auto& v = t.faces[f];
    total += triangle_area(t.positions[v[0]], t.positions[v[1]], t.positions[v[2]]);
    cdf[f] = total;
  }
  std::vector<Vec3> s(n + t.n_vertices());
  parallel_for_as_here(Index(0), n, [&](Index i) {
    const double pick = uniform01(i, 3 * stream) * total;
    const Index f = Index(std::min<std::size_t>(std::lower_bound(cdf.begin(), cdf.end(), pick) - cdf.begin(),
                                                cdf.size() - 1));
    double r1 = std::sqrt(uniform01(i, 3 * stream + 1)), r2 = uniform01(i, 3 * stream + 2);
    const auto& v = t.faces[f];
    s[i] = (1 - r1) * t.positions[v[0]] + r1 * (1 - r2) * t.positions[v[1]] + r1 * r2 * t.positions[v[2]];
  });
  std::copy(t.positions.begin(), t.positions.end(), s.begin() + n);
  return s;
}

struct OneSided {
  double max = 0, sum = 0, sum2 = 0;
  std::size_t n = 0;
};

OneSided distances(const std::vector<Vec3>& points, const ReferenceSurface& target) {
  std::vector<double> d(points.size());
  parallel_for_as_here(std::size_t(0), points.size(),
                       [&](std::size_t i) { d[i] = target.closest(points[i]).distance; });
  OneSided r;
  for (double x : d) {  // serial: the same sum whatever the thread count
    r.max = std::max(r.max, x);
    r.sum += x;
    r.sum2 += x * x;
  }
  r.n = d.size();
  return r;
}

}  // namespace

TriMesh triangulate(const QuadMesh& m) {
  TriMesh t;
  const std::vector<Index> id = m.live_vertex_ids();
  for (Index v = 0; v < m.vertex_capacity(); ++v)
    if (m.is_vertex_live(v)) t.positions.push_back(m.position(v));
  for (Index f = 0; f < m.face_capacity(); ++f) {
    if (!m.is_face_live(f)) continue;
    auto q = m.face_vertices(f);
    for (Index& v : q) v = id[v];
    split_quad(t.positions, q, t.faces);
  }
  return t;
}

QuadQuality quad_quality(const QuadMesh& m, const ReferenceSurface* ref, std::vector<Index>* flawed) {
  QuadQuality q;
  q.faces = m.n_faces();
  q.vertices = m.n_vertices();
  Index regular = 0, four = 0;
  for (Index v = 0; v < m.vertex_capacity(); ++v) {
    if (!m.is_vertex_live(v)) continue;
    const int val = m.valence(v);
    const bool border = m.is_border_vertex(v);
    q.max_valence = std::max(q.max_valence, val);
    if (!border) q.max_valence_interior = std::max(q.max_valence_interior, val);
    regular += val == (border ? 3 : 4);
    four += val == 4;
    q.border_vertices += border;
  }
  // Each border vertex has one outgoing border half-edge, out(v): following them from an
  // unvisited one goes round its loop.
  std::vector<char> on_loop(m.vertex_capacity(), 0);
  for (Index v = 0; v < m.vertex_capacity(); ++v) {
    if (!m.is_vertex_live(v) || !m.is_border_vertex(v) || on_loop[v]) continue;
    ++q.border_loops;
    for (Index u = v; !on_loop[u]; u = m.next_on_border(u)) on_loop[u] = 1;
  }
  if (q.vertices) {
    q.regular_percent = 100.0 * regular / q.vertices;
    q.valence4_percent = 100.0 * four / q.vertices;
  }
  q.mu = mean_edge_length(m);
  q.homeometry_min = q.edge_ratio_min = std::numeric_limits<double>::infinity();
  for (Index f = 0; f < m.face_capacity(); ++f) {
    if (!m.is_face_live(f)) continue;
    const auto c = m.face_vertices(f);
    const auto p = m.positions_of(c);
    for (int k = 0; k < 4; ++k) {
      const double e = (p[k] - p[(k + 1) % 4]).norm() / q.mu;
      q.edge_ratio_min = std::min(q.edge_ratio_min, e);
      q.edge_ratio_max = std::max(q.edge_ratio_max, e);
    }
    for (int k = 0; k < 2; ++k) {
      const double d = (p[k] - p[k + 2]).norm() / (kSqrt2 * q.mu);
      q.homeometry_min = std::min(q.homeometry_min, d);
      q.homeometry_max = std::max(q.homeometry_max, d);
    }
    const bool nonconvex = !quad_is_convex(p[0], p[1], p[2], p[3]), folded = quad_folds(p[0], p[1], p[2], p[3]);
    bool flipped = false;
    q.nonconvex_faces += nonconvex;
    q.folded_faces += folded;
    const Index partner = two_quad_piece_partner(m, f);
    q.two_quad_pieces += partner != kNone && partner > f;  // counted at the lower of the two
    if (ref) {
      // Flipped: the surface nearest the centre faces against the quad, and so does the
      // surface nearest two of its corners or more. The centre alone misjudged quads
      // whose chord passes under a part thinner than their bulge: pyvista's airplane had
      // 3 "flipped" quads on its wings, each with every corner on the side facing it
      // (bench/RESULTS.md, "Flipped quads over thin parts").
      // Where the nearest point is inside a triangle, away from its edges, and the quad lies
      // within 30 degrees of that triangle's plane, the triangle's own normal says which way
      // the input faces there, not the interpolated one: over a coarse CAD mesh's long
      // triangles the vertex normals mix a sharp rim's two sides, and a cone of 33 segments
      // whose base is a fan from one rim vertex, remeshed and simplified, had 29 "flipped"
      // quads against its file (bench/RESULTS.md, "Flipped quads over coarse CAD
      // triangles"). Steeper quads, and points on an edge, whose triangles disagree, are left
      // to the interpolated normal.
      const Vec3 n = quad_normal(p[0], p[1], p[2], p[3]);
      const double cos30 = 0.5 * std::sqrt(3.0) * n.norm();  // times |n|, as `along` is
      auto against = [&](const SurfacePoint& s) {
        if (!s.found()) return false;
        const double along = ref->face_normal(s.face).dot(n);
        if (std::abs(along) > cos30 && std::min({s.u, s.v, 1 - s.u - s.v}) > 1e-6) return along < 0;
        return ref->normal_at(s).dot(n) < 0;
      };
      if (against(ref->closest_to_quad_centre(p.data()))) {
        int corners = 0;
        for (const Vec3& x : p) corners += against(ref->closest(x));
        flipped = corners >= 2;
        q.flipped_faces += flipped;
      }
    }
    if (flawed && (nonconvex || folded || flipped)) flawed->push_back(f);
  }
  q.homeometry_min = std::min(q.homeometry_min, q.edge_ratio_min);
  q.homeometry_max = std::max(q.homeometry_max, q.edge_ratio_max);
  if (!q.faces) q.homeometry_min = q.edge_ratio_min = 0;
  return q;
}

SurfaceDistance surface_distance(const QuadMesh& m, const ReferenceSurface& ref, Index samples) {
  SurfaceDistance r;
  r.samples = samples;
  const TriMesh out = triangulate(m);
  const ReferenceSurface out_surface(out);
  const std::vector<Vec3> on_out = sample_surface(out, samples, 1);
  const std::vector<Vec3> on_ref = sample_surface(ref.mesh(), samples, 2);
  const OneSided to = distances(on_out, ref), from = distances(on_ref, out_surface);
  const double diag = ref.bbox_diagonal();
  r.max_to_ref = to.max / diag;
  r.max_from_ref = from.max / diag;
  r.hausdorff = std::max(r.max_to_ref, r.max_from_ref);
  r.mean_to_ref = to.sum / to.n / diag;
  r.rms_to_ref = std::sqrt(to.sum2 / to.n) / diag;
  r.rms_from_ref = std::sqrt(from.sum2 / from.n) / diag;
  r.rms = std::sqrt((to.sum2 + from.sum2) / double(to.n + from.n)) / diag;

  // Projectability: from a sample on the output, along the output's normal, the
  // nearest hit on the reference must face the same way.
  std::vector<char> ok(samples, 0);
  const double reach = kProjectabilityReach * diag;
  parallel_for_as_here(Index(0), samples, [&](Index i) {
    const SurfacePoint s = out_surface.closest(on_out[i]);
    if (!s.found()) return;
    const Vec3 n = out_surface.normal_at(s);
    const SurfacePoint hit = ref.ray_project(on_out[i], n, reach);
    ok[i] = hit.found();
  });
  std::size_t good = 0;
  for (char c : ok) good += c;
  r.projectability = samples ? double(good) / samples : 1.0;
  return r;
}

std::string to_json(const QuadQuality& q, const SurfaceDistance* d, const std::vector<Index>* flawed) {
  char buf[2048];
  int n =
      std::snprintf(buf, sizeof buf,
                    "{\"faces\": %u, \"vertices\": %u, \"pure_quad\": true, \"max_valence\": %d, "
                    "\"max_valence_interior\": %d, \"regular_percent\": %.3f, \"valence4_percent\": %.3f, "
                    "\"homeometry_min\": %.4f, \"homeometry_max\": %.4f, \"edge_ratio_min\": %.4f, "
                    "\"edge_ratio_max\": %.4f, \"mean_edge\": %.6g, \"nonconvex_faces\": %u, \"flipped_faces\": %u, "
                    "\"folded_faces\": %u, \"two_quad_pieces\": %u, \"border_vertices\": %u, \"border_loops\": %u",
                    q.faces, q.vertices, q.max_valence, q.max_valence_interior, q.regular_percent, q.valence4_percent,
                    q.homeometry_min, q.homeometry_max, q.edge_ratio_min, q.edge_ratio_max, q.mu, q.nonconvex_faces,
                    q.flipped_faces, q.folded_faces, q.two_quad_pieces, q.border_vertices, q.border_loops);
  std::string s(buf, std::size_t(n));
  if (d) {
    n = std::snprintf(buf, sizeof buf,
                      ", \"hausdorff_e3\": %.4f, \"rms_e3\": %.4f, \"mean_to_ref_e3\": %.4f, \"max_to_ref_e3\": %.4f, "
                      "\"max_from_ref_e3\": %.4f, \"rms_to_ref_e3\": %.4f, \"rms_from_ref_e3\": %.4f, "
                      "\"projectability\": %.5f, \"samples\": %u",
                      1e3 * d->hausdorff, 1e3 * d->rms, 1e3 * d->mean_to_ref, 1e3 * d->max_to_ref,
                      1e3 * d->max_from_ref, 1e3 * d->rms_to_ref, 1e3 * d->rms_from_ref, d->projectability, d->samples);
    s.append(buf, std::size_t(n));
  }
  if (flawed) {
    s += ", \"flawed_faces\": [";
    for (std::size_t i = 0; i < flawed->size(); ++i) s += (i ? ", " : "") + std::to_string((*flawed)[i]);
    s += "]";
  }
  return s + "}";
}

}  // namespace qs
