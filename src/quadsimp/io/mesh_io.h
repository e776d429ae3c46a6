// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <string>
#include <vector>

#include "quadsimp/mesh/mesh_file.h"
#include "quadsimp/mesh/quad_mesh.h"
#include "quadsimp/mesh/tri_mesh.h"
#include "quadsimp/texture/texture_bake.h"

namespace qs {

//! Reads PLY (ASCII or binary; old Stanford files' triangle strips and range grids too),
//! OBJ or OFF with our readers, STL through vcglib's importer. Quads come
//! back as quads whether the file has quad polygons or MeshLab's triangle pairs with
//! faux-edge face flags (PLY saved with per-face flags); other polygons as triangles.
//! Vertex colours come back too (MeshFile::colours): PLY's, COFF's, and OBJ's
//! `v x y z r g b` (MeshLab's extension), where every vertex has one; and face colours
//! (MeshFile::triangle_colours and quad_colours): PLY's and OFF's where every face has
//! one, and OBJ's materials' diffuse colours where some face has one, with MeshLab's
//! colours for faces without (read_obj.cpp); and OBJ's and PLY's texture
//! (MeshFile::texture), where every face has coordinates into an image, or in an OBJ
//! where some face has and the others take their colour (FileTexture::colours).
//! \throw InvalidInput "PATH: reason" for unreadable, truncated or unknown files.
MeshFile read_mesh(const std::string& path);

//! A quad mesh's colours: one per vertex id and one per face id, or none of a kind.
struct QuadColours {
  std::vector<Colour> vertices;
  std::vector<Colour> faces;
};

//! Writes the quads of `mesh` as PLY (binary), OBJ or OFF, chosen by extension, with
//! their `colours` if given (OBJ, as MeshLab writes them: the vertices' after the
//! coordinates, the faces' as materials in PATH.mtl), and for OBJ and PLY their
//! `texture` if given (its image in texture_path_of(PATH), named by the materials'
//! map_Kd, or a PLY's TextureFile comment; a textured PLY's quads are triangle pairs with
//! a faux diagonal, as MeshLab writes them, since it reads no texture on a polygon). Each
//! file appears atomically: written to a temporary beside it, then renamed.
//! \throw InvalidInput for an unknown extension or a file that cannot be written.
void write_quad_mesh(const std::string& path, const QuadMesh& mesh, const QuadColours& colours = {},
                     const QuadTexture& texture = {});

//! Where write_quad_mesh() puts a texture: "DIR/NAME_texture.png" for DIR/NAME.obj or .ply,
//! each character of NAME but ASCII letters, digits, '.', '-' and '_' made '_' (for MeshLab).
std::string texture_path_of(const std::string& path);

//! The colours of `from` (read_mesh()'s) on the quads, as the MeshLab filters give them
//! (surface_colours.h): each vertex the vertex colour at its closest point on `from`'s
//! surface, each quad the colour of the face closest to its centroid. None of a kind
//! `from` does not have.
QuadColours colours_of_quads(const MeshFile& from, const QuadMesh& quads);

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
