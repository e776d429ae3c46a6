// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/reference/reference_surface.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace qs {

struct ReferenceSurface::Bvh {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::string error;
  ~Bvh() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

namespace {

// Embree reports errors through a C callback: remember the first one and throw it
// from our own code once the call returns (never unwind through Embree).
void embree_error(void* user, RTCError code, const char* str) {
  auto* first = static_cast<std::string*>(user);
  if (first->empty()) first->assign("Embree error " + std::to_string(int(code)) + ": " + (str ? str : ""));
}

struct ClosestQuery {
  const ReferenceSurface* ref;
  Vec3 origin;  // what Embree's coordinates are relative to
  double unit;  // and in what unit
  Vec3 normal;  // zero: any orientation
  SurfacePoint* best;
};

bool closest_callback(RTCPointQueryFunctionArguments* args) {
  auto* q = static_cast<ClosestQuery*>(args->userPtr);
  const Index f = args->primID;
  // Exactly zero: Eigen's isZero() is fuzzy by an absolute 1e-12, and a quad's area
  // normal is that short on a scan 1e-4 units across (bunny.ply in units 2^15 times smaller).
  if (q->normal != Vec3::Zero() && q->ref->face_normal(f).dot(q->normal) <= 0) return false;
  const auto& t = q->ref->mesh().faces[f];
  const auto& P = q->ref->mesh().positions;
  const Vec3 p = Vec3(args->query->x, args->query->y, args->query->z) / q->unit + q->origin;
  double u, v;
  const Vec3 c = closest_on_triangle(p, P[t[0]], P[t[1]], P[t[2]], u, v);
  const double d = (c - p).norm();
  if (d * q->unit > args->query->radius || (q->best->found() && d >= q->best->distance)) return false;
  *q->best = SurfacePoint{f, u, v, c, d};
  args->query->radius = float(d * q->unit);
  return true;
}

// Scans fold the odd patch of triangles over onto the surface (folded_patches()); clean()
// lays most flat, and marks here the rest: the patch and every triangle touching it,
// where the layers meet and the normals point both ways.
std::vector<char> folded_flaps(const TriMesh& m, const std::vector<std::array<Index, 3>>& adjacency,
                               const std::vector<Vec3>& normals) {
  std::vector<char> flap(normals.size(), 0);
  std::vector<Index> patch;
  // Under kLaidFlatShare, which clean() tries: marked, the top of a leaf on a stalk (1e-2
  // of its piece, tried and put back) turned 12 of 2,000 quads over it, and on grids
  // folded over 1e-3 to 1e-2 of their area marking changed nothing (clean() laid them
  // flat).
  constexpr double kLargestShare = 1e-3;
  if (folded_patches(m, adjacency, normals, patch, kLargestShare, kFoldedBackCos) == 0) return flap;
  std::vector<char> at_flap(m.n_vertices(), 0);
  for (Index f = 0; f < m.n_faces(); ++f)
    if (patch[f] != kNone)
      for (Index v : m.faces[f]) at_flap[v] = 1;
  for (Index f = 0; f < m.n_faces(); ++f)
    for (Index v : m.faces[f]) flap[f] = flap[f] || at_flap[v];
  return flap;
}

}  // namespace

Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, double& u, double& v) {
  // Voronoi-region walk (Ericson, Real-Time Collision Detection, 5.1.5).
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) { u = v = 0; return a; }
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) { u = 1; v = 0; return b; }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double t = d1 / (d1 - d3);
    u = t; v = 0;
    return a + t * ab;
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) { u = 0; v = 1; return c; }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double t = d2 / (d2 - d6);
    u = 0; v = t;
    return a + t * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    u = 1 - t; v = t;
    return b + t * (c - b);
  }
  const double denom = 1 / (va + vb + vc);
  u = vb * denom;
  v = vc * denom;
  return a + ab * u + ac * v;
}

ReferenceSurface::ReferenceSurface(TriMesh mesh, EmbreeKernels kernels)
    : mesh_(std::move(mesh)), bvh_(std::make_unique<Bvh>()) {
  const auto& P = mesh_.positions;
  diagonal_ = qs::bbox_diagonal(P);
  normals_.resize(mesh_.n_faces());
  for (Index f = 0; f < mesh_.n_faces(); ++f) normals_[f] = mesh_.area_normal(mesh_.faces[f]).normalized();
  mean_edge_ = qs::mean_edge_length(mesh_);
  area_ = surface_area(mesh_);
  vertex_normals_ = vertex_area_normals(mesh_);
  for (Vec3& n : vertex_normals_) n.normalize();
  adjacency_ = triangle_adjacency(mesh_);
  flap_ = folded_flaps(mesh_, adjacency_, normals_);
  border_out_.assign(mesh_.n_vertices(), kNone);
  border_in_.assign(mesh_.n_vertices(), kNone);
  for (Index f = 0; f < mesh_.n_faces(); ++f)
    for (Index k = 0; k < 3; ++k)
      if (adjacency_[f][k] == kNone) {
        border_out_[mesh_.faces[f][k]] = 3 * f + k;
        border_in_[mesh_.faces[f][(k + 1) % 3]] = 3 * f + k;
        const Vec3& a = mesh_.positions[mesh_.faces[f][k]];
        border_segments_.emplace_back(a, mesh_.positions[mesh_.faces[f][(k + 1) % 3]] - a);
      }

  bvh_->device = rtcNewDevice(kernels == EmbreeKernels::Sse2 ? "threads=0,isa=sse2" : "threads=0");
  if (!bvh_->device) throw std::runtime_error("Embree: cannot create a device");
  rtcSetDeviceErrorFunction(bvh_->device, embree_error, &bvh_->error);
  bvh_->scene = rtcNewScene(bvh_->device);
  rtcSetSceneFlags(bvh_->scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(bvh_->scene, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry geom = rtcNewGeometry(bvh_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  // Embree owns these buffers (and pads them as it needs).
  auto* xyz = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), P.size()));
  // Embree works in float: shifted to working_origin(), and queries alike. And scaled by
  // a power of two (exactly) to a diagonal between 1 and 2, so that its arithmetic is the
  // same at every unit of length: its answers changed on bunny.ply in units 2^30 times
  // smaller (1e-10 across), and results with them.
  origin_ = working_origin(P);
  unit_ = diagonal_ > 0 ? std::ldexp(1.0, -std::ilogb(diagonal_)) : 1.0;
  for (std::size_t i = 0; i < P.size(); ++i)
    Eigen::Vector3f::Map(xyz + 3 * i) = to_embree(P[i]);
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                             3 * sizeof(unsigned), mesh_.faces.size()));
  for (std::size_t f = 0; f < mesh_.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) idx[3 * f + k] = mesh_.faces[f][k];
  rtcCommitGeometry(geom);
  rtcAttachGeometryByID(bvh_->scene, geom, 0);
  rtcReleaseGeometry(geom);
  rtcCommitScene(bvh_->scene);
  if (!bvh_->error.empty()) throw std::runtime_error(bvh_->error);
}

ReferenceSurface::~ReferenceSurface() = default;

SurfacePoint ReferenceSurface::ray_project(const Vec3& p, const Vec3& dir, double max_dist) const {
  SurfacePoint best;
  const double len = dir.norm();
  if (!(len > 0) || !(max_dist > 0)) return best;
  const Vec3 d = dir / len;
  // Both directions; along each, skip hits whose triangle faces the other way.
  for (double sign : {1.0, -1.0}) {
    float tnear = 0.f;
    for (int tries = 0; tries < 8; ++tries) {
      RTCIntersectContext ctx;
      rtcInitIntersectContext(&ctx);
      RTCRayHit rh;
      const Eigen::Vector3f org = to_embree(p);
      rh.ray.org_x = org.x(), rh.ray.org_y = org.y(), rh.ray.org_z = org.z();
      rh.ray.dir_x = float(sign * d.x());
      rh.ray.dir_y = float(sign * d.y());
      rh.ray.dir_z = float(sign * d.z());
      rh.ray.tnear = tnear;
      rh.ray.tfar = float(std::min(max_dist, best.distance) * unit_);
      rh.ray.mask = ~0u;
      rh.ray.flags = 0;
      rh.ray.time = 0.f;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(bvh_->scene, &ctx, &rh);
      if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) break;
      const Index f = rh.hit.primID;
      if (normals_[f].dot(d) > 0) {
        const auto& t = mesh_.faces[f];
        const auto& P = mesh_.positions;
        const double u = rh.hit.u, v = rh.hit.v;
        const Vec3 q = (1 - u - v) * P[t[0]] + u * P[t[1]] + v * P[t[2]];
        best = SurfacePoint{f, u, v, q, double(rh.ray.tfar) / unit_};
        break;
      }
      tnear = std::nextafter(rh.ray.tfar, std::numeric_limits<float>::infinity());
    }
  }
  return best;
}

SurfacePoint ReferenceSurface::closest(const Vec3& p, double max_dist, const Vec3& normal) const {
  SurfacePoint best;
  RTCPointQuery q;
  const Eigen::Vector3f at = to_embree(p);
  q.x = at.x(), q.y = at.y(), q.z = at.z();
  q.time = 0.f;
  q.radius = std::isfinite(max_dist) ? float(max_dist * unit_) : std::numeric_limits<float>::infinity();
  RTCPointQueryContext ctx;
  rtcInitPointQueryContext(&ctx);
  ClosestQuery data{this, origin_, unit_, normal, &best};
  rtcPointQuery(bvh_->scene, &q, &ctx, closest_callback, &data);
  if (best.found()) {
    // Exact distance from the double-precision input point.
    best.distance = (best.point - p).norm();
  }
  return best;
}

SurfacePoint ReferenceSurface::closest_within(const Vec3& p, double hint) const {
  // The slack covers Embree's float query point, rounded by up to about 1e-7 of the
  // diagonal, and float radii.
  const SurfacePoint s = closest(p, hint * (1 + 1e-6) + 1e-5 * diagonal_);
  return s.found() ? s : closest(p);
}

SurfacePoint ReferenceSurface::closest_to_quad_centre(const Vec3* q) const {
  const Vec3 centre = 0.25 * (q[0] + q[1] + q[2] + q[3]);
  double corner2 = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 4; ++i) corner2 = std::min(corner2, (q[i] - centre).squaredNorm());
  return closest_within(centre, std::sqrt(corner2));
}

SurfacePoint ReferenceSurface::project(const Vec3& p, const Vec3& dir, double max_dist) const {
  SurfacePoint s = ray_project(p, dir, max_dist);
  if (s.found()) return s;
  s = closest(p, max_dist, dir);
  if (s.found()) return s;
  return closest(p);
}

SurfacePoint ReferenceSurface::project_near(Index start, const Vec3& p, const Vec3& dir, double max_dist) const {
  constexpr int kMaxSteps = 32;
  const double len = dir.norm();
  if (start < mesh_.n_faces() && len > 0) {
    const Vec3 d = dir / len;
    const auto& P = mesh_.positions;
    Index t = start;
    for (int step = 0; step < kMaxSteps && t != kNone; ++step) {
      const Vec3& n = normals_[t];
      const double cos = n.dot(d);
      if (cos < 1e-3) break;  // disagreeing or grazing: let the BVH decide
      const auto& f = mesh_.faces[t];
      const Vec3 &a = P[f[0]], &b = P[f[1]], &c = P[f[2]];
      const double s = (a - p).dot(n) / cos;
      const Vec3 y = p + s * d;
      const double area2 = (b - a).cross(c - a).dot(n);
      const double w[3] = {(b - y).cross(c - y).dot(n) / area2, (c - y).cross(a - y).dot(n) / area2,
                           (a - y).cross(b - y).dot(n) / area2};
      const int worst = int(std::min_element(w, w + 3) - w);
      if (w[worst] >= -1e-9) {
        if (std::abs(s) > max_dist) break;
        return SurfacePoint{t, w[1], w[2], y, std::abs(s)};
      }
      // Leave across the edge opposite the corner with the most negative weight;
      // edge k runs from corner k to corner k+1.
      t = adjacency_[t][(worst + 1) % 3];
    }
  }
  return project(p, dir, max_dist);
}

SurfacePoint ReferenceSurface::closest_on_border(Index start, const Vec3& p, double reach, const BorderArc& arc) const {
  SurfacePoint best;
  if (start >= mesh_.n_faces()) return best;
  const auto& P = mesh_.positions;
  auto corner = [&](Index e, Index i) { return mesh_.faces[e / 3][(e % 3 + i) % 3]; };
  // Border edge e's points by their parameter s, 0 at its start and 1 at its end:
  // nearest() gives the one nearest x, point_at() the one at s, and where_on() where x
  // lies on e (-1 off it).
  auto nearest = [&](Index e, const Vec3& x) {
    const Vec3& a = P[corner(e, 0)];
    const Vec3 ab = P[corner(e, 1)] - a;
    const double len2 = ab.squaredNorm();
    return len2 > 0 ? std::clamp((x - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  };
  auto point_at = [&](Index e, double s) { return Vec3(P[corner(e, 0)] + s * (P[corner(e, 1)] - P[corner(e, 0)])); };
  // Points placed on the border lie off it by Embree's rounding (closest() searches from a
  // float copy of the point: up to about 1e-7 of the diagonal). Matched within 1e-9 input
  // edges, such an arc.from started the walk on another edge of its triangle, and such
  // ends bounded nothing: the walk slid past them.
  const double on_edge = 1e-6 * diagonal_;
  auto distance_to = [&](Index e, const Vec3& x) { return (point_at(e, nearest(e, x)) - x).norm(); };
  auto where_on = [&](Index e, const Vec3& x) {
    const double s = nearest(e, x);
    return (point_at(e, s) - x).norm() <= on_edge ? s : -1.0;
  };
  // The walk starts at the border edge at a corner of `start` nearest arc.from; of two
  // as near (arc.from at their shared corner), the later one, as it always has: the
  // other starts the reach's count elsewhere.
  Index first = kNone;
  double first_distance = std::numeric_limits<double>::infinity();
  for (Index v : mesh_.faces[start])
    for (Index e : {border_out_[v], border_in_[v]}) {
      if (e == kNone) continue;
      const double d = distance_to(e, arc.from);
      if (d <= first_distance) first = e, first_distance = d;
    }
  if (first == kNone) return best;
  // The closest point of border edge e between lo and hi (as where_on() measures);
  // returns the edge's length.
  auto visit = [&](Index e, double lo, double hi) {
    const double s = std::clamp(nearest(e, p), lo, std::max(lo, hi));
    const Vec3 x = point_at(e, s);
    const double d = (x - p).norm();
    if (!best.found() || d < best.distance) {
      double w[3] = {0, 0, 0};
      w[e % 3] = 1 - s;
      w[(e % 3 + 1) % 3] = s;
      best = SurfacePoint{e / 3, w[1], w[2], x, d};
    }
    return (P[corner(e, 1)] - P[corner(e, 0)]).norm();
  };
  // Forward from `first` (each edge's end starts the next) up to arc.ahead, then
  // backward (each edge's start ends the previous) up to arc.behind; each also stops at
  // `reach`, after kMaxEdges edges (a guard) or where a closed loop comes back to `first`.
  constexpr int kMaxEdges = 256;
  const double ahead = where_on(first, arc.ahead), behind = where_on(first, arc.behind);
  const double first_length = visit(first, std::max(0.0, behind), ahead >= 0 ? ahead : 1.0);
  for (const bool forward : {true, false}) {
    if ((forward ? ahead : behind) >= 0) continue;  // the arc ends on `first`
    auto step = [&](Index e) { return forward ? border_out_[corner(e, 1)] : border_in_[corner(e, 0)]; };
    double walked = first_length;
    int steps = 0;
    for (Index e = step(first); e != kNone && e != first && walked < reach && steps < kMaxEdges; e = step(e), ++steps) {
      const double end = where_on(e, forward ? arc.ahead : arc.behind);
      walked += forward ? visit(e, 0.0, end >= 0 ? end : 1.0) : visit(e, std::max(0.0, end), 1.0);
      if (end >= 0) break;
    }
  }
  return best;
}

double ReferenceSurface::border_distance(const Vec3& p) const {
  double d = std::numeric_limits<double>::infinity();
  for (const auto& [a, ab] : border_segments_) {
    const double len2 = ab.squaredNorm();
    const double s = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    d = std::min(d, (a + s * ab - p).norm());
  }
  return d;
}

double ReferenceSurface::interpolate(const std::vector<float>& field, const SurfacePoint& s) const {
  const auto& t = mesh_.faces[s.face];
  return (1 - s.u - s.v) * field[t[0]] + s.u * field[t[1]] + s.v * field[t[2]];
}

Vec3 ReferenceSurface::normal_at(const SurfacePoint& s) const {
  const auto& t = mesh_.faces[s.face];
  const Vec3 n = (1 - s.u - s.v) * vertex_normals_[t[0]] + s.u * vertex_normals_[t[1]] + s.v * vertex_normals_[t[2]];
  const double l = n.norm();
  return l > 0 ? Vec3(n / l) : normals_[s.face];
}

}  // namespace qs
