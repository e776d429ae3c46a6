// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
//
// The only file that sees vcglib's I/O: it reads STL, and writes PLY and OFF. PLY (the
// old Stanford files' triangle strips and range grids too), OBJ and OFF are read by
// read_ply.cpp, read_obj.cpp and read_off.cpp (why is said there). Every reader gives
// triangles with "faux" flags on the inner edges of polygons, the way vcglib and MeshLab
// store quads (MeshLab writes the flags to PLY with -m ff), and the triangles joined by
// a faux edge are regrouped into quads.
#include "quadsimp/io/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include <vcg/complex/complex.h>
#include <wrap/io_trimesh/export_off.h>
#include <wrap/io_trimesh/export_ply.h>
#include <wrap/io_trimesh/import_stl.h>

#include "quadsimp/io/text_readers.h"
#include "quadsimp/io/surface_colours.h"
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

class PVertex;
class PFace;
struct PTypes : vcg::UsedTypes<vcg::Use<PVertex>::AsVertexType, vcg::Use<PFace>::AsFaceType> {};
class PVertex : public vcg::Vertex<PTypes, vcg::vertex::Coord3d, vcg::vertex::Color4b, vcg::vertex::BitFlags> {};
class PFace : public vcg::Face<PTypes, vcg::face::PolyInfo, vcg::face::PFVAdj, vcg::face::Color4b,
                                vcg::face::BitFlags> {};
class PMesh : public vcg::tri::TriMesh<std::vector<PVertex>, std::vector<PFace>> {
 public:
  ~PMesh() override { ClearAttributes(); }
};

[[noreturn]] void fail(const std::string& path, const std::string& why) {
  throw InvalidInput(path + ": " + why);
}

void check_readable(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail(path, "no such file");
  std::ifstream probe(path, std::ios::binary);
  if (!probe) fail(path, "cannot be opened for reading");
  if (probe.peek() == std::ifstream::traits_type::eof()) fail(path, "the file is empty");
}

void load_vcg(const std::string& path, TMesh& m) {
  const std::string ext = extension_of(path);
  if (ext == "stl") {
    int mask = 0;
    const int err = vcg::tri::io::ImporterSTL<TMesh>::Open(m, path.c_str(), mask);
    if (err != 0) fail(path, std::string("unreadable STL (") + vcg::tri::io::ImporterSTL<TMesh>::ErrorMsg(err) + ")");
  } else {
    fail(path, "unknown format '" + ext + "' (expected .ply, .obj, .off or .stl)");
  }
}

// Triangles with their faux-edge bits, then quads rebuilt from the faux pairs.
MeshFile regroup(const std::string& path, const TMesh& m) {
  std::vector<Vec3> positions;
  positions.reserve(m.vert.size());
  std::vector<int> vid(m.vert.size(), -1);
  for (std::size_t i = 0; i < m.vert.size(); ++i) {
    if (m.vert[i].IsD()) continue;
    vid[i] = int(positions.size());
    const auto& p = m.vert[i].cP();
    positions.emplace_back(p[0], p[1], p[2]);
  }
  std::vector<std::array<Index, 3>> tris;
  std::vector<std::uint8_t> faux;
  for (const auto& f : m.face) {
    if (f.IsD()) continue;
    std::array<Index, 3> t;
    for (int k = 0; k < 3; ++k) {
      // Unpatched, vcglib's PLY reader passes a polygon's corner that names no vertex
      // (scripts/patches): refused here rather than followed, whatever vcglib did.
      const std::size_t v = vcg::tri::Index(m, f.cV(k));
      if (v >= m.vert.size() || vid[v] < 0) fail(path, "a face refers to a vertex that does not exist");
      t[k] = Index(vid[v]);
    }
    tris.push_back(t);
    faux.push_back(std::uint8_t(unsigned(f.IsF(0)) | unsigned(f.IsF(1)) << 1 | unsigned(f.IsF(2)) << 2));
  }
  return pair_faux_triangles(std::move(positions), std::move(tris), faux);
}

// Writes through a temporary file beside the target so that readers never see a
// partial file and a failed run leaves nothing behind.
template <class WriteFn>
void write_atomically(const std::string& path, WriteFn&& write) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  fs::path tmp = target;
  tmp += ".part";
  tmp.replace_filename("." + tmp.filename().string());
  try {
    write(tmp.string());
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    fail(path, "cannot be written (" + ec.message() + ")");
  }
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

// The live vertices and faces of q (tombstones skipped, ids renumbered in order), with
// their colours if there are any (indexed as q's vertices and faces).
void fill_poly_mesh(const QuadMesh& q, const QuadColours& colours, PMesh& pm) {
  std::vector<Index> id(q.vertex_capacity(), kNone);
  auto vi = vcg::tri::Allocator<PMesh>::AddVertices(pm, q.n_vertices());
  Index n = 0;
  for (Index v = 0; v < q.vertex_capacity(); ++v) {
    if (!q.is_vertex_live(v)) continue;
    id[v] = n++;
    const Vec3& p = q.position(v);
    vi->P() = vcg::Point3d(p.x(), p.y(), p.z());
    if (!colours.vertices.empty()) vi->C() = vcg_colour(colours.vertices[v]);
    ++vi;
  }
  auto fi = vcg::tri::Allocator<PMesh>::AddFaces(pm, q.n_faces());
  for (Index f = 0; f < q.face_capacity(); ++f) {
    if (!q.is_face_live(f)) continue;
    fi->Alloc(4);
    for (Index k = 0; k < 4; ++k) fi->V(k) = &pm.vert[id[q.vertex(f, k)]];
    if (!colours.faces.empty()) fi->C() = vcg_colour(colours.faces[f]);
    ++fi;
  }
}

// A colour channel as the fraction OBJ and MTL files write.
std::string fraction(std::uint8_t channel) { return std::to_string(channel / 255.0); }

// OBJ is written here: vcglib's writer printed coordinates with 16 fixed decimals (a mesh
// in units of 1e-9 kept 7 significant digits), headed the file "Generated by Meshlab" and
// named the temporary file in it. Coordinates are written in the shortest form that reads
// back to the same double. Face colours go to materials, one per colour, in the file
// `mtl` (named as it is, beside the OBJ), as MeshLab writes them.
void write_obj(const std::string& path, const QuadMesh& q, const QuadColours& colours, const std::string& mtl,
               const std::map<Colour, int>& materials) {
  std::ofstream out(path, std::ios::binary);
  out << "# quadsimp: " << q.n_vertices() << " vertices, " << q.n_faces() << " quads\n";
  if (!materials.empty()) out << "mtllib " << mtl << '\n';
  std::vector<Index> id(q.vertex_capacity(), kNone);
  Index n = 0;
  char buf[32];
  for (Index v = 0; v < q.vertex_capacity(); ++v) {
    if (!q.is_vertex_live(v)) continue;
    id[v] = ++n;  // OBJ counts from 1
    out << 'v';
    for (int k = 0; k < 3; ++k) {
      const auto r = std::to_chars(buf, buf + sizeof buf, q.position(v)[k]);
      out << ' ' << std::string_view(buf, std::size_t(r.ptr - buf));
    }
    // Colours after the coordinates, as fractions: the extension MeshLab reads and writes.
    if (!colours.vertices.empty())
      for (std::size_t k = 0; k < 3; ++k) out << ' ' << fraction(colours.vertices[v][k]);
    out << '\n';
  }
  int material = -1;
  for (Index f = 0; f < q.face_capacity(); ++f) {
    if (!q.is_face_live(f)) continue;
    if (!materials.empty() && materials.at(colours.faces[f]) != material)
      out << "usemtl material_" << (material = materials.at(colours.faces[f])) << '\n';
    out << 'f';
    for (Index k = 0; k < 4; ++k) out << ' ' << id[q.vertex(f, k)];
    out << '\n';
  }
  if (!out.flush()) fail(path, "cannot be written");
}

// The materials of write_obj(): one per face colour, numbered in the order they come.
std::map<Colour, int> materials_of(const QuadMesh& q, const std::vector<Colour>& face_colours) {
  std::map<Colour, int> materials;
  for (Index f = 0; f < q.face_capacity() && !face_colours.empty(); ++f)
    if (q.is_face_live(f)) materials.emplace(face_colours[f], int(materials.size()));
  return materials;
}

void write_mtl(const std::string& path, const std::map<Colour, int>& materials) {
  std::vector<const Colour*> by_number(materials.size());
  for (const auto& [colour, k] : materials) by_number[std::size_t(k)] = &colour;
  std::ofstream out(path, std::ios::binary);
  out << "# quadsimp: the quads' face colours\n";
  for (std::size_t k = 0; k < by_number.size(); ++k) {
    const Colour& c = *by_number[k];
    out << "newmtl material_" << k << "\nKd " << fraction(c[0]) << ' ' << fraction(c[1]) << ' ' << fraction(c[2])
        << "\nd " << fraction(c[3]) << '\n';
  }
  if (!out.flush()) fail(path, "cannot be written");
}

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
  } else {
    TMesh m;
    load_vcg(path, m);
    file = regroup(path, m);
  }
  if (file.positions.empty()) fail(path, "the file holds no vertices (empty mesh)");
  return file;
}

void write_quad_mesh(const std::string& path, const QuadMesh& mesh, const QuadColours& colours) {
  const std::string ext = extension_of(path);
  if (ext != "ply" && ext != "obj" && ext != "off")
    fail(path, "cannot write '" + ext + "' (quads are written as .ply, .obj or .off)");
  if (!colours.vertices.empty() && colours.vertices.size() != mesh.vertex_capacity())
    throw std::invalid_argument("write_quad_mesh: one colour per vertex id expected");
  if (!colours.faces.empty() && colours.faces.size() != mesh.face_capacity())
    throw std::invalid_argument("write_quad_mesh: one colour per face id expected");
  PMesh pm;
  if (ext != "obj") fill_poly_mesh(mesh, colours, pm);
  int mask = colours.vertices.empty() ? 0 : int(vcg::tri::io::Mask::IOM_VERTCOLOR);
  if (!colours.faces.empty()) mask |= int(vcg::tri::io::Mask::IOM_FACECOLOR);
  // An OBJ's face colours go to a material file beside it, written first, and removed if
  // the OBJ cannot be.
  const std::map<Colour, int> materials = ext == "obj" ? materials_of(mesh, colours.faces) : std::map<Colour, int>();
  const std::string mtl = path + ".mtl";
  if (!materials.empty()) write_atomically(mtl, [&](const std::string& tmp) { write_mtl(tmp, materials); });
  try {
    write_atomically(path, [&](const std::string& tmp) {
      int err = 0;
      // vcglib's binary PLY writer emits triangles only (three indices per face,
      // whatever the polygon); its ASCII writer handles polygons.
      if (ext == "ply")
        err = vcg::tri::io::ExporterPLY<PMesh>::Save(pm, tmp.c_str(), mask, false);
      else if (ext == "obj")
        write_obj(tmp, mesh, colours, std::filesystem::path(mtl).filename().string(), materials);
      else
        err = vcg::tri::io::ExporterOFF<PMesh>::Save(pm, tmp.c_str(), mask);
      if (err != 0) fail(path, "cannot be written (vcglib error " + std::to_string(err) + ")");
    });
  } catch (...) {
    std::error_code ec;
    if (!materials.empty()) std::filesystem::remove(mtl, ec);
    throw;
  }
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
  if (extension_of(path) != "ply") fail(path, "fields are written as .ply only");
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
  write_atomically(path, [&](const std::string& tmp) {
    const int err = vcg::tri::io::ExporterPLY<TMesh>::Save(tm, tmp.c_str(), true, info);
    if (err != 0) fail(path, "cannot be written (vcglib error " + std::to_string(err) + ")");
  });
}

}  // namespace qs
