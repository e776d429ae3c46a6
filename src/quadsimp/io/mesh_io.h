// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <string>
#include <vector>

#include "quadsimp/mesh/mesh_file.h"
#include "quadsimp/mesh/quad_mesh.h"
#include "quadsimp/mesh/tri_mesh.h"

namespace qs {

//! Reads PLY (ASCII or binary; old Stanford files' triangle strips and range grids too),
//! OBJ or OFF with our readers, STL through vcglib's importer. Quads come
//! back as quads whether the file has quad polygons or MeshLab's triangle pairs with
//! faux-edge face flags (PLY saved with per-face flags); other polygons as triangles.
//! Vertex colours come back too (MeshFile::colours): PLY's, COFF's, and OBJ's
//! `v x y z r g b` (MeshLab's extension), where every vertex has one.
//! \throw InvalidInput "PATH: reason" for unreadable, truncated or unknown files.
MeshFile read_mesh(const std::string& path);

//! Writes the quads of `mesh` as PLY (ASCII), OBJ or OFF, chosen by extension, with
//! per-vertex `colours` if given (one per vertex id of `mesh`; OBJ: after the
//! coordinates, as MeshLab writes them). The file appears atomically: written to a
//! temporary beside it, then renamed.
//! \throw InvalidInput for an unknown extension or a file that cannot be written.
void write_quad_mesh(const std::string& path, const QuadMesh& mesh, const std::vector<Colour>& colours = {});

//! The colours of `from` (read_mesh()'s vertex colours) at the quads' vertices: each
//! the colour at its closest point on `from`'s surface, as the MeshLab filters give them
//! (vertex_colours.h). One per vertex id of `quads`; none if `from` has no colours.
std::vector<Colour> colours_of_quads(const MeshFile& from, const QuadMesh& quads);

//! Writes a triangle mesh as PLY with per-vertex float properties and a colour ramp
//! of the first property (for viewing fields in MeshLab). Atomic like write_quad_mesh.
struct VertexField {
  std::string name;
  std::vector<float> values;
};
void write_tri_mesh_ply(const std::string& path, const TriMesh& mesh,
                        const std::vector<VertexField>& fields = {});

//! Lower-case extension without the dot ("ply"), or "" if there is none.
std::string extension_of(const std::string& path);

}  // namespace qs
