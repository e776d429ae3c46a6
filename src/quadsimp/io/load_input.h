// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <string>

#include "quadsimp/convert/tri_to_quad.h"
#include "quadsimp/mesh/quad_mesh.h"
#include "quadsimp/mesh/tri_mesh.h"
#include "quadsimp/util/progress.h"

namespace qs {

//! A mesh file made ready for simplification.
struct Input {
  TriMesh reference;       //!< M0: the cleaned input triangles (quads split in two)
  QuadMesh quads;          //!< the pure quad mesh to simplify
  bool was_pure_quad = false;
  CleanReport clean;
  ConvertReport convert;   //!< empty when the file was already pure quad
};

//! Reads `path`, repairs what has a standard repair (logged through `log`), and
//! converts triangles to quads; a pure quad file is taken as it is.
//! \throw InvalidInput "PATH: reason" for anything that cannot be used.
Input load_input(const std::string& path, const ConvertOptions& options = {}, const LogFn& log = {});

}  // namespace qs
