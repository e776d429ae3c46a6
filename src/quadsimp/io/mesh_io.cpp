// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
//
// The only file that sees vcglib's I/O: it reads STL, writes the fitmaps' PLY, and
// searches the input for the quads' colours. PLY (the old Stanford files' triangle strips
// and range grids too), OBJ and OFF are read by read_ply.cpp, read_obj.cpp and
// read_off.cpp, and quads written by write_quads.cpp (why is said there). Those readers
// give triangles with "faux" flags on the inner edges of polygons, the way vcglib and
// MeshLab store quads (MeshLab writes the flags to PLY with -m ff), and the triangles
// joined by a faux edge are regrouped into quads.
#include "quadsimp/io/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include <vcg/complex/complex.h>
#include <wrap/io_trimesh/export_ply.h>
#include <wrap/io_trimesh/import_stl.h>

#include "quadsimp/io/atomic_file.h"
#include "quadsimp/io/surface_colours.h"
#include "quadsimp/io/text_readers.h"
#include "quadsimp/util/errors.h"

namespace qs {
namespace {

class TVertex;
class TFace;
struct TTypes : vcg::UsedTypes<vcg::Use<TVertex>::AsVertexType, vcg::Use<TFace>::AsFaceType> {};
class TVertex : public vcg::Vertex<TTypes, vcg::vertex::Coord3d, vcg::vertex::Color4b,
                                   vcg::vertex::BitFlags> {};
class TFace : public vcg::Face<TTypes, vcg::face::VertexRef, vcg::face::Normal3d, vcg::face::Color4b,
                                vcg::face::Mark, vcg::face::BitFlags> {};
// vcglib's mesh destructor leaves attributes (the importers add some) allocated.
class TMesh : public vcg::tri::TriMesh<std::vector<TVertex>, std::vector<TFace>> {
 public:
  ~TMesh() override { ClearAttributes(); }
};

void check_readable(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail_file(path, "no such file");
  std::ifstream probe(path, std::ios::binary);
  if (!probe) fail_file(path, "cannot be opened for reading");
  if (probe.peek() == std::ifstream::traits_type::eof()) fail_file(path, "the file is empty");
}

// STL through vcglib's importer, which makes each facet three vertices of its own: a
// triangle soup, with no deleted elements or faux edges (cleaning welds it). A file it
// takes for ASCII but holds no line of facets (all on one line, a truncated binary file
// of zeros) gives none, and with scripts/patches/vcglib-stl-first-line.patch it no longer
// reads such a file for ever.
MeshFile read_stl(const std::string& path) {
  TMesh m;
  int mask = 0;
  const int err = vcg::tri::io::ImporterSTL<TMesh>::Open(m, path.c_str(), mask);
  if (err != 0)
    fail_file(path, std::string("unreadable STL (") + vcg::tri::io::ImporterSTL<TMesh>::ErrorMsg(err) + ")");
  if (m.face.empty())
    fail_file(path, "unreadable STL (no facet read: neither a binary STL of the size its facet count gives, nor lines "
                    "of text)");
  MeshFile out;
  out.positions.reserve(m.vert.size());
  for (const auto& v : m.vert) out.positions.emplace_back(v.cP()[0], v.cP()[1], v.cP()[2]);
  out.triangles.reserve(m.face.size());
  for (const auto& f : m.face) {
    const auto id = [&](int k) { return Index(vcg::tri::Index(m, f.cV(k))); };
    out.triangles.push_back({id(0), id(1), id(2)});
  }
  return out;
}

// t as vcglib's triangle mesh (same ids), for its writer and its closest-point search.
void fill_tri_mesh(const TriMesh& t, TMesh& m) {
  auto vi = vcg::tri::Allocator<TMesh>::AddVertices(m, t.positions.size());
  for (const Vec3& p : t.positions) (vi++)->P() = vcg::Point3d(p.x(), p.y(), p.z());
  auto fi = vcg::tri::Allocator<TMesh>::AddFaces(m, t.faces.size());
  for (const auto& f : t.faces) {
    for (int k = 0; k < 3; ++k) fi->V(k) = &m.vert[f[std::size_t(k)]];
    ++fi;
  }
}

vcg::Color4b vcg_colour(const Colour& c) { return vcg::Color4b(c[0], c[1], c[2], c[3]); }

}  // namespace

std::string extension_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  if (!ext.empty()) ext.erase(0, 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

MeshFile read_mesh(const std::string& path) {
  check_readable(path);
  MeshFile file;
  const std::string ext = extension_of(path);
  if (ext == "off") {
    file = read_off(path);
  } else if (ext == "obj") {
    file = read_obj(path);
  } else if (ext == "ply") {
    file = read_ply(path);
  } else if (ext == "stl") {
    file = read_stl(path);
  } else {
    fail_file(path, "unknown format '" + ext + "' (expected .ply, .obj, .off or .stl)");
  }
  if (file.positions.empty()) fail_file(path, "the file holds no vertices (empty mesh)");
  return file;
}

QuadColours colours_of_quads(const MeshFile& from, const QuadMesh& quads) {
  const std::vector<Colour> face_colours = triangle_colours_of(from);
  const bool vertices = !from.colours.empty(), faces = !face_colours.empty();
  if (!vertices && !faces) return {};
  TMesh m;
  fill_tri_mesh(triangles_of(from), m);  // triangles_of() keeps the positions' order
  for (std::size_t i = 0; vertices && i < from.colours.size(); ++i) m.vert[i].C() = vcg_colour(from.colours[i]);
  for (std::size_t i = 0; i < face_colours.size(); ++i) m.face[i].C() = vcg_colour(face_colours[i]);
  SurfaceColours<TMesh> source(m, vertices, faces, SurfaceColours<TMesh>::Use::in_place);
  const auto point = [](const Vec3& p) { return vcg::Point3d(p.x(), p.y(), p.z()); };
  const auto colour = [](const vcg::Color4b& c) { return Colour{c[0], c[1], c[2], c[3]}; };
  QuadColours out;
  if (vertices) {
    out.vertices.assign(quads.vertex_capacity(), Colour{0, 0, 0, 255});
    for (Index v = 0; v < quads.vertex_capacity(); ++v)
      if (quads.is_vertex_live(v)) out.vertices[v] = colour(source.vertex_colour(point(quads.position(v))));
  }
  if (faces) {
    out.faces.assign(quads.face_capacity(), Colour{0, 0, 0, 255});
    for (Index f = 0; f < quads.face_capacity(); ++f)
      if (quads.is_face_live(f)) out.faces[f] = colour(source.face_colour(point(quads.face_centroid(f))));
  }
  return out;
}

void write_tri_mesh_ply(const std::string& path, const TriMesh& mesh,
                        const std::vector<VertexField>& fields) {
  if (extension_of(path) != "ply") fail_file(path, "fields are written as .ply only");
  for (const auto& f : fields)
    if (f.values.size() != mesh.positions.size())
      throw std::invalid_argument("write_tri_mesh_ply: field '" + f.name + "' has the wrong size");
  TMesh tm;
  fill_tri_mesh(mesh, tm);
  // Colour ramp of the first field (5th to 95th percentile), so that MeshLab shows
  // it without any setup.
  if (!fields.empty()) {
    std::vector<float> sorted = fields[0].values;
    std::sort(sorted.begin(), sorted.end());
    const float lo = sorted[sorted.size() / 20], hi = sorted[sorted.size() * 19 / 20];
    for (std::size_t i = 0; i < sorted.size(); ++i) {
      const float t = hi > lo ? std::clamp((fields[0].values[i] - lo) / (hi - lo), 0.f, 1.f) : 0.f;
      tm.vert[i].C().SetColorRamp(0.f, 1.f, t);
    }
  }
  vcg::tri::io::PlyInfo info;
  info.mask = fields.empty() ? int(vcg::tri::io::Mask::IOM_NONE) : int(vcg::tri::io::Mask::IOM_VERTCOLOR);
  for (const auto& f : fields) {
    auto h = vcg::tri::Allocator<TMesh>::AddPerVertexAttribute<float>(tm, f.name);
    for (std::size_t i = 0; i < f.values.size(); ++i) h[i] = f.values[i];
    info.AddPerVertexFloatAttribute(f.name);
  }
  detail::write_atomically(path, [&](const std::string& tmp) {
    const int err = vcg::tri::io::ExporterPLY<TMesh>::Save(tm, tmp.c_str(), true, info);
    if (err != 0) fail_file(path, "cannot be written (vcglib error " + std::to_string(err) + ")");
  });
}

}  // namespace qs
