// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <functional>
#include <string>

#include "quadsimp/convert/tri_to_quad.h"
#include "quadsimp/mesh/clean.h"
#include "quadsimp/mesh/mesh_file.h"
#include "quadsimp/mesh/quad_mesh.h"
#include "quadsimp/mesh/tri_mesh.h"
#include "quadsimp/util/progress.h"

namespace qs {

//! A mesh made ready for simplification.
struct Input {
  TriMesh reference;       //!< M0: the cleaned input triangles (quads split in two), or their retriangulation
  TriMesh input_surface;   //!< with a retriangulation (prepare_input()), the cleaned input triangles
  QuadMesh quads;          //!< the pure quad mesh to simplify
  bool was_pure_quad = false;  //!< the input's quads were taken as they are
  CleanReport clean;
  ConvertReport convert;   //!< empty when the input was already pure quad
  //! The mesh as given, kept only when it has vertex or face colours or a texture:
  //! preparing it merges, splits and moves vertices, and the quads take their colours
  //! (colours_of_quads()) and texture (texture_of_quads()) from it.
  MeshFile source;
};

//! The surface of `file` (its triangles, quads split in two), cleaned (clean()) as
//! prepare_input() cleans it: a pure quad mesh's folds are laid flat only where one of its
//! quads folds over itself. What the fitmaps and the distances of a file are computed on.
TriMesh cleaned_surface(const MeshFile& file, const std::string& name, const LogFn& log = {},
                        CleanReport* report = nullptr);

//! Triangles that replace the cleaned input's own (the CLI's --remesh, an isotropic
//! remeshing): they are converted, and are the reference M0 the quads are fitted to. The
//! fitting reads M0's normals interpolated from its vertices', which a coarse CAD mesh's
//! long triangles spread across its sharp edges (a 12-sided cone's base: 9 flipped quads
//! of 100 fitted to it, none fitted to the remeshing).
using Retriangulate = std::function<TriMesh(const TriMesh& surface)>;

//! Repairs what has a standard repair (logged through `log`) and converts triangles
//! to quads; a pure quad mesh is taken as it is, unless cleaning repaired it: then its
//! triangles are converted like any others. `name` prefixes every message.
//! The CLI (from a file) and the MeshLab plugins (from a layer) both come here. With
//! `retriangulate`, its triangles (cleaned in turn) are the reference and are converted,
//! even a quad mesh's.
//! \throw InvalidInput "NAME: reason" for anything that cannot be used.
Input prepare_input(MeshFile file, const std::string& name, const ConvertOptions& options = {},
                    const LogFn& log = {}, const Retriangulate& retriangulate = {});

}  // namespace qs
