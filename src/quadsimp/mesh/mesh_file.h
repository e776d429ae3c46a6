// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "quadsimp/mesh/tri_mesh.h"

namespace qs {

using Colour = std::array<std::uint8_t, 4>;  //!< red, green, blue, alpha

//! A colour channel of 0 to 255 (or beyond: clamped) as its nearest byte.
inline std::uint8_t colour_byte(double x) {
  return x >= 255 ? 255 : x > 0 ? std::uint8_t(x + 0.5) : 0;  // NaN: 0
}

using TexCoord = std::array<float, 2>;  //!< u, v: v = 0 at the image's bottom row, as OBJ and MeshLab have it

//! A file's texture: its faces with their corners' texture coordinates, fanned into
//! triangles of their own (a list apart from the mesh's, which cleaning may change), and
//! the images they point into. The quads get a texture of their own, baked from it
//! (texture_bake.h).
struct FileTexture {
  std::vector<std::string> images;              //!< image files, as paths readable from here
  std::vector<std::array<Index, 3>> triangles;  //!< corners, as positions' indices
  std::vector<std::array<TexCoord, 3>> coords;  //!< each triangle's corners' coordinates
  std::vector<int> image;                       //!< each triangle's image, or -1: its colour
  //! Each triangle's colour where its image is -1 (an OBJ's faces whose material has a
  //! colour and no image, beside textured ones); none where every triangle has an image.
  std::vector<Colour> colours;
  bool empty() const { return triangles.empty(); }
};

//! A texture read face by face, as kept: none where no triangle has an image (colours
//! alone are face colours, not a texture), and no colours where every triangle has one.
FileTexture kept_texture(FileTexture texture);

//! A mesh as a file or a host application holds it, before any cleaning: its quads and
//! its other faces as triangles (a polygon of five or more corners fanned); a pure quad
//! mesh has quads alone.
struct MeshFile {
  std::vector<Vec3> positions;
  std::vector<std::array<Index, 3>> triangles;
  std::vector<std::array<Index, 4>> quads;
  std::vector<Colour> colours = {};  //!< one per position, or none
  //! Face colours: one per triangle and one per quad, or none.
  std::vector<Colour> triangle_colours = {};
  std::vector<Colour> quad_colours = {};
  //! The file or layer has texture coordinates.
  bool texture_coordinates = false;
  //! Its texture, where every face has coordinates into an image; else empty.
  FileTexture texture = {};
  //! An OBJ's lines that begin with no OBJ statement, skipped (damage: a vertex whose "v"
  //! was lost shifts every later one): how many, and where the first is, for the log.
  Index skipped_lines = 0;
  std::string first_skipped = {};
  bool is_pure_quad() const { return !quads.empty() && triangles.empty(); }
  bool has_face_colours() const { return !triangle_colours.empty() || !quad_colours.empty(); }
};

//! `file`'s surface as its texture's triangles, with the texture's colours as face
//! colours (a coloured triangle's own, a textured one's its material's) and the file's
//! vertex colours: what keeps an OBJ's faces coloured beside its texture in their colour
//! where the texture cannot be written (OFF, an image that cannot be read). Needs
//! file.texture.colours.
MeshFile texture_colours_as_faces(const MeshFile& file);

//! Rebuilds quads from triangles that carry "faux" edge flags, the way vcglib and
//! MeshLab store polygons: bit k of faux[t] marks edge k (corner k to k+1) of triangle
//! t as the inner diagonal of a quad. Triangles paired through a faux edge shared with a
//! neighbour become quads; the others stay triangles. `colours`, one per triangle if
//! given, go to the faces made of them (a quad takes its first triangle's).
MeshFile pair_faux_triangles(std::vector<Vec3> positions, std::vector<std::array<Index, 3>> triangles,
                             const std::vector<std::uint8_t>& faux, const std::vector<Colour>& colours = {});

//! Appends the two triangles of quad q split along its shorter diagonal.
void split_quad(const std::vector<Vec3>& positions, const std::array<Index, 4>& q,
                std::vector<std::array<Index, 3>>& triangles);

//! The triangles of a mesh: its triangles, or its quads each split along its shorter
//! diagonal, or along the other where the shorter one is already an edge or another
//! quad's split (vertices at one position counted as one), so that no edge gets four
//! triangles.
TriMesh triangles_of(const MeshFile& file);

//! The face colours of triangles_of(file), one per triangle (a quad's two take its
//! colour), or none if the file has none.
std::vector<Colour> triangle_colours_of(const MeshFile& file);

}  // namespace qs
