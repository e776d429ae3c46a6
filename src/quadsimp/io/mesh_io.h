// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <string>
#include <vector>

#include "quadsimp/mesh/quad_mesh.h"
#include "quadsimp/mesh/tri_mesh.h"

namespace qs {

//! What a mesh file held, as read (no cleaning yet). Either `quads` (the file was a
//! pure quad mesh: quad polygons, or MeshLab triangle pairs sharing a faux edge) or
//! `triangles` (anything else; other polygons are fan-triangulated).
struct MeshFile {
  std::vector<Vec3> positions;
  std::vector<std::array<Index, 3>> triangles;
  std::vector<std::array<Index, 4>> quads;
  bool is_pure_quad() const { return !quads.empty() && triangles.empty(); }
};

//! Reads PLY (ascii/binary), OBJ, OFF or STL through vcglib's importers.
//! \throw InvalidInput "PATH: reason" for unreadable, truncated or unknown files.
MeshFile read_mesh(const std::string& path);

//! The triangles of a file: its triangles, or its quads split along their shorter diagonal.
TriMesh triangles_of(const MeshFile& file);

//! Writes the quads of `mesh` as PLY (ASCII), OBJ or OFF, chosen by extension.
//! The file appears atomically: written to a temporary beside it, then renamed.
//! \throw InvalidInput for an unknown extension or a file that cannot be written.
void write_quad_mesh(const std::string& path, const QuadMesh& mesh);

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
