// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// What each filter does, in plain C++ on the core's types: both MeshLab adapters call
// these after converting their layer, so the two generations (and the CLI, which runs
// the same core functions) give the same results.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "quadsimp/mesh/mesh_file.h"
#include "quadsimp/mesh/quad_mesh.h"
#include "quadsimp/simplify/pipeline.h"
#include "quadsimp/texture/texture_bake.h"

namespace qs::plugin {

//! Lines for the MeshLab log and named values to return.
struct Outcome {
  std::vector<std::string> log;
  std::map<std::string, double> values;
};

//! A layer's quads, as MeshLab draws them, and the layer's texture on them.
struct LayerQuads {
  QuadMesh mesh;
  std::vector<std::uint8_t> split;  //!< per face id: the diagonal it is drawn split at (split_diagonals())
  QuadTexture texture;              //!< the layer's texture baked onto them, or none
  //! Face ids of the quads a simplification left non-convex, flipped, folded or beyond
  //! the reach (noted_faces()), which the filter selects in its result; none after a
  //! conversion.
  std::vector<Index> flawed;
};

//! Prepares `layer` (cleaning, conversion) and simplifies it; a layer with a texture
//! (MeshFile::texture, whose images are `images`) gets it baked onto the quads, as the CLI
//! bakes it, in an atlas at most `texture_size` texels across (TextureBakeOptions::max_side).
//! \throw InvalidInput.
LayerQuads run_simplification(MeshFile layer, const std::string& name, const SimplifyParams& params,
                              const ProgressFn& progress, Outcome& outcome, const std::vector<Image>& images = {},
                              int texture_size = TextureBakeOptions().max_side);

//! Prepares `layer` and returns its quads, with its texture as run_simplification() does;
//! no pair is made across an edge sharper than `crease_angle` degrees (0: none).
//! \throw InvalidInput; std::invalid_argument for an angle outside [0, 180).
LayerQuads run_conversion(MeshFile layer, const std::string& name, double crease_angle, Outcome& outcome,
                          const std::vector<Image>& images = {}, int texture_size = TextureBakeOptions().max_side);

//! S and M fitmaps at the layer's own vertices (cleaning may merge or drop vertices,
//! so each one reads the field at its closest point on the cleaned surface).
Fitmaps run_fitmaps(const MeshFile& layer, const std::string& name, double tau, const ProgressFn& progress,
                    Outcome& outcome);

//! Quality of a pure quad layer and its distance to a reference layer.
//! \throw InvalidInput if `quads` is not a pure quad mesh.
void run_quality(const MeshFile& quads, const std::string& quads_name, const MeshFile& reference,
                 const std::string& reference_name, unsigned samples, Outcome& outcome);

}  // namespace qs::plugin
