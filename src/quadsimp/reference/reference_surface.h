// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <limits>
#include <memory>
#include <vector>

#include "quadsimp/mesh/tri_mesh.h"
#include "quadsimp/util/prefetch.h"

namespace qs {

//! A point on the reference surface: triangle and barycentric coordinates.
struct SurfacePoint {
  Index face = kNone;       //!< kNone when nothing was found
  double u = 0, v = 0;      //!< weights of corners 1 and 2 (corner 0 gets 1-u-v)
  Vec3 point = Vec3::Zero();
  double distance = std::numeric_limits<double>::infinity();
  bool found() const { return face != kNone; }
};

//! Which of Embree's kernels answer the queries. Embree picks the widest the CPU has
//! (SSE2 to AVX-512), and their hits differ in the last bits, which decide between
//! near-equal moves: glmark2's bunny to 5,000 quads came out three ways on one machine
//! with SSE2, AVX2 and AVX-512 kernels (bench/RESULTS.md, "The same quads on every
//! machine"). SSE2 kernels exist on every x86-64 CPU, and were as fast here.
enum class EmbreeKernels {
  Sse2,    //!< the same results on every x86-64 CPU (the default)
  Native,  //!< the CPU's widest: results depend on the CPU
};

//! The input surface M0 with an Embree 3 BVH: ray projection along a direction,
//! closest point, and barycentric lookup of per-vertex fields. Queries are const and
//! thread-safe. The only class that sees Embree.
class ReferenceSurface {
 public:
  //! Copies the mesh (it must be clean: see clean()).
  explicit ReferenceSurface(TriMesh mesh, EmbreeKernels kernels = EmbreeKernels::Sse2);
  ~ReferenceSurface();
  ReferenceSurface(const ReferenceSurface&) = delete;
  ReferenceSurface& operator=(const ReferenceSurface&) = delete;

  const TriMesh& mesh() const { return mesh_; }
  double bbox_diagonal() const { return diagonal_; }
  double mean_edge_length() const { return mean_edge_; }
  double area() const { return area_; }
  //! Each triangle's neighbours across its edges k -> k+1 (triangle_adjacency()).
  const std::vector<std::array<Index, 3>>& adjacency() const { return adjacency_; }
  //! Unit normal of triangle f.
  const Vec3& face_normal(Index f) const { return normals_[f]; }
  //! Whether triangle f is part of, or touches, a small patch folded over onto the
  //! surface (a scan defect: bounded all round by edges turning back by over 120
  //! degrees), where the surface's orientation says little.
  bool is_flap(Index f) const { return flap_[f] != 0; }

  //! Nearest point hit by the line p + t*dir, |t| <= max_dist, whose triangle normal
  //! agrees with dir (dot > 0). Falls back to the closest point within max_dist with
  //! an agreeing normal, then to the closest point at any distance with any normal.
  SurfacePoint project(const Vec3& p, const Vec3& dir, double max_dist) const;
  //! The same, starting from a known nearby triangle (the point's previous foot): the
  //! line is followed across neighbouring triangles from `start`, which is much
  //! cheaper than a ray through the BVH for the small moves of smoothing, and stays on
  //! the sheet the point was on. Falls back to project() when the walk leaves M0,
  //! meets a disagreeing triangle or takes too many steps.
  SurfacePoint project_near(Index start, const Vec3& p, const Vec3& dir, double max_dist) const;
  //! Prefetches (qs::prefetch()) what project_near() reads first of triangle `f`; then,
  //! as a second step once `f`'s corner numbers have come, what it and normal_at() read of
  //! its corners. Either ignores an `f` that is no triangle (kNone).
  void prefetch_triangle(Index f) const {
    if (f >= mesh_.n_faces()) return;
    prefetch(&normals_[f]);
    prefetch(&mesh_.faces[f]);
    prefetch(&adjacency_[f]);
  }
  void prefetch_corners(Index f) const {
    if (f >= mesh_.n_faces()) return;
    for (Index v : mesh_.faces[f]) prefetch(&mesh_.positions[v]), prefetch(&vertex_normals_[v]);
  }
  //! Nearest point of the line only (no fallback).
  SurfacePoint ray_project(const Vec3& p, const Vec3& dir, double max_dist) const;
  //! Closest point within max_dist; if `normal` is nonzero, only triangles whose
  //! normal agrees with it are considered.
  SurfacePoint closest(const Vec3& p, double max_dist = std::numeric_limits<double>::infinity(),
                       const Vec3& normal = Vec3::Zero()) const;
  //! The closest point at any distance, for a p known to have a point of M0 within
  //! `hint` (a vertex's own position, a face's corner): the search starts bounded by
  //! it, which prunes most of the BVH, and widens only if that finds nothing. Any hint
  //! gives the same point as closest(p); a tight one only makes it faster.
  SurfacePoint closest_within(const Vec3& p, double hint) const;
  //! Closest point to the centre of quad q (four corners): closest_within() with the
  //! nearest corner as hint, tight when the corners lie on M0.
  SurfacePoint closest_to_quad_centre(const Vec3* q) const;

  //! Where a point on M0's border may slide: from `from`, forward (the way the
  //! triangles' border edges run) up to `ahead` and backward up to `behind`. An end on
  //! no border edge bounds nothing.
  struct BorderArc {
    Vec3 from, ahead, behind;
  };
  //! Closest point to p on M0's border, searched along the border from the border edge
  //! nearest arc.from among those at a corner of triangle `start`, within `reach` (length
  //! along the border) and within the arc (its ends matched within 1e-6 of the diagonal);
  //! not found when `start` touches no border. Border vertices slide along the border
  //! with it, between their border neighbours: the closest point on the whole surface
  //! leaves the border wherever the border bends out of its tangent plane, and one found
  //! past a neighbour reverses the border's order.
  SurfacePoint closest_on_border(Index start, const Vec3& p, double reach, const BorderArc& arc) const;
  //! Distance from p to M0's border, every border edge tried (no walk): linear in the
  //! border, for checks and tests. Infinite where M0 has no border.
  double border_distance(const Vec3& p) const;

  //! Linear interpolation of a per-vertex field at a surface point.
  double interpolate(const std::vector<float>& field, const SurfacePoint& s) const;
  //! The same for a field of N values per vertex.
  template <std::size_t N>
  std::array<double, N> interpolate(const std::vector<std::array<float, N>>& field, const SurfacePoint& s) const {
    const auto& t = mesh_.faces[s.face];
    std::array<double, N> x;
    for (std::size_t k = 0; k < N; ++k)
      x[k] = (1 - s.u - s.v) * field[t[0]][k] + s.u * field[t[1]][k] + s.v * field[t[2]][k];
    return x;
  }
  //! Interpolated (area-weighted) vertex normal at a surface point.
  Vec3 normal_at(const SurfacePoint& s) const;

 private:
  TriMesh mesh_;
  std::vector<Vec3> normals_, vertex_normals_;
  std::vector<std::array<Index, 3>> adjacency_;  // for project_near()
  std::vector<char> flap_;
  // Per vertex, the border edge leaving it and the one arriving at it (3 * triangle +
  // corner, the edge running from that corner to the next), or kNone.
  std::vector<Index> border_out_, border_in_;
  std::vector<std::pair<Vec3, Vec3>> border_segments_;  // each border edge's start, and start to end
  double diagonal_ = 0, mean_edge_ = 0, area_ = 0;
  Vec3 origin_ = Vec3::Zero();  // subtracted from every point Embree sees
  double unit_ = 1;             // then multiplied by this power of two (Embree's unit length)
  // A point as Embree holds it.
  Eigen::Vector3f to_embree(const Vec3& p) const { return ((p - origin_) * unit_).cast<float>(); }
  struct Bvh;
  std::unique_ptr<Bvh> bvh_;
};

//! Closest point to p on triangle (a, b, c); returns it and writes the weights of b and c.
Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, double& u, double& v);

}  // namespace qs
