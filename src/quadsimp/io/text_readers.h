// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <string>

#include "quadsimp/mesh/mesh_file.h"

namespace qs {

// Quads come back as quads (also MeshLab's triangle pairs whose shared edge a PLY's face
// flags mark faux); larger polygons are fanned into triangles from their first corner. \throw InvalidInput "PATH: line
// N: reason" for anything they cannot read as stated.

//! ASCII OFF ("[ST][C][N]OFF", one vertex and one face per line): positions, COFF's
//! vertex colours and the faces' colours; normals and texture coordinates ignored.
MeshFile read_off(const std::string& path);

//! OBJ: "v" and "f" lines (corners from 1, or back from -1; "q": QOBJ's zero-based
//! quads), vertex colours after the coordinates, face colours from the materials'
//! diffuse colours, and the texture ("vt", corners "v/vt", the materials' map_Kd images);
//! normals and groups ignored.
MeshFile read_obj(const std::string& path);

//! PLY, ASCII or binary: vertex x, y, z and colours, the faces' corner lists, flags and
//! colours, old Stanford files' triangle strips and range grids (a quad per cell of four
//! points), and the texture as MeshLab writes it ("comment TextureFile" images, texcoord
//! per face corner or texture_u/v per vertex, texnumber).
MeshFile read_ply(const std::string& path);

}  // namespace qs
