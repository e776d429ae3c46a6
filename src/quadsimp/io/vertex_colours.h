// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// Vertex colours carried from an input mesh to its quads, on vcglib's meshes. A template
// header: qs_io compiles it with its vcglib, each MeshLab plugin with MeshLab's (they
// never link qs_io), so the CLI and both filters colour quads the same way.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include <vcg/complex/algorithms/closest.h>
#include <vcg/complex/algorithms/update/normal.h>
#include <vcg/complex/append.h>
#include <vcg/space/index/grid_static_ptr.h>

#include "quadsimp/mesh/mesh_file.h"

namespace qs {

namespace detail {
// The closest-point search marks faces: MeshLab's meshes hold marks as an optional
// component, to enable; ours have them built in.
template <class Mesh>
auto enable_marks(Mesh& m, int) -> decltype(m.face.EnableMark(), void()) {
  m.face.EnableMark();
}
template <class Mesh>
void enable_marks(Mesh&, long) {}
}  // namespace detail

//! A mesh's vertex colours, kept to colour its quads with once the mesh has changed: the
//! quads' vertices lie on the input surface, and each takes the colour at its closest
//! point there, interpolated over the triangle, as MeshLab's Vertex Attribute Transfer
//! does. A mesh of one colour (pymeshlab gives meshes made from arrays a default one)
//! passes it on without a copy or a search. \pre Mesh's faces have normals.
template <class Mesh>
class VertexColours {
 public:
  using Coord = typename Mesh::CoordType;
  //! Searched: a copy of the mesh's live part (a MeshLab layer, which may have deleted
  //! faces, and which the filters leave as it was or replace), or the mesh itself (one
  //! made to be searched, without deleted faces, kept alive meanwhile).
  enum class Use { copy, in_place };

  explicit VertexColours(Mesh& mesh, Use use = Use::copy) {
    bool seen = false;
    for (const auto& v : mesh.vert) {
      if (v.IsD()) continue;
      if (!seen) colour_ = v.cC(), seen = true;
      if (v.cC() != colour_) {
        // The grid indexes deleted faces too, hence the copy of the live part. vcglib's
        // point-to-triangle distance reads unit face normals, which a layer's may not be.
        if (use == Use::copy) vcg::tri::Append<Mesh, Mesh>::MeshCopy(copy_, mesh);
        source_ = use == Use::copy ? &copy_ : &mesh;
        detail::enable_marks(*source_, 0);
        vcg::tri::UpdateNormal<Mesh>::PerFaceNormalized(*source_);
        grid_.Set(source_->face.begin(), source_->face.end());
        return;
      }
    }
  }

  VertexColours(const VertexColours&) = delete;  // source_ may point into the object
  VertexColours& operator=(const VertexColours&) = delete;

  //! The colour at the point of the mesh closest to p.
  vcg::Color4b at(const Coord& p) {
    if (!source_) return colour_;
    using Scalar = typename Mesh::ScalarType;
    Scalar dist = 0;
    Coord foot(0, 0, 0);
    const auto* f = vcg::tri::GetClosestFaceBase(*source_, grid_, p, std::numeric_limits<Scalar>::max(), dist, foot);
    if (!f) return colour_;
    // The closest point lies on the triangle, up to rounding: its weights are clamped to
    // it. A triangle of no area has none: its nearest corner's colour.
    Coord w(0, 0, 0);
    vcg::InterpolationParameters(*f, vcg::TriangleNormal(*f), foot, w);
    for (int i = 0; i < 3; ++i) w[i] = std::isfinite(w[i]) ? std::max(w[i], Scalar(0)) : Scalar(0);
    if (const Scalar sum = w[0] + w[1] + w[2]; sum > 0) {
      w /= sum;
    } else {
      int k = 0;
      for (int i = 1; i < 3; ++i)
        if (vcg::SquaredDistance(f->cP(i), foot) < vcg::SquaredDistance(f->cP(k), foot)) k = i;
      w = Coord(0, 0, 0);
      w[k] = 1;
    }
    vcg::Color4b c;
    for (int k = 0; k < 4; ++k) {
      const double x = w[0] * f->cV(0)->cC()[k] + w[1] * f->cV(1)->cC()[k] + w[2] * f->cV(2)->cC()[k];
      c[k] = colour_byte(x);
    }
    return c;
  }

 private:
  Mesh copy_;
  Mesh* source_ = nullptr;  // what at() searches; none for a mesh of one colour
  vcg::GridStaticPtr<typename Mesh::FaceType, typename Mesh::ScalarType> grid_;
  vcg::Color4b colour_;
};

}  // namespace qs
