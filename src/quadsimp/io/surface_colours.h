// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// Vertex and face colours carried from an input mesh to its quads, on vcglib's meshes. A
// template header: qs_io compiles it with its vcglib, each MeshLab plugin with MeshLab's
// (they never link qs_io), so the CLI and both filters colour quads the same way.
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
// The closest-point search marks faces, and a copy keeps face colours only where its
// faces hold them: MeshLab's meshes hold both as optional components, to enable; ours
// have them built in.
template <class Mesh>
auto enable_marks(Mesh& m, int) -> decltype(m.face.EnableMark(), void()) {
  m.face.EnableMark();
}
template <class Mesh>
void enable_marks(Mesh&, long) {}
template <class Mesh>
auto enable_face_colours(Mesh& m, int) -> decltype(m.face.EnableColor(), void()) {
  m.face.EnableColor();
}
template <class Mesh>
void enable_face_colours(Mesh&, long) {}
}  // namespace detail

//! A mesh's vertex and face colours, kept to colour its quads with once the mesh has
//! changed. The quads' vertices lie on the input surface, and each takes the colour at
//! its closest point there, interpolated over the triangle, as MeshLab's Vertex Attribute
//! Transfer does; a quad takes the colour of the face closest to its centre (colours are
//! not blended across a face's border). A mesh of one colour (pymeshlab gives meshes made
//! from arrays a default one) passes it on without a copy or a search.
//! \pre Mesh's faces have normals, and colours if `faces` is asked for.
template <class Mesh>
class SurfaceColours {
 public:
  using Coord = typename Mesh::CoordType;
  //! Searched: a copy of the mesh's live part (a MeshLab layer, which may have deleted
  //! faces, and which the filters leave as it was or replace), or the mesh itself (one
  //! made to be searched, without deleted faces, kept alive meanwhile).
  enum class Use { copy, in_place };

  //! Keeps the colours of the mesh's vertices if `vertices`, of its faces if `faces`.
  SurfaceColours(Mesh& mesh, bool vertices, bool faces, Use use = Use::copy)
      : vertices_(vertices), faces_(faces) {
    if (vertices) keep_colours(mesh.vert, vertex_colour_);
    if (faces) keep_colours(mesh.face, face_colour_);
    if (!vertex_colour_.varied && !face_colour_.varied) return;
    // The grid indexes deleted faces too, hence the copy of the live part. vcglib's
    // point-to-triangle distance reads unit face normals, which a layer's may not be.
    if (use == Use::copy) {
      if (faces) detail::enable_face_colours(copy_, 0);
      vcg::tri::Append<Mesh, Mesh>::MeshCopy(copy_, mesh);
    }
    source_ = use == Use::copy ? &copy_ : &mesh;
    detail::enable_marks(*source_, 0);
    vcg::tri::UpdateNormal<Mesh>::PerFaceNormalized(*source_);
    grid_.Set(source_->face.begin(), source_->face.end());
  }

  SurfaceColours(const SurfaceColours&) = delete;  // source_ may point into the object
  SurfaceColours& operator=(const SurfaceColours&) = delete;

  bool has_vertex_colours() const { return vertices_; }
  bool has_face_colours() const { return faces_; }

  //! The vertex colour at the point of the mesh closest to p.
  vcg::Color4b vertex_colour(const Coord& p) {
    Coord foot(0, 0, 0);
    const auto* f = !vertex_colour_.varied ? nullptr : closest(p, foot);
    if (!f) return vertex_colour_.colour;
    // The closest point lies on the triangle, up to rounding: its weights are clamped to
    // it. A triangle of no area has none: its nearest corner's colour.
    using Scalar = typename Mesh::ScalarType;
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

  //! The colour of the face of the mesh closest to p.
  vcg::Color4b face_colour(const Coord& p) {
    Coord foot(0, 0, 0);
    const auto* f = !face_colour_.varied ? nullptr : closest(p, foot);
    return f ? f->cC() : face_colour_.colour;
  }

 private:
  struct Kept {
    vcg::Color4b colour = vcg::Color4b(0, 0, 0, 255);  // the one colour, if not varied
    bool varied = false;
  };

  // The live elements' one colour, or that they vary.
  template <class Elements>
  static void keep_colours(const Elements& elements, Kept& kept) {
    bool seen = false;
    for (const auto& e : elements) {
      if (e.IsD()) continue;
      if (!seen) kept.colour = e.cC(), seen = true;
      if (e.cC() != kept.colour) {
        kept.varied = true;
        return;
      }
    }
  }

  const typename Mesh::FaceType* closest(const Coord& p, Coord& foot) {
    using Scalar = typename Mesh::ScalarType;
    Scalar dist = 0;
    return vcg::tri::GetClosestFaceBase(*source_, grid_, p, std::numeric_limits<Scalar>::max(), dist, foot);
  }

  bool vertices_, faces_;
  Kept vertex_colour_, face_colour_;
  Mesh copy_;
  Mesh* source_ = nullptr;  // what the search runs on; none where every kept kind has one colour
  vcg::GridStaticPtr<typename Mesh::FaceType, typename Mesh::ScalarType> grid_;
};

}  // namespace qs
