// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <string>

#include "quadsimp/mesh/mesh_file.h"

namespace qs {

//! Reads an ASCII OFF file ("[ST][C][N]OFF", one vertex and one face per line, colours
//! and normals ignored). Quads come back as quads; larger polygons are fanned into
//! triangles from their first corner, as the PLY and OBJ readers do.
//! \throw InvalidInput "PATH: line N: reason" for anything it cannot read as stated.
MeshFile read_off(const std::string& path);

}  // namespace qs
