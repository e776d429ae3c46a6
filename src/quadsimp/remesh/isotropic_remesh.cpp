// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/remesh/isotropic_remesh.h"

#include <vcg/complex/algorithms/isotropic_remeshing.h>
#include <vcg/complex/complex.h>

#include <algorithm>
#include <cmath>

namespace qs {
namespace {

// The components vcglib's remeshing asks for (MeshLab's filter enables the same ones),
// in double precision as our meshes are.
class RVertex;
class RFace;
struct RTypes : vcg::UsedTypes<vcg::Use<RVertex>::AsVertexType, vcg::Use<RFace>::AsFaceType> {};
class RVertex : public vcg::Vertex<RTypes, vcg::vertex::Coord3d, vcg::vertex::Normal3d, vcg::vertex::VFAdj,
                                   vcg::vertex::Qualityd, vcg::vertex::Mark, vcg::vertex::BitFlags> {};
class RFace : public vcg::Face<RTypes, vcg::face::VertexRef, vcg::face::Normal3d, vcg::face::FFAdj, vcg::face::VFAdj,
                               vcg::face::Qualityd, vcg::face::Mark, vcg::face::BitFlags> {};
class RMesh : public vcg::tri::TriMesh<std::vector<RVertex>, std::vector<RFace>> {};

void fill(RMesh& m, const TriMesh& t) {
  auto v = vcg::tri::Allocator<RMesh>::AddVertices(m, t.positions.size());
  for (const Vec3& p : t.positions) (v++)->P() = vcg::Point3d(p.x(), p.y(), p.z());
  auto f = vcg::tri::Allocator<RMesh>::AddFaces(m, t.faces.size());
  for (const auto& tri : t.faces) {
    for (int k = 0; k < 3; ++k) f->V(k) = &m.vert[tri[k]];
    ++f;
  }
}

double edge_length_for(double diagonal, double area, Index target_quads) {
  // Near-equilateral triangles of edge L cover 0.433 L^2 each, pairs of them L^2 / 1.15.
  // A surface of much area in a small box (a crumpled sheet, a soup of random triangles
  // across a cube) at 1% of its diagonal took 766,070 triangles and 108 s to remesh: the
  // 1% is lengthened to keep to about 200,000.
  double length = std::max(0.01 * diagonal, std::sqrt(area / (0.433 * kMostTriangles)));
  if (target_quads > 0) length = std::min(length, std::sqrt(area / (4.0 * double(target_quads))));
  return length;
}

double diagonal_of(const TriMesh& surface) {
  const auto [lo, hi] = used_bbox(surface);
  return (hi - lo).norm();
}

}  // namespace

double remesh_edge_length(const TriMesh& surface, Index target_quads) {
  return edge_length_for(diagonal_of(surface), surface_area(surface), target_quads);
}

TriMesh remesh_isotropic(const TriMesh& surface, const RemeshOptions& options, RemeshReport* report) {
  const double diagonal = diagonal_of(surface);
  const double length = options.edge_share > 0 ? options.edge_share * diagonal
                                               : edge_length_for(diagonal, surface_area(surface), options.target_quads);
  RMesh work, target;
  fill(work, surface);
  fill(target, surface);
  vcg::tri::UpdateNormal<RMesh>::PerVertexNormalizedPerFaceNormalized(work);  // Do() makes the boxes
  vcg::tri::IsotropicRemeshing<RMesh>::Params params;
  params.SetTargetLen(length);
  params.SetFeatureAngleDeg(options.feature_angle_deg);
  params.iter = options.iterations;
  // A local operation may move the surface by 1% of the diagonal at most, as MeshLab's
  // filter lets it by default.
  params.maxSurfDist = 0.01 * diagonal;
  params.surfDistCheck = true;
  vcg::tri::IsotropicRemeshing<RMesh>::Do(work, target, params);
  vcg::tri::Allocator<RMesh>::CompactEveryVector(work);

  TriMesh out;
  out.positions.reserve(work.vert.size());
  for (const RVertex& v : work.vert) out.positions.emplace_back(v.cP()[0], v.cP()[1], v.cP()[2]);
  out.faces.reserve(work.face.size());
  for (const RFace& f : work.face)
    out.faces.push_back({Index(vcg::tri::Index(work, f.cV(0))), Index(vcg::tri::Index(work, f.cV(1))),
                         Index(vcg::tri::Index(work, f.cV(2)))});
  if (report) *report = {surface.n_faces(), out.n_faces(), length, diagonal};
  return out;
}

}  // namespace qs
