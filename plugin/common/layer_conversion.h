// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// CMeshO <-> core meshes, written once for both MeshLab generations (their CMeshO
// differ, the vcglib calls used here do not). Quads in a CMeshO are triangle pairs
// whose shared edge is marked faux on both sides.
#pragma once

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "quadsimp/io/surface_colours.h"
#include "quadsimp/mesh/mesh_file.h"
#include "quadsimp/mesh/quad_mesh.h"
#include "quadsimp/simplify/pipeline.h"
#include "quadsimp/texture/texture_bake.h"
#include "quadsimp/util/errors.h"
#include "quadsimp/util/progress.h"

namespace qs::plugin {

//! Each vertex's number among the live vertices of `m`, -1 for deleted ones.
template <class CMesh>
std::vector<int> live_vertex_numbers(const CMesh& m) {
  std::vector<int> id(m.vert.size(), -1);
  int n = 0;
  for (std::size_t i = 0; i < m.vert.size(); ++i)
    if (!m.vert[i].IsD()) id[i] = n++;
  return id;
}

//! The live vertices and faces of a MeshLab mesh, with quads rebuilt from faux pairs.
//! Vertex i of the result is the i-th live vertex of `m`.
template <class CMesh>
MeshFile mesh_file_of(const CMesh& m) {
  std::vector<Vec3> positions;
  const std::vector<int> id = live_vertex_numbers(m);
  for (const auto& v : m.vert) {
    if (v.IsD()) continue;
    const auto& p = v.cP();
    positions.emplace_back(double(p[0]), double(p[1]), double(p[2]));
  }
  std::vector<std::array<Index, 3>> tris;
  std::vector<std::uint8_t> faux;
  tris.reserve(m.face.size());
  for (const auto& f : m.face) {
    if (f.IsD()) continue;
    std::array<Index, 3> t;
    for (int k = 0; k < 3; ++k) t[k] = Index(id[f.cV(k) - &m.vert[0]]);
    tris.push_back(t);
    faux.push_back(std::uint8_t(unsigned(f.IsF(0)) | unsigned(f.IsF(1)) << 1 | unsigned(f.IsF(2)) << 2));
  }
  return pair_faux_triangles(std::move(positions), std::move(tris), faux);
}

//! Replaces the content of `m` with the quads of `q`, each as two triangles split
//! along the diagonal `split` (split_diagonals()) picks, which is marked faux; the two
//! triangles of each quad in `selected` (face ids of `q`) are selected, no other. At a
//! doublet (two quads sharing two edges) both quads' shorter diagonals join the same two
//! corners, which made the same triangle twice, and MeshLab's polygon view then saw an 8-gon.
template <class CMesh>
void assign_quads(CMesh& m, const QuadMesh& q, const std::vector<std::uint8_t>& split,
                  const std::vector<Index>& selected = {}) {
  using Alloc = typename vcg::tri::Allocator<CMesh>;
  m.Clear();
  const std::vector<Index> id = q.live_vertex_ids();
  auto vi = Alloc::AddVertices(m, q.n_vertices());
  for (Index v = 0; v < q.vertex_capacity(); ++v)
    if (q.is_vertex_live(v)) {
      const Vec3& p = q.position(v);
      m.vert[id[v]].P() = typename CMesh::CoordType(p.x(), p.y(), p.z());
    }
  (void)vi;
  Alloc::AddFaces(m, 2 * std::size_t(q.n_faces()));
  std::vector<char> chosen(q.face_capacity(), 0);
  for (Index face : selected) chosen[face] = 1;
  std::size_t f = 0;
  for (Index face = 0; face < q.face_capacity(); ++face) {
    if (!q.is_face_live(face)) continue;
    auto c = q.face_vertices(face);
    if (split[face]) c = {c[1], c[2], c[3], c[0]};  // the diagonal taken is c0-c2
    auto& t1 = m.face[f++];
    auto& t2 = m.face[f++];
    t1.V(0) = &m.vert[id[c[0]]], t1.V(1) = &m.vert[id[c[1]]], t1.V(2) = &m.vert[id[c[2]]];
    t2.V(0) = &m.vert[id[c[0]]], t2.V(1) = &m.vert[id[c[2]]], t2.V(2) = &m.vert[id[c[3]]];
    t1.ClearAllF();
    t2.ClearAllF();
    t1.SetF(2);  // c2 -> c0
    t2.SetF(0);  // c0 -> c2
    if (chosen[face]) t1.SetS(), t2.SetS();
  }
}

template <class CMesh>
void assign_quads(CMesh& m, const QuadMesh& q) {
  assign_quads(m, q, split_diagonals(q));
}

//! The texture of a layer: its live faces' corner coordinates (wedge ones if `wedge`,
//! else the vertices'), into the layer's textures, named by `images` (one per entry of
//! m.textures). Vertices numbered as mesh_file_of() numbers them. With `face_colours`, a
//! face whose texture number is -1 at every corner (MeshLab's reading of an OBJ face whose
//! material has no image) takes its face colour instead. Empty where some face's texture
//! number names no texture otherwise, or where none does.
template <class CMesh>
FileTexture texture_of(const CMesh& m, bool wedge, std::vector<std::string> images, bool face_colours = false) {
  const std::vector<int> id = live_vertex_numbers(m);
  FileTexture t;
  for (const auto& f : m.face) {
    if (f.IsD()) continue;
    std::array<TexCoord, 3> coords;
    int image = -1;
    for (int k = 0; k < 3; ++k) {
      const auto& tc = wedge ? f.cWT(k) : f.cV(k)->cT();
      coords[k] = {float(tc.U()), float(tc.V())};
      if (k == 0) image = tc.N();
      const bool coloured = face_colours && image == -1;
      if (tc.N() != image || (!coloured && (image < 0 || std::size_t(image) >= images.size()))) return {};
    }
    t.triangles.push_back({Index(id[f.cV(0) - &m.vert[0]]), Index(id[f.cV(1) - &m.vert[0]]),
                           Index(id[f.cV(2) - &m.vert[0]])});
    t.coords.push_back(coords);
    t.image.push_back(image);
    if (face_colours) t.colours.push_back({f.cC()[0], f.cC()[1], f.cC()[2], f.cC()[3]});
  }
  t.images = std::move(images);
  return kept_texture(std::move(t));
}

//! Gives `quads` (as assign_quads(q, split) made them) the coordinates of `texture` as
//! wedge texture coordinates into the layer's texture 0. \pre `quads` has them enabled.
template <class CMesh>
void assign_texture(CMesh& quads, const QuadMesh& q, const std::vector<std::uint8_t>& split,
                    const QuadTexture& texture) {
  std::size_t f = 0;
  for (Index face = 0; face < q.face_capacity(); ++face) {
    if (!q.is_face_live(face)) continue;
    const int first = split[face] ? 1 : 0;  // the corner assign_quads() starts both triangles at
    const auto corner = [&](int k) { return texture.corners[face][std::size_t((first + k) % 4)]; };
    const int corners[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (const auto& tri : corners) {
      auto& t = quads.face[f++];
      for (int k = 0; k < 3; ++k) {
        t.WT(k).U() = corner(tri[k])[0];
        t.WT(k).V() = corner(tri[k])[1];
        t.WT(k).N() = 0;
      }
    }
  }
}

//! Colours `quads` (as assign_quads() made them) from `colours` (SurfaceColours of the
//! input layer): their vertices, and each quad's two triangles alike, as `colours` has
//! them. \pre `quads` has the colours enabled that `colours` has.
template <class Colours, class CMesh>
void paint(Colours&& colours, CMesh& quads) {
  if (colours.has_vertex_colours())
    for (auto& v : quads.vert)
      if (!v.IsD()) v.C() = colours.vertex_colour(v.cP());
  if (!colours.has_face_colours()) return;
  for (std::size_t f = 0; f + 1 < quads.face.size(); f += 2) {
    auto& t1 = quads.face[f];
    auto& t2 = quads.face[f + 1];
    const auto centroid = (t1.cP(0) + t1.cP(1) + t1.cP(2) + t2.cP(2)) / 4;  // t2 is c0, c2, c3
    t1.C() = t2.C() = colours.face_colour(centroid);
  }
}

//! Refuses a layer without faces with a message that says what it probably is.
template <class CMesh>
void require_faces(const CMesh& m, const std::string& name) {
  if (m.fn == 0)
    throw InvalidInput(name + ": the layer has no faces (" + std::to_string(m.vn) +
                       " vertices: a point cloud, or lines only?); quadsimp needs a triangle surface");
}

//! The simplification parameters from either generation's RichParameterList (their
//! getters share names), checked. \throw std::invalid_argument.
template <class ParameterList>
SimplifyParams simplify_params_of(const ParameterList& params) {
  SimplifyParams p;
  p.adaptive = params.getBool("Adaptive");
  p.auto_halt = params.getBool("AutoHalt");
  p.target_faces = p.adaptive && p.auto_halt ? 0 : Index(std::max(0, params.getInt("TargetFaceNum")));
  p.target_share = p.adaptive && p.auto_halt ? 0 : params.getFloat("TargetPerc");
  p.halt_share = params.getFloat("HaltShare");
  p.tau = params.getFloat("Tau");
  p.max_aspect = params.getFloat("MaxAspect");
  p.reach = params.getFloat("Reach");
  p.preserve_boundary = params.getBool("PreserveBoundary");
  p.keep_tips = params.getBool("KeepTips");
  p.crease_angle = params.getFloat("CreaseAngle");
  p.fast = params.getBool("Fast");
  p.fit_to_input = params.getBool("FitToInput");
  if (const std::string why = check_params(p); !why.empty()) throw std::invalid_argument(why);
  return p;
}

//! The Texture size parameter (either generation's list), checked against the range the
//! CLI takes. \throw std::invalid_argument.
template <class ParameterList>
int texture_size_of(const ParameterList& params) {
  const int side = params.getInt("TextureSize");
  if (side < TextureBakeOptions::kSmallestSide || side > TextureBakeOptions::kLargestSide)
    throw std::invalid_argument("the texture size must be from " + std::to_string(TextureBakeOptions::kSmallestSide) +
                                " to " + std::to_string(TextureBakeOptions::kLargestSide) + " texels, not " +
                                std::to_string(side));
  return side;
}

//! Fitmaps of the live vertices (in order) into the attributes FitmapS and FitmapM,
//! and S into the vertex quality. \pre the mesh has per-vertex quality enabled.
template <class CMesh>
void store_fitmaps(CMesh& m, const Fitmaps& f) {
  using Scalar = typename CMesh::ScalarType;
  auto s = vcg::tri::Allocator<CMesh>::template GetPerVertexAttribute<Scalar>(m, "FitmapS");
  auto mm = vcg::tri::Allocator<CMesh>::template GetPerVertexAttribute<Scalar>(m, "FitmapM");
  std::size_t i = 0;
  for (std::size_t v = 0; v < m.vert.size(); ++v) {
    if (m.vert[v].IsD()) continue;
    s[v] = Scalar(f.s[i]);
    mm[v] = Scalar(f.m[i]);
    m.vert[v].Q() = Scalar(f.s[i]);
    ++i;
  }
}

//! MeshLab's progress callback (vcg::CallBackPos, the same in both generations) as the
//! core's ProgressFn, called only when the percentage changes (meshlabserver prints
//! every call). MeshLab has no cancel button for filters: always continue.
template <class CallBack>
ProgressFn progress_of(CallBack* cb) {
  if (!cb) return {};
  return [cb, last = -1](float f, std::string_view stage) mutable {
    const int percent = int(100 * f);
    if (percent != last) {
      last = percent;
      cb(percent, (std::string(stage) + " ").c_str());
    }
    return true;
  };
}

}  // namespace qs::plugin
