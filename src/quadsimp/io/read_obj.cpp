// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
//
// OBJ is read here, not by vcglib: its reader took a coordinate that is not a number for
// 0, followed face corners naming no vertex into memory it did not own (a crash),
// dropped a triangle naming a later vertex without a word, and read a comment after a
// face's corners as more corners. It also took 2.7 s on a 1.1M-triangle file.
#include <filesystem>
#include <optional>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "quadsimp/io/text_lines.h"
#include "quadsimp/io/text_readers.h"

namespace qs {
namespace {

// A name that may hold spaces: the fields from the second on.
std::string name_on(const detail::TextLines& line) {
  std::string name;
  for (std::size_t i = 1; i < line.size(); ++i) (name += i > 1 ? " " : "") += line[i];
  return name;
}

// The diffuse colours (Kd, with d as alpha, or Tr as 1 - alpha: MeshLab writes Tr) of an
// .mtl file's materials, into `colours` by name, as MeshLab reads face colours from OBJ. A material with a diffuse texture
// (map_Kd) gets none: its faces' colours are the texture's. A file that cannot be read
// adds nothing (its faces then have no colour, and the mesh none).
void read_materials(const std::string& path, std::unordered_map<std::string, Colour>& colours) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return;
  detail::TextLines in(path);
  std::string name;
  std::optional<Colour> colour;
  bool textured = false;
  const auto keep = [&] {
    if (!name.empty() && colour && !textured) colours[name] = *colour;
  };
  while (in.next()) {
    const std::string_view kw = in[0];
    if (kw == "newmtl") {
      keep();
      name = name_on(in), colour.reset(), textured = false;
    } else if (kw == "Kd") {
      Colour c;
      const std::uint8_t alpha = colour ? (*colour)[3] : 255;
      colour = in.colour(1, true, c) ? std::optional<Colour>(c) : std::nullopt;
      if (colour) (*colour)[3] = alpha;
    } else if ((kw == "d" || kw == "Tr") && in.size() == 2 && colour) {
      double x;
      if (parse_number(in[1], x)) (*colour)[3] = colour_byte(255 * (kw == "d" ? x : 1 - x));
    } else if (kw == "map_Kd") {
      textured = true;
    }
  }
  keep();
}

}  // namespace

MeshFile read_obj(const std::string& path) {
  detail::TextLines in(path);
  std::vector<Vec3> positions;
  // Vertex colours after the coordinates, as fractions (MeshLab's extension); kept only if
  // every vertex has one.
  std::vector<Colour> colours;
  bool coloured = true;
  std::vector<std::array<Index, 3>> triangles;
  std::vector<std::uint8_t> faux;
  // Face colours from the materials' diffuse colours; kept only if every face has one.
  std::unordered_map<std::string, Colour> materials;
  std::optional<Colour> material;
  std::vector<Colour> face_colours;
  bool face_coloured = true;
  bool textured = false;
  std::vector<Index> corners;
  const auto n = [&positions] { return static_cast<long long>(positions.size()); };
  while (in.next()) {
    const std::string_view kw = in[0];
    if (kw == "v") {
      positions.push_back(in.position(1));
      Colour c;
      if (coloured && (coloured = in.colour(4, true, c))) colours.push_back(c);
    } else if (kw == "f" || kw == "q") {
      // Corners count from 1, or back from -1, over the vertices above the line; the
      // zero-based QOBJ variant's "q" quads count from 0.
      const bool qobj = kw == "q";
      corners.clear();
      for (std::size_t i = 1; i < in.size(); ++i) {
        const long long c = in.whole_number(i, "a vertex number (a face corner)", in[i].find('/'));
        const long long index = qobj ? c : c > 0 ? c - 1 : n() + c;
        if ((!qobj && c == 0) || index < 0 || index >= n())
          in.fail("face corner " + std::to_string(c) + " names no vertex (only " + std::to_string(n()) +
                  " come before it)");
        corners.push_back(Index(index));
      }
      if (qobj && corners.size() != 4) in.fail("a QOBJ quad ('q') with " + std::to_string(corners.size()) + " corners");
      if (corners.size() < 3) continue;  // fewer than three corners: no face
      detail::fan(corners.data(), corners.size(), triangles, faux);
      if (face_coloured && (face_coloured = material.has_value())) face_colours.resize(triangles.size(), *material);
    } else if (kw == "vt") {
      textured = true;
    } else if (kw == "mtllib") {
      // Material files are named relative to the OBJ's folder, several to a line, or one
      // whose name has spaces (as we and MeshLab write an OBJ's named so).
      const std::filesystem::path folder = std::filesystem::path(path).parent_path();
      for (std::size_t i = 1; i < in.size(); ++i) read_materials((folder / std::string(in[i])).string(), materials);
      if (in.size() > 2) read_materials((folder / name_on(in)).string(), materials);
    } else if (kw == "usemtl") {
      const auto it = materials.find(name_on(in));
      material = it != materials.end() ? std::optional<Colour>(it->second) : std::nullopt;
    }
  }
  if (!face_coloured) face_colours.clear();
  MeshFile out = pair_faux_triangles(std::move(positions), std::move(triangles), faux, face_colours);
  if (coloured) out.colours = std::move(colours);
  out.texture_coordinates = textured;
  return out;
}

}  // namespace qs
