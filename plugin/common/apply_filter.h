// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// The body of applyFilter for both MeshLab generations: their MeshDocument and
// MeshModel share every call used here except two, which the adapter passes in.
#pragma once

#include <algorithm>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>

#include <vcg/complex/algorithms/update/normal.h>

#include "filter_runner.h"
#include "filter_specs.h"
#include "layer_conversion.h"

namespace qs::plugin {

//! Marks a layer of quads (triangle pairs with a faux diagonal) polygonal, as MeshLab's
//! own quad filters do: without it the GUI draws the diagonals, and MeshLab's polygon
//! filters (planarity quality, the OBJ exporter's polygons) take the layer for triangles.
//! Those walk the faux edges through face-face adjacency, which a polygonal layer loaded
//! from a file has and a fresh one needs computed: without it pymeshlab's planarity
//! quality crashed on our layer. Each quad's two triangles then get the quad's normal,
//! as MeshLab gives them when it loads quads, so that flat shading shows quads.
template <class Model>
void mark_polygonal(Model* m) {
  m->updateDataMask(Model::MM_POLYGONAL | Model::MM_FACEFACETOPO);
  vcg::tri::UpdateNormal<std::remove_reference_t<decltype(m->cm)>>::PerBitQuadFaceNormalized(m->cm);
}

//! The layer's label, or "layer ID" for a layer without one (pymeshlab.Mesh arrays),
//! whose messages began with a bare ": ".
template <class Model>
std::string layer_name(const Model& m) {
  const std::string label = m.label().toStdString();
  return label.empty() ? "layer " + std::to_string(m.id()) : label;
}

//! How a MeshLab generation keeps textures, which the two do not share: `load(model*)` gives
//! a layer's images, one per entry of its cm.textures (an empty Image where one cannot be
//! had); `store(input model*, quads model*, name, image)` gives the quads' layer its one
//! texture, under `name` or (changing it) another, and says why not if it cannot ("" when
//! it has).
template <class Load, class Store>
struct TextureStore {
  Load load;
  Store store;
};
template <class Load, class Store>
TextureStore<Load, Store> texture_store(Load load, Store store) {
  return {load, store};
}

//! The layer of `m` as the core reads it. Its texture (MeshFile::texture) is kept where
//! every face has coordinates into a texture that loads, or a face colour (texture_of()),
//! whose images go to `images`; else none is, and loading logs that it is not carried.
template <class Model, class Textures>
MeshFile layer_file(Model* m, Textures& textures, std::vector<Image>& images) {
  MeshFile file = mesh_file_of(m->cm);
  file.texture_coordinates = m->hasDataMask(Model::MM_WEDGTEXCOORD) || m->hasDataMask(Model::MM_VERTTEXCOORD);
  if (!file.texture_coordinates) return file;
  file.texture = texture_of(m->cm, m->hasDataMask(Model::MM_WEDGTEXCOORD),
                            std::vector<std::string>(m->cm.textures.begin(), m->cm.textures.end()),
                            m->hasDataMask(Model::MM_FACECOLOR));
  if (file.texture.empty()) return file;
  images = textures.load(m);
  for (const int i : file.texture.image)
    if (i >= 0 && images[std::size_t(i)].empty()) {
      file.texture = {};
      break;
    }
  return file;
}

//! Gives the layer `result` holding `q` (assign_quads()) their texture, named after the
//! input layer, as texture coordinates into it.
template <class Model, class Textures>
void store_texture(const LayerQuads& q, Model* input, Model* result, Textures& textures, const std::string& name,
                   Outcome& out) {
  if (q.texture.empty()) return;
  std::string file = std::filesystem::path(name).stem().string() + "_quads_texture.png";
  if (const std::string why = textures.store(input, result, file, q.texture.image); !why.empty()) {
    out.log.push_back("the texture is not carried to the quads: " + why);
    return;
  }
  result->updateDataMask(Model::MM_WEDGTEXCOORD);
  assign_texture(result->cm, q.mesh, q.split, q.texture);
  out.log.push_back("texture baked onto the quads: " + file + ", " + std::to_string(q.texture.image.width) + " x " +
                    std::to_string(q.texture.image.height) + " texels, a tile for each quad");
}

//! Runs filter `id` on the current layer of `md`. `update_box(model*)` recomputes a
//! layer's bounding box and normals; `reference_layer()` returns the layer chosen as
//! ReferenceMesh (nullptr if none); `textures` is texture_store()'s.
//! \throw InvalidInput, std::invalid_argument.
template <class Document, class ParameterList, class CallBack, class UpdateBox, class ReferenceLayer, class Textures>
Outcome apply_filter(int id, Document& md, const ParameterList& params, CallBack* cb, UpdateBox update_box,
                     ReferenceLayer reference_layer, Textures textures) {
  auto* m = md.mm();
  using Model = std::remove_pointer_t<decltype(m)>;
  if (!m) throw InvalidInput("there is no current mesh");
  using Mesh = std::remove_reference_t<decltype(m->cm)>;
  const std::string name = layer_name(*m);
  require_faces(m->cm, name);
  // The quads take the input's vertex and face colours (at their closest points on it).
  const bool vertex_coloured = m->hasDataMask(Model::MM_VERTCOLOR);
  const bool face_coloured = m->hasDataMask(Model::MM_FACECOLOR);
  const bool coloured = vertex_coloured || face_coloured;
  const int colour_mask =
      (vertex_coloured ? int(Model::MM_VERTCOLOR) : 0) | (face_coloured ? int(Model::MM_FACECOLOR) : 0);
  // The quads take its texture too, baked onto them (run_simplification()).
  std::vector<Image> images;
  Outcome out;
  switch (id) {
    case kSimplify: {
      const SimplifyParams p = simplify_params_of(params);
      const int texture_size = texture_size_of(params);
      MeshFile file = layer_file(m, textures, images);
      const LayerQuads q = run_simplification(std::move(file), name, p, progress_of(cb), out, images, texture_size);
      auto* result = md.addNewMesh("", QString::fromStdString(name + " quads"), true);
      assign_quads(result->cm, q.mesh, q.split, q.flawed);
      store_texture(q, m, result, textures, name, out);
      if (coloured) {
        result->updateDataMask(colour_mask);
        paint(SurfaceColours<Mesh>(m->cm, vertex_coloured, face_coloured), result->cm);
      }
      update_box(result);
      mark_polygonal(result);
      break;
    }
    case kConvert: {
      const int texture_size = texture_size_of(params);
      MeshFile file = layer_file(m, textures, images);
      const LayerQuads q =
          run_conversion(std::move(file), name, params.getFloat("CreaseAngle"), out, images, texture_size);
      std::optional<SurfaceColours<Mesh>> colours;
      if (coloured) colours.emplace(m->cm, vertex_coloured, face_coloured);
      assign_quads(m->cm, q.mesh, q.split);
      if (colours) paint(*colours, m->cm);
      m->clearDataMask(Model::MM_WEDGTEXCOORD | Model::MM_VERTTEXCOORD);
      store_texture(q, m, m, textures, name, out);
      m->clearDataMask(Model::MM_VERTFACETOPO);
      update_box(m);
      mark_polygonal(m);
      break;
    }
    case kFitmaps: {
      const Fitmaps f = run_fitmaps(mesh_file_of(m->cm), name, params.getFloat("Tau"), progress_of(cb), out);
      m->updateDataMask(Model::MM_VERTQUALITY);
      store_fitmaps(m->cm, f);
      break;
    }
    case kQuality: {
      const auto* ref = reference_layer();
      if (!ref) throw InvalidInput("choose a reference mesh");
      run_quality(mesh_file_of(m->cm), name, mesh_file_of(ref->cm), layer_name(*ref),
                  unsigned(std::max(1000, params.getInt("SampleNum"))), out);
      break;
    }
    default: throw std::invalid_argument("unknown filter");
  }
  return out;
}

}  // namespace qs::plugin
