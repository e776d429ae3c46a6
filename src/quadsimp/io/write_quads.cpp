// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
//
// Quads are written here, not by vcglib: its OBJ writer printed coordinates with 16 fixed
// decimals (a mesh in units of 1e-9 kept 7 significant digits), and its PLY and OFF
// writers with 16 significant digits, one short of what reads back to the same double;
// its binary PLY writer wrote every polygon as a triangle. PLY is written in binary
// (doubles, exact, half the size of text), OFF and OBJ with each coordinate in the
// shortest form that reads back to the same double.
#include <charconv>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "quadsimp/io/atomic_file.h"
#include "quadsimp/io/images.h"
#include "quadsimp/io/mesh_io.h"
#include "quadsimp/util/errors.h"

namespace qs {
namespace {

// A coordinate in the shortest form that reads back to the same double (or float).
template <class Real>
std::ostream& put_number(std::ostream& out, Real x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return out << std::string_view(buf, std::size_t(r.ptr - buf));
}

// A colour channel as the fraction OBJ and MTL files write.
std::string fraction(std::uint8_t channel) { return std::to_string(channel / 255.0); }

// Values appended to `data` in little-endian order, whatever the host's.
template <class T>
void put_le(std::string& data, T value) {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  const std::uint16_t probe = 1;
  const bool little = *reinterpret_cast<const unsigned char*>(&probe) == 1;
  for (std::size_t i = 0; i < sizeof(T); ++i) data += char(bytes[little ? i : sizeof(T) - 1 - i]);
}

const char* const kColourProperties = "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                                      "property uchar alpha\n";

// PLY: quads as polygons; with a texture, as MeshLab writes a textured quad layer (it
// reads no texture coordinates on a polygon): each quad two triangles split at corners
// 0-2, as the texture was baked, their shared edge marked faux in the face flags, each
// with its corners' coordinates, the image named by a TextureFile comment.
void write_ply(const std::string& path, const QuadMesh& q, const QuadColours& colours, const QuadTexture& texture,
               const std::string& image) {
  const bool textured = !texture.empty();
  std::ofstream out(path, std::ios::binary);
  std::string data = "ply\nformat binary_little_endian 1.0\ncomment quadsimp\n";
  if (textured) data += "comment TextureFile " + image + "\n";
  data += "element vertex " + std::to_string(q.n_vertices()) +
          "\nproperty double x\nproperty double y\nproperty double z\n";
  if (!colours.vertices.empty()) data += kColourProperties;
  data += "element face " + std::to_string((textured ? 2 : 1) * q.n_faces()) +
          "\nproperty list uchar int vertex_indices\n";
  if (textured) data += "property int flags\nproperty list uchar float texcoord\n";
  if (!colours.faces.empty()) data += kColourProperties;
  data += "end_header\n";
  // Written a megabyte at a time: a copy of the whole file in memory would double a large
  // result's footprint.
  constexpr std::size_t kChunk = 1 << 20;
  const auto spill = [&](std::size_t above) {
    if (data.size() <= above) return;
    out.write(data.data(), std::streamsize(data.size()));
    data.clear();
  };
  for (Index v = 0; v < q.vertex_capacity(); ++v) {
    if (!q.is_vertex_live(v)) continue;
    for (int k = 0; k < 3; ++k) put_le(data, q.position(v)[k]);
    if (!colours.vertices.empty()) data.append(reinterpret_cast<const char*>(colours.vertices[v].data()), 4);
    spill(kChunk);
  }
  const std::vector<Index> id = q.live_vertex_ids();
  // vcglib's faux bit of edge k (corner k to k+1) of a triangle.
  const auto faux = [](int k) { return std::int32_t(0x40000 << k); };
  for (Index f = 0; f < q.face_capacity(); ++f) {
    if (!q.is_face_live(f)) continue;
    const auto put_colour = [&] {
      if (!colours.faces.empty()) data.append(reinterpret_cast<const char*>(colours.faces[f].data()), 4);
    };
    if (!textured) {
      data += char(4);
      for (Index k = 0; k < 4; ++k) put_le(data, std::int32_t(id[q.vertex(f, k)]));
      put_colour();
    } else {
      const int halves[2][3] = {{0, 1, 2}, {0, 2, 3}};
      for (int half = 0; half < 2; ++half) {
        data += char(3);
        for (const int k : halves[half]) put_le(data, std::int32_t(id[q.vertex(f, Index(k))]));
        put_le(data, faux(half == 0 ? 2 : 0));  // the diagonal: 2 -> 0 in the first, 0 -> 2 in the second
        data += char(6);
        for (const int k : halves[half])
          for (const float x : texture.corners[f][std::size_t(k)]) put_le(data, x);
        put_colour();
      }
    }
    spill(kChunk);
  }
  spill(0);
  if (!out.flush()) fail_file(path, "cannot be written");
}

// OFF: COFF's vertex colours after the coordinates, a face's after its corners (bytes,
// alpha included: MeshLab reads both).
void write_off(const std::string& path, const QuadMesh& q, const QuadColours& colours) {
  std::ofstream out(path, std::ios::binary);
  const auto put_colour = [&out](const Colour& c) {
    for (const std::uint8_t channel : c) out << ' ' << unsigned(channel);
  };
  out << (colours.vertices.empty() ? "OFF\n" : "COFF\n") << q.n_vertices() << ' ' << q.n_faces() << " 0\n";
  for (Index v = 0; v < q.vertex_capacity(); ++v) {
    if (!q.is_vertex_live(v)) continue;
    for (int k = 0; k < 3; ++k) put_number(out << (k ? " " : ""), q.position(v)[k]);
    if (!colours.vertices.empty()) put_colour(colours.vertices[v]);
    out << '\n';
  }
  const std::vector<Index> id = q.live_vertex_ids();
  for (Index f = 0; f < q.face_capacity(); ++f) {
    if (!q.is_face_live(f)) continue;
    out << '4';
    for (Index k = 0; k < 4; ++k) out << ' ' << id[q.vertex(f, k)];
    if (!colours.faces.empty()) put_colour(colours.faces[f]);
    out << '\n';
  }
  if (!out.flush()) fail_file(path, "cannot be written");
}

// OBJ, with vertex colours after the coordinates as fractions (the extension MeshLab reads
// and writes), and face colours as materials, one per colour, in the file `mtl` (named as
// it is, beside the OBJ), as MeshLab writes them; a texture's coordinates four to a face.
void write_obj(const std::string& path, const QuadMesh& q, const QuadColours& colours, const QuadTexture& texture,
               const std::string& mtl, const std::map<Colour, int>& materials) {
  std::ofstream out(path, std::ios::binary);
  out << "# quadsimp: " << q.n_vertices() << " vertices, " << q.n_faces() << " quads\n";
  if (!materials.empty()) out << "mtllib " << mtl << '\n';
  for (Index v = 0; v < q.vertex_capacity(); ++v) {
    if (!q.is_vertex_live(v)) continue;
    out << 'v';
    for (int k = 0; k < 3; ++k) put_number(out << ' ', q.position(v)[k]);
    if (!colours.vertices.empty())
      for (std::size_t k = 0; k < 3; ++k) out << ' ' << fraction(colours.vertices[v][k]);
    out << '\n';
  }
  const bool textured = !texture.empty();
  for (Index f = 0; f < q.face_capacity() && textured; ++f)
    if (q.is_face_live(f))
      for (const TexCoord& c : texture.corners[f]) put_number(put_number(out << "vt ", c[0]) << ' ', c[1]) << '\n';
  const std::vector<Index> id = q.live_vertex_ids();
  int material = -1;
  std::size_t corner = 0;
  for (Index f = 0; f < q.face_capacity(); ++f) {
    if (!q.is_face_live(f)) continue;
    const int m = materials.empty() ? -1 : colours.faces.empty() ? 0 : materials.at(colours.faces[f]);
    if (m != material) out << "usemtl material_" << (material = m) << '\n';
    out << 'f';
    for (Index k = 0; k < 4; ++k) {
      out << ' ' << id[q.vertex(f, k)] + 1;  // OBJ counts from 1
      if (textured) out << '/' << ++corner;
    }
    out << '\n';
  }
  if (!out.flush()) fail_file(path, "cannot be written");
}

// The materials of write_obj(): one per face colour, numbered in the order they come, or
// a white one for a texture without them.
std::map<Colour, int> materials_of(const QuadMesh& q, const std::vector<Colour>& face_colours, bool textured) {
  std::map<Colour, int> materials;
  for (Index f = 0; f < q.face_capacity() && !face_colours.empty(); ++f)
    if (q.is_face_live(f)) materials.emplace(face_colours[f], int(materials.size()));
  if (materials.empty() && textured) materials.emplace(Colour{255, 255, 255, 255}, 0);
  return materials;
}

void write_mtl(const std::string& path, const std::map<Colour, int>& materials, const std::string& image) {
  std::vector<const Colour*> by_number(materials.size());
  for (const auto& [colour, k] : materials) by_number[std::size_t(k)] = &colour;
  std::ofstream out(path, std::ios::binary);
  out << "# quadsimp: the quads' face colours" << (image.empty() ? "" : " and texture") << '\n';
  for (std::size_t k = 0; k < by_number.size(); ++k) {
    const Colour& c = *by_number[k];
    out << "newmtl material_" << k << "\nKd " << fraction(c[0]) << ' ' << fraction(c[1]) << ' ' << fraction(c[2])
        << "\nd " << fraction(c[3]) << '\n';
    if (!image.empty()) out << "map_Kd " << image << '\n';
  }
  if (!out.flush()) fail_file(path, "cannot be written");
}

}  // namespace

// The name keeps ASCII letters, digits, '.', '-' and '_' only: MeshLab's OBJ reader takes
// a map_Kd of one word, and its PLY reader drops spaces and bytes past '|' from a
// TextureFile, so it found no texture beside "my scan.obj" or "scène.ply".
std::string texture_path_of(const std::string& path) {
  const std::filesystem::path p(path);
  std::string name;
  for (const char c : p.stem().string()) {
    const auto byte = static_cast<unsigned char>(c);
    if ((byte & 0xC0) == 0x80) continue;  // UTF-8's continuation bytes: a character gives one '_'
    const bool kept = (byte >= '0' && byte <= '9') || (byte >= 'A' && byte <= 'Z') || (byte >= 'a' && byte <= 'z') ||
                      byte == '.' || byte == '-' || byte == '_';
    name += kept ? c : '_';
  }
  return (p.parent_path() / (name + "_texture.png")).string();
}

void write_quad_mesh(const std::string& path, const QuadMesh& mesh, const QuadColours& colours,
                     const QuadTexture& texture) {
  const std::string ext = extension_of(path);
  if (ext != "ply" && ext != "obj" && ext != "off")
    fail_file(path, "cannot write '" + ext + "' (quads are written as .ply, .obj or .off)");
  if (!colours.vertices.empty() && colours.vertices.size() != mesh.vertex_capacity())
    throw std::invalid_argument("write_quad_mesh: one colour per vertex id expected");
  if (!colours.faces.empty() && colours.faces.size() != mesh.face_capacity())
    throw std::invalid_argument("write_quad_mesh: one colour per face id expected");
  const bool textured = !texture.empty();
  if (textured && (ext == "off" || texture.corners.size() != mesh.face_capacity()))
    throw std::invalid_argument("write_quad_mesh: a texture goes to .obj or .ply, with coordinates per face id");
  // An OBJ's face colours and texture go to a material file and an image beside it,
  // written first, and removed if the OBJ cannot be.
  const std::map<Colour, int> materials =
      ext == "obj" ? materials_of(mesh, colours.faces, textured) : std::map<Colour, int>();
  const std::string mtl = path + ".mtl", image = textured ? texture_path_of(path) : std::string();
  const auto remove_beside = [&] {
    std::error_code ec;
    if (!materials.empty()) std::filesystem::remove(mtl, ec);
    if (textured) std::filesystem::remove(image, ec);
  };
  try {
    if (textured) detail::write_atomically(image, [&](const std::string& tmp) { write_png(tmp, texture.image); });
    if (!materials.empty())
      detail::write_atomically(mtl, [&](const std::string& tmp) {
        write_mtl(tmp, materials, textured ? std::filesystem::path(image).filename().string() : std::string());
      });
    detail::write_atomically(path, [&](const std::string& tmp) {
      if (ext == "ply")
        write_ply(tmp, mesh, colours, texture, std::filesystem::path(image).filename().string());
      else if (ext == "obj")
        write_obj(tmp, mesh, colours, texture, std::filesystem::path(mtl).filename().string(), materials);
      else
        write_off(tmp, mesh, colours);
    });
  } catch (...) {
    remove_beside();
    throw;
  }
}

}  // namespace qs
