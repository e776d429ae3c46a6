// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
//
// OBJ is read here, not by vcglib: its reader took a coordinate that is not a number for
// 0, followed face corners naming no vertex into memory it did not own (a crash),
// dropped a triangle naming a later vertex without a word, and read a comment after a
// face's corners as more corners. It also took 2.7 s on a 1.1M-triangle file.
#include <algorithm>
#include <filesystem>
#include <iterator>
#include <map>
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

// An .mtl file's material: its diffuse colour (Kd, white without one, as MeshLab takes
// it; d as alpha, or Tr as 1 - alpha: MeshLab writes Tr), and its diffuse texture (map_Kd),
// whose image colours its faces that have texture coordinates.
struct Material {
  Colour colour{255, 255, 255, 255};
  bool diffuse = false;  // Kd given
  std::string image;     // a path from here, or none; the file may be missing (the bake says so)
};

// map_Kd's image: the rest of the line, which may hold spaces, if that names a file; else
// its last field, after any options ("-s 1 1 1 wall.png"). Named relative to the material
// file's folder, with Windows' separators too.
std::string image_on(const detail::TextLines& line, const std::filesystem::path& folder) {
  std::error_code ec;
  const std::string whole = detail::file_beside(folder, name_on(line));
  if (std::filesystem::is_regular_file(whole, ec)) return whole;
  return detail::file_beside(folder, std::string(line[line.size() - 1]));
}

// The materials of an .mtl file, into `materials` by name, as MeshLab reads them. A file
// that cannot be read adds nothing (its faces then have no colour, and the mesh none).
void read_materials(const std::string& path, std::unordered_map<std::string, Material>& materials) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return;
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  detail::TextLines in(path);
  std::string name;
  Material material;
  const auto keep = [&] {
    if (!name.empty()) materials[name] = material;
  };
  while (in.next()) {
    const std::string_view kw = in[0];
    if (kw == "newmtl") {
      keep();
      name = name_on(in), material = Material();
    } else if (kw == "Kd") {
      Colour c;
      if ((material.diffuse = in.colour(1, true, c))) std::copy_n(c.begin(), 3, material.colour.begin());
    } else if ((kw == "d" || kw == "Tr") && in.size() == 2) {
      double x;
      if (parse_number(in[1], x)) material.colour[3] = colour_byte(255 * (kw == "d" ? x : 1 - x));
    } else if (kw == "map_Kd" && in.size() > 1) {
      material.image = image_on(in, folder);
    }
  }
  keep();
}

// Reads a face corner's texture coordinate number ("v/vt", "v/vt/vn"): false where it has
// none or names none of the `n` above it.
bool texture_corner(std::string_view corner, std::size_t n, std::size_t& index) {
  const std::size_t slash = corner.find('/');
  if (slash == std::string_view::npos) return false;
  const std::string_view field = corner.substr(slash + 1, corner.find('/', slash + 1) - slash - 1);
  long long c;
  if (field.empty() || !parse_number(field, c)) return false;
  const long long i = c > 0 ? c - 1 : static_cast<long long>(n) + c;
  if (c == 0 || i < 0 || i >= static_cast<long long>(n)) return false;
  index = std::size_t(i);
  return true;
}

// What MeshLab (vcglib's OBJ reader) gives a face before any material.
constexpr Colour kMeshLabGrey{192, 192, 192, 255};

// The statements of the OBJ format (geometry, grouping, display and rendering
// attributes), and QOBJ's quads: lines that begin with anything else are damage.
bool is_obj_statement(std::string_view kw) {
  static constexpr std::string_view kStatements[] = {
      "bevel",     "bmat", "c_interp", "con",    "cstype", "ctech",      "curv",   "curv2", "d_interp", "deg",
      "end",       "f",    "g",        "hole",   "l",      "lod",        "maplib", "mg",    "mtllib",   "o",
      "p",         "parm", "q",        "s",      "scrv",   "shadow_obj", "sp",     "stech", "step",     "surf",
      "trace_obj", "trim", "usemap",   "usemtl", "v",      "vn",         "vp",     "vt"};
  return std::find(std::begin(kStatements), std::end(kStatements), kw) != std::end(kStatements);
}

}  // namespace

MeshFile read_obj(const std::string& path) {
  detail::TextLines in(path, true);
  std::vector<Vec3> positions;
  // Vertex colours after the coordinates, as fractions (MeshLab's extension); kept only if
  // every vertex has one.
  std::vector<Colour> colours;
  bool coloured = true;
  std::vector<std::array<Index, 3>> triangles;
  std::vector<std::uint8_t> faux;
  // Face colours from the materials' diffuse colours, as MeshLab reads them: a face before
  // any material takes its light grey, and one after a material no file defines the colour
  // before it. Kept if some face has a material's colour and none is textured. Dropping
  // them all where some faces had no material lost a model's colours with no word said.
  std::unordered_map<std::string, Material> materials;
  const Material* material = nullptr;
  Colour colour = kMeshLabGrey;
  std::vector<Colour> face_colours;
  bool from_material = false;
  // The texture: a face is textured where every corner has coordinates and its material an
  // image. Kept if some face is, with the others' colours baked in beside it: dropping it
  // where one material had none lost a model's texture with only a note.
  bool textured = false, coordinates_read = true, some_textured = false;
  std::vector<TexCoord> coords;
  FileTexture texture;
  std::map<std::string, int> image_number;
  std::vector<Index> corners;
  std::vector<TexCoord> corner_coords;
  Index skipped = 0;
  std::string first_skipped;
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
      corner_coords.clear();
      bool has_coords = true;
      for (std::size_t i = 1; i < in.size(); ++i) {
        const long long c = in.whole_number(i, "a vertex number (a face corner)", in[i].find('/'));
        const long long index = qobj ? c : c > 0 ? c - 1 : n() + c;
        if ((!qobj && c == 0) || index < 0 || index >= n())
          in.fail("face corner " + std::to_string(c) + " names no vertex (only " + std::to_string(n()) +
                  " come before it)");
        corners.push_back(Index(index));
        std::size_t t;
        has_coords = has_coords && texture_corner(in[i], coords.size(), t);
        if (has_coords) corner_coords.push_back(coords[t]);
      }
      if (qobj && corners.size() != 4) in.fail("a QOBJ quad ('q') with " + std::to_string(corners.size()) + " corners");
      if (corners.size() < 3) continue;  // fewer than three corners: no face
      int image = -1;
      if (has_coords && material && !material->image.empty())
        image = image_number.emplace(material->image, int(image_number.size())).first->second;
      from_material |= image < 0 && material && material->diffuse;
      if (image >= 0 && !some_textured) {  // the faces before the first textured one, coloured
        texture.triangles = triangles;
        texture.coords.assign(triangles.size(), {});
        texture.image.assign(triangles.size(), -1);
        texture.colours = face_colours;
      }
      some_textured |= image >= 0;
      detail::fan(corners.data(), corners.size(), triangles, faux);
      face_colours.resize(triangles.size(), colour);
      if (some_textured) {
        corner_coords.resize(corners.size());  // a face without: zeros, unread
        detail::fan(corners.data(), corner_coords.data(), corners.size(), image, texture);
        texture.colours.resize(texture.triangles.size(), colour);
      }
    } else if (kw == "vt") {
      textured = true;
      // Coordinates that are not numbers leave the texture out, not the mesh.
      double u = 0, v = 0;
      coordinates_read =
          coordinates_read && in.size() > 1 && parse_number(in[1], u) && (in.size() < 3 || parse_number(in[2], v));
      coords.push_back({float(u), float(v)});
    } else if (kw == "mtllib") {
      // Material files are named relative to the OBJ's folder, several to a line, or one
      // whose name has spaces (as we and MeshLab write an OBJ's named so).
      const std::filesystem::path folder = std::filesystem::path(path).parent_path();
      for (std::size_t i = 1; i < in.size(); ++i) read_materials((folder / std::string(in[i])).string(), materials);
      if (in.size() > 2) read_materials((folder / name_on(in)).string(), materials);
    } else if (kw == "usemtl") {
      const auto it = materials.find(name_on(in));
      material = it != materials.end() ? &it->second : nullptr;
      if (material) colour = material->colour;
    } else if (!is_obj_statement(kw) && !skipped++) {
      first_skipped = "line " + std::to_string(in.line_number()) + ", " + detail::quoted(kw);
    }
  }
  const bool keep_texture = coordinates_read && some_textured;
  if (keep_texture || !from_material) face_colours.clear();
  MeshFile out = pair_faux_triangles(std::move(positions), std::move(triangles), faux, face_colours);
  if (coloured) out.colours = std::move(colours);
  out.texture_coordinates = textured;
  out.skipped_lines = skipped;
  out.first_skipped = std::move(first_skipped);
  if (keep_texture) {
    texture.images.resize(image_number.size());
    for (const auto& [path, k] : image_number) texture.images[std::size_t(k)] = path;
    out.texture = kept_texture(std::move(texture));
  }
  return out;
}

}  // namespace qs
