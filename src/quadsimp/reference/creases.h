// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "quadsimp/mesh/tri_mesh.h"
#include "quadsimp/reference/reference_surface.h"

namespace qs {

//! Per triangle edge (3 * f + k, corner k to k + 1), whether it is a crease, as Creases
//! chains them: its two triangles' normals, filtered, part by more than `angle_deg`
//! degrees, and its network is not dropped (see Creases). Border edges are not creases;
//! all false for angle_deg 0 (no creases asked for) or 180 and over.
std::vector<char> crease_edges(const TriMesh& mesh, const std::vector<std::array<Index, 3>>& adjacency,
                               double angle_deg);

//! The sharp edges of M0 chained into curves (ours; the paper keeps no feature, and
//! smoothing rounds them off: a CAD cylinder's rims came out bevelled). An edge is sharp
//! where its triangles' normals, filtered first so that a scan's noise neither makes nor
//! breaks creases, part by more than the angle. A curve runs between two corners, or round
//! a closed loop. Corners are the crease vertices where the curves end or meet (one crease
//! edge, three or more, or a crease reaching M0's border) and those where a curve turns by
//! more than 45 degrees, there and still two mean input edges on (a box's edge loop round a
//! rounded corner has none; a bracket's L has one; a noisy crease's zigzags have none). A
//! network of curves (those meeting at corners) shorter than four mean input edges in all
//! (a scan's noise) is dropped. The simplifier keeps corners where they are and slides the
//! other crease vertices along their curves.
//!
//! Points on a curve are given by a parameter s: segment i spans [i, i + 1] (vertex i at
//! s = i); a closed curve's last segment ends back at vertex 0 (s = its segment count).
class Creases {
 public:
  Creases() = default;
  //! The creases of `mesh` (its triangle_adjacency()) sharper than angle_deg.
  Creases(const TriMesh& mesh, const std::vector<std::array<Index, 3>>& adjacency, double angle_deg);

  bool empty() const { return edges_ == 0; }
  Index n_curves() const { return Index(curves_.size()); }
  Index n_edges() const { return edges_; }
  Index n_corners() const { return corners_; }
  bool closed(Index c) const { return curves_[c].closed; }
  //! The curve's segment count: the range of its parameter.
  double span(Index c) const { return double(curves_[c].faces.size()); }
  //! M0's vertices along curve c, in order (a closed curve's first is not repeated).
  const std::vector<Index>& vertices(Index c) const { return curves_[c].vertices; }

  //! Where a point of M0 lies: on a corner, or on a curve at parameter s, or on neither.
  struct Place {
    Index curve = kNone;
    double s = 0;
    bool corner = false;
  };
  //! The place of p, a point on triangle `face` of M0 (or at one of its corners), within
  //! `tolerance` of a corner or a crease edge of that triangle.
  Place place_of(const TriMesh& mesh, Index face, const Vec3& p, double tolerance) const;
  //! The place of M0's vertex v.
  Place place_of_vertex(Index v) const;

  //! The point of curve c nearest p, among those from parameter s back by `back` and
  //! ahead by `ahead` (an open curve's ends bound both), with its parameter and its place
  //! on M0 (one of the crease edge's triangles; its distance is to p).
  struct CurvePoint {
    SurfacePoint foot;
    double s = 0;
  };
  CurvePoint closest(const TriMesh& mesh, Index c, const Vec3& p, double s, double back, double ahead) const;
  //! The point of curve c at parameter s.
  CurvePoint at(const TriMesh& mesh, Index c, double s) const;

  //! Parameter distance from s to t going forward along curve c (wrapping round a closed
  //! curve; negative when t lies behind s on an open one).
  double ahead_of(Index c, double s, double t) const;

 private:
  struct Curve {
    std::vector<Index> vertices;
    // Per segment, a triangle with the segment as its edge k (from corner k to k + 1, in
    // either direction along the curve) and whether it runs backward there.
    std::vector<Index> faces;
    std::vector<std::uint8_t> edge;
    bool closed = false;
  };
  // Chains the crease edges `crease` marks into curves, and sets every member from them.
  void chain(const TriMesh& mesh, const std::vector<std::array<Index, 3>>& adjacency, const std::vector<char>& crease);
  // Segment i of curve c's point at t in [0, 1] from its start.
  CurvePoint on_segment(const TriMesh& mesh, const Curve& curve, Index i, double t) const;
  std::vector<Curve> curves_;
  // Per triangle edge, the curve and segment it is (kNone: not a crease edge).
  std::vector<Index> edge_curve_, edge_segment_;
  // Per M0 vertex: a corner, or the curve it lies inside and its index along it (kNone).
  std::vector<char> corner_;
  std::vector<Index> vertex_curve_, vertex_index_;
  Index edges_ = 0, corners_ = 0;
};

}  // namespace qs
