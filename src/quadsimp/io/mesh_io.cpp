// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
//
// The only file that sees vcglib's I/O. vcglib triangulates polygons on import and
// marks the inner edges "faux"; MeshLab stores its quads the same way (and writes the
// flags to PLY with -m ff). So one path serves every format: read triangles with
// face flags, then regroup triangles joined by a faux edge into polygons.
#include "quadsimp/io/mesh_io.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include <vcg/complex/complex.h>
#include <wrap/io_trimesh/export_obj.h>
#include <wrap/io_trimesh/export_off.h>
#include <wrap/io_trimesh/export_ply.h>
#include <wrap/io_trimesh/import_obj.h>
#include <wrap/io_trimesh/import_off.h>
#include <wrap/io_trimesh/import_ply.h>
#include <wrap/io_trimesh/import_stl.h>

#include "quadsimp/util/errors.h"

namespace qs {
namespace {

class TVertex;
class TFace;
struct TTypes : vcg::UsedTypes<vcg::Use<TVertex>::AsVertexType, vcg::Use<TFace>::AsFaceType> {};
class TVertex : public vcg::Vertex<TTypes, vcg::vertex::Coord3d, vcg::vertex::Color4b,
                                   vcg::vertex::BitFlags> {};
class TFace : public vcg::Face<TTypes, vcg::face::VertexRef, vcg::face::BitFlags> {};
// vcglib's mesh destructor leaves attributes (the importers add some) allocated.
class TMesh : public vcg::tri::TriMesh<std::vector<TVertex>, std::vector<TFace>> {
 public:
  ~TMesh() override { ClearAttributes(); }
};

class PVertex;
class PFace;
struct PTypes : vcg::UsedTypes<vcg::Use<PVertex>::AsVertexType, vcg::Use<PFace>::AsFaceType> {};
class PVertex : public vcg::Vertex<PTypes, vcg::vertex::Coord3d, vcg::vertex::BitFlags> {};
class PFace : public vcg::Face<PTypes, vcg::face::PolyInfo, vcg::face::PFVAdj, vcg::face::BitFlags> {};
class PMesh : public vcg::tri::TriMesh<std::vector<PVertex>, std::vector<PFace>> {
 public:
  ~PMesh() override { ClearAttributes(); }
};

[[noreturn]] void fail(const std::string& path, const std::string& why) {
  throw InvalidInput(path + ": " + why);
}

// vcglib's OBJ and OFF readers trust what they read: a coordinate that is not a number
// becomes 0 (atof), so a damaged file loaded with vertices piled at the origin, and a
// face corner naming a vertex that does not exist is followed into memory the mesh does
// not own (a crash, or a face on garbage). So the text is checked first, line by line:
// the first three fields of each vertex line must be numbers, every corner of a face a
// vertex of the file.
class TextMeshCheck {
 public:
  TextMeshCheck(std::string path, bool obj) : path_(std::move(path)), obj_(obj) {}

  void run() {
    std::ifstream in(path_);
    std::string line;
    while (next_line(in, line)) obj_ ? obj_line() : off_line(in);
  }

 private:
  bool next_line(std::ifstream& in, std::string& line) {
    while (std::getline(in, line)) {
      ++lineno_;
      tokens_.clear();
      for (std::size_t b = line.find_first_not_of(" \t\r"); b != std::string::npos;) {
        const std::size_t e = std::min(line.find_first_of(" \t\r", b), line.size());
        tokens_.emplace_back(line.data() + b, e - b);
        b = line.find_first_not_of(" \t\r", e);
      }
      if (!tokens_.empty() && tokens_[0][0] != '#') return true;
    }
    return false;
  }

  [[noreturn]] void fail_line(long line, const std::string& why) const {
    fail(path_, "line " + std::to_string(line) + ": " + why);
  }
  [[noreturn]] void bad_corner(long long corner, const std::string& why) const {
    fail_line(lineno_, "face corner " + std::to_string(corner) + " names no vertex (" + why + ")");
  }

  static bool parse(std::string_view t, double& x) {
    if (!t.empty() && t[0] == '+') t.remove_prefix(1);  // from_chars takes no '+', strtod does
    const auto r = std::from_chars(t.data(), t.data() + t.size(), x);
    return r.ec == std::errc() && r.ptr == t.data() + t.size();
  }
  static bool parse(std::string_view t, long long& x) {
    if (!t.empty() && t[0] == '+') t.remove_prefix(1);
    const auto r = std::from_chars(t.data(), t.data() + t.size(), x);
    return r.ec == std::errc() && r.ptr == t.data() + t.size();
  }

  // Tokens [from, from + 3) are coordinates; a missing one is left to vcglib's own check.
  void check_coordinates(std::size_t from) const {
    double x;
    for (std::size_t i = from; i < std::min(from + 3, tokens_.size()); ++i)
      if (!parse(tokens_[i], x)) fail_line(lineno_, "'" + std::string(tokens_[i]) + "' is not a number (a vertex coordinate)");
  }

  long long corner_at(std::size_t i) const {
    long long c;
    if (!parse(tokens_[i].substr(0, tokens_[i].find('/')), c))
      fail_line(lineno_, "'" + std::string(tokens_[i]) + "' is not a vertex number (a face corner)");
    return c;
  }

  void obj_line() {
    const std::string_view kw = tokens_[0];
    if (kw == "v") {
      check_coordinates(1);
      ++n_vertices_;
    } else if (kw == "f" || kw == "q") {  // "q": a quad of the zero-based QOBJ variant
      // Corners count from 1, or back from -1, over the vertices above the line; vcglib
      // dropped a triangle naming one further down without a word.
      for (std::size_t i = 1; i < tokens_.size(); ++i) {
        long long c = corner_at(i);
        if (kw == "q" && c >= 0) ++c;
        if (c == 0 || (c < 0 ? -c : c) > n_vertices_)
          bad_corner(c, "only " + std::to_string(n_vertices_) + " come before it");
      }
    }
  }

  // OFF: "[C][N][ST]OFF [nv nf ne]", counts on the next line if not there, nv vertex
  // lines, then nf face lines "n v_0 .. v_n-1 [colour]" (vcglib lets the corners of a
  // face whose count stands alone continue on the next line).
  void off_line(std::ifstream& in) {
    if (state_ == Off::header) {
      state_ = Off::counts;
      if (tokens_.size() == 1) return;
      tokens_.erase(tokens_.begin());
    }
    if (state_ == Off::counts) {
      long long nf = 0;
      if (tokens_.size() < 2 || !parse(tokens_[0], n_vertices_) || !parse(tokens_[1], nf)) {
        state_ = Off::done;  // vcglib refuses the file itself
        return;
      }
      vertices_left_ = n_vertices_;
      faces_left_ = nf;
      state_ = Off::vertices;
      return;
    }
    if (vertices_left_ > 0) {
      --vertices_left_;
      check_coordinates(0);
      return;
    }
    if (faces_left_ <= 0) return;
    --faces_left_;
    long long n;
    if (!parse(tokens_[0], n)) fail_line(lineno_, "'" + std::string(tokens_[0]) + "' is not a corner count (a face)");
    if (n < 2) fail_line(lineno_, "a face listed with only " + std::to_string(n) + " corner(s)");
    std::size_t first = 1;
    std::string more;  // holds the corners when the count stands alone
    if (tokens_.size() == 1) {
      if (!next_line(in, more)) fail_line(lineno_, "a face without its corners");
      first = 0;
    }
    const std::size_t listed = tokens_.size() - first;
    if (listed < std::size_t(n))
      fail_line(lineno_, "a face of " + std::to_string(n) + " corners lists " + std::to_string(listed));
    for (std::size_t i = first; i < first + std::size_t(n); ++i) {
      const long long c = corner_at(i);
      if (c < 0 || c >= n_vertices_) bad_corner(c, "the file has " + std::to_string(n_vertices_));
    }
  }

  enum class Off { header, counts, vertices, done };

  std::string path_;
  bool obj_;
  long lineno_ = 0;
  std::vector<std::string_view> tokens_;
  long long n_vertices_ = 0;  // OBJ: so far; OFF: as counted in the header
  Off state_ = Off::header;
  long long vertices_left_ = 0, faces_left_ = 0;
};

void load_vcg(const std::string& path, TMesh& m) {
  const std::string ext = extension_of(path);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail(path, "no such file");
  {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) fail(path, "cannot be opened for reading");
    if (probe.peek() == std::ifstream::traits_type::eof()) fail(path, "the file is empty");
  }
  if (ext == "ply") {
    int mask = 0;
    const int err = vcg::tri::io::ImporterPLY<TMesh>::Open(m, path.c_str(), mask);
    if (err != 0) fail(path, std::string("unreadable PLY (") + vcg::tri::io::ImporterPLY<TMesh>::ErrorMsg(err) + ")");
  } else if (ext == "obj") {
    TextMeshCheck(path, ext == "obj").run();
    vcg::tri::io::ImporterOBJ<TMesh>::Info info;
    const int err = vcg::tri::io::ImporterOBJ<TMesh>::Open(m, path.c_str(), info);
    if (err != 0 && vcg::tri::io::ImporterOBJ<TMesh>::ErrorCritical(err))
      fail(path, std::string("unreadable OBJ (") + vcg::tri::io::ImporterOBJ<TMesh>::ErrorMsg(err) + ")");
  } else if (ext == "off") {
    TextMeshCheck(path, ext == "obj").run();
    int mask = 0;
    const int err = vcg::tri::io::ImporterOFF<TMesh>::Open(m, path.c_str(), mask);
    if (err != 0) fail(path, std::string("unreadable OFF (") + vcg::tri::io::ImporterOFF<TMesh>::ErrorMsg(err) + ")");
  } else if (ext == "stl") {
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

// The live vertices and faces of q (tombstones skipped, ids renumbered in order).
void fill_poly_mesh(const QuadMesh& q, PMesh& pm) {
  std::vector<Index> id(q.vertex_capacity(), kNone);
  auto vi = vcg::tri::Allocator<PMesh>::AddVertices(pm, q.n_vertices());
  Index n = 0;
  for (Index v = 0; v < q.vertex_capacity(); ++v) {
    if (!q.is_vertex_live(v)) continue;
    id[v] = n++;
    const Vec3& p = q.position(v);
    (vi++)->P() = vcg::Point3d(p.x(), p.y(), p.z());
  }
  auto fi = vcg::tri::Allocator<PMesh>::AddFaces(pm, q.n_faces());
  for (Index f = 0; f < q.face_capacity(); ++f) {
    if (!q.is_face_live(f)) continue;
    fi->Alloc(4);
    for (Index k = 0; k < 4; ++k) fi->V(k) = &pm.vert[id[q.vertex(f, k)]];
    ++fi;
  }
}

}  // namespace

std::string extension_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  if (!ext.empty()) ext.erase(0, 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

MeshFile read_mesh(const std::string& path) {
  TMesh m;
  load_vcg(path, m);
  if (m.vn == 0) fail(path, "the file holds no vertices (empty mesh)");
  return regroup(path, m);
}

void write_quad_mesh(const std::string& path, const QuadMesh& mesh) {
  const std::string ext = extension_of(path);
  if (ext != "ply" && ext != "obj" && ext != "off")
    fail(path, "cannot write '" + ext + "' (quads are written as .ply, .obj or .off)");
  PMesh pm;
  fill_poly_mesh(mesh, pm);
  write_atomically(path, [&](const std::string& tmp) {
    int err = 0;
    // vcglib's binary PLY writer emits triangles only (three indices per face,
    // whatever the polygon); its ASCII writer handles polygons.
    if (ext == "ply")
      err = vcg::tri::io::ExporterPLY<PMesh>::Save(pm, tmp.c_str(), vcg::tri::io::Mask::IOM_NONE, false);
    else if (ext == "obj")
      err = vcg::tri::io::ExporterOBJ<PMesh>::Save(pm, tmp.c_str(), vcg::tri::io::Mask::IOM_NONE);
    else
      err = vcg::tri::io::ExporterOFF<PMesh>::Save(pm, tmp.c_str(), vcg::tri::io::Mask::IOM_NONE);
    if (err != 0) fail(path, "cannot be written (vcglib error " + std::to_string(err) + ")");
  });
}

void write_tri_mesh_ply(const std::string& path, const TriMesh& mesh,
                        const std::vector<VertexField>& fields) {
  if (extension_of(path) != "ply") fail(path, "fields are written as .ply only");
  for (const auto& f : fields)
    if (f.values.size() != mesh.positions.size())
      throw std::invalid_argument("write_tri_mesh_ply: field '" + f.name + "' has the wrong size");
  TMesh tm;
  auto vi = vcg::tri::Allocator<TMesh>::AddVertices(tm, mesh.positions.size());
  for (const Vec3& p : mesh.positions) (vi++)->P() = vcg::Point3d(p.x(), p.y(), p.z());
  auto fi = vcg::tri::Allocator<TMesh>::AddFaces(tm, mesh.faces.size());
  for (const auto& t : mesh.faces) {
    for (int k = 0; k < 3; ++k) fi->V(k) = &tm.vert[t[k]];
    ++fi;
  }
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
