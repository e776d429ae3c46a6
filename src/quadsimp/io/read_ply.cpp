// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
//
// PLY is read here, not by vcglib: its list reader wrote a face's corners into a fixed
// buffer of 512 with a one-byte count, so a polygon of more than 255 corners was cut
// short without a word and a longer list overran the buffer (a crash), and it allocated
// every element a header counts before reading one (300,000,000 vertices in a 188-byte
// file took 9 GB). Its readers of the old Stanford elements were worse: a triangle
// strip's second and third corners were looked up unchecked and its lists never freed,
// and a range grid's entry of more than five indices overran an array on the stack.
// Vertex x, y, z and the faces' corner lists and MeshLab's face flags (whose faux bits
// mark the inner edges of quads stored as triangle pairs) are read, and those old
// elements, "tristrips" and "range_grid", as vcglib turned them into faces; other
// properties and elements are skipped.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "quadsimp/io/text_lines.h"
#include "quadsimp/io/text_readers.h"

namespace qs {
namespace {

[[noreturn]] void unreadable(const std::string& path, const std::string& why) {
  throw InvalidInput(path + ": unreadable PLY (" + why + ")");
}

enum class Type : std::uint8_t { i8, u8, i16, u16, i32, u32, f32, f64 };

bool type_named(std::string_view name, Type& t) {
  static const std::pair<std::string_view, Type> names[] = {
      {"char", Type::i8},    {"int8", Type::i8},     {"uchar", Type::u8},   {"uint8", Type::u8},
      {"short", Type::i16},  {"int16", Type::i16},   {"ushort", Type::u16}, {"uint16", Type::u16},
      {"int", Type::i32},    {"int32", Type::i32},   {"uint", Type::u32},   {"uint32", Type::u32},
      {"float", Type::f32},  {"float32", Type::f32}, {"double", Type::f64}, {"float64", Type::f64}};
  for (const auto& [n, type] : names)
    if (n == name) return t = type, true;
  return false;
}

std::size_t size_of(Type t) {
  static constexpr std::size_t sizes[] = {1, 1, 2, 2, 4, 4, 4, 8};
  return sizes[std::size_t(t)];
}

struct Property {
  std::string name;
  bool list = false;
  Type count = Type::u8, value = Type::f32;
};

struct Element {
  std::string name;
  long long count = 0;
  std::vector<Property> properties;
  int find(std::string_view n) const {
    for (std::size_t i = 0; i < properties.size(); ++i)
      if (properties[i].name == n) return int(i);
    return -1;
  }
};

// The body as a stream of values: ASCII fields, or binary in either byte order.
class Values {
 public:
  enum class Format { ascii, little, big };

  Values(std::string_view body, Format format)
      : body_(body), ascii_(format == Format::ascii), swap_((format == Format::big) == little_endian_host()) {}

  // The next value as a double (indices up to 2^32 are exact); false when the data ends
  // or an ASCII field is not a number of the type.
  bool next(Type t, double& x) {
    if (ascii_) return next_ascii(t, x);
    const std::size_t n = size_of(t);
    if (body_.size() - pos_ < n) return false;
    unsigned char b[8];
    std::memcpy(b, body_.data() + pos_, n);
    pos_ += n;
    if (swap_) std::reverse(b, b + n);
    switch (t) {
      case Type::i8: x = double(std::int8_t(b[0])); break;
      case Type::u8: x = double(b[0]); break;
      case Type::i16: x = double(load<std::int16_t>(b)); break;
      case Type::u16: x = double(load<std::uint16_t>(b)); break;
      case Type::i32: x = double(load<std::int32_t>(b)); break;
      case Type::u32: x = double(load<std::uint32_t>(b)); break;
      case Type::f32: x = double(load<float>(b)); break;
      case Type::f64: x = load<double>(b); break;
    }
    return true;
  }

  // Bytes left, an upper bound on the values left in either format.
  std::size_t left() const { return body_.size() - pos_; }

 private:
  static bool little_endian_host() {
    const std::uint16_t one = 1;
    unsigned char c;
    std::memcpy(&c, &one, 1);
    return c == 1;
  }
  template <class T>
  static T load(const unsigned char* b) {
    T v;
    std::memcpy(&v, b, sizeof v);
    return v;
  }

  static bool space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

  bool next_ascii(Type t, double& x) {
    while (pos_ < body_.size() && space(body_[pos_])) ++pos_;
    std::size_t end = pos_;
    while (end < body_.size() && !space(body_[end])) ++end;
    if (end == pos_) return false;
    const std::string_view field = body_.substr(pos_, end - pos_);
    pos_ = end;
    if (t == Type::f32) {  // as a float, rounded once, as a binary file would hold it
      float f;
      if (!parse_number(field, f)) return false;
      x = double(f);
      return true;
    }
    if (t == Type::f64) return parse_number(field, x);
    long long i;
    if (!parse_number(field, i)) return false;
    x = double(i);
    return true;
  }

  std::string_view body_;
  bool ascii_, swap_;  // swap_: the file's byte order is not this machine's
  std::size_t pos_ = 0;
};

// The header, checked against the data: its elements, the data's format, where the
// data starts.
struct Header {
  std::vector<Element> elements;
  Values::Format format = Values::Format::ascii;
  std::size_t data = 0;
  long long grid_cols = -1, grid_rows = -1;  // a range grid's size ("obj_info num_cols 640")
  std::vector<std::string> textures;          // "comment TextureFile NAME" (MeshLab's), in order
};

Header read_header(const std::string& path, const std::string& file) {
  Header h;
  bool ended = false, formatted = false;
  std::vector<std::string_view> f;
  std::size_t pos = 0;
  for (int line = 0; !ended && pos < file.size(); ++line) {
    const std::size_t eol = std::min(file.find('\n', pos), file.size());
    detail::split_fields(std::string_view(file).substr(pos, eol - pos), f);
    pos = eol + 1;
    if (line == 0) {
      // In capitals too: compas's sample tube mesh says "PLY" (MeshLab refuses it).
      const auto magic = [](std::string_view w) {
        return w.size() == 3 && (w[0] | 0x20) == 'p' && (w[1] | 0x20) == 'l' && (w[2] | 0x20) == 'y';
      };
      if (f.size() != 1 || !magic(f[0])) unreadable(path, "the file does not start with 'ply'");
      continue;
    }
    if (f.empty()) continue;
    if (f[0] == "comment" && f.size() >= 3 && f[1] == "TextureFile") {
      // The rest of the line: a name may hold spaces.
      const std::size_t from = std::size_t(f[2].data() - file.data());
      std::string name(file, from, eol - from);
      while (!name.empty() && (name.back() == '\r' || name.back() == ' ' || name.back() == '\t')) name.pop_back();
      h.textures.push_back(name);
      continue;
    }
    if (f[0] == "comment" || f[0] == "obj_info") {
      // A range grid's size; anything else there (a size that is no number included) is
      // text, which only a range grid, refused without its size, would miss.
      long long n;
      if (f.size() == 3 && (f[1] == "num_cols" || f[1] == "num_rows") && parse_number(f[2], n))
        (f[1] == "num_cols" ? h.grid_cols : h.grid_rows) = n;
      continue;
    }
    if (f[0] == "end_header") {
      ended = true;
    } else if (f[0] == "format" && f.size() >= 2) {
      formatted = true;
      if (f[1] == "ascii") h.format = Values::Format::ascii;
      else if (f[1] == "binary_little_endian") h.format = Values::Format::little;
      else if (f[1] == "binary_big_endian") h.format = Values::Format::big;
      else unreadable(path, "unknown format " + detail::quoted(f[1]));
    } else if (f[0] == "element" && f.size() >= 2) {
      Element e;
      e.name = f[1];
      if (f.size() != 3 || !parse_number(f[2], e.count) || e.count < 0)
        unreadable(path, "element " + detail::quoted(e.name) + " has no count");
      h.elements.push_back(e);
    } else if (f[0] == "property" && !h.elements.empty()) {
      Property p;
      const bool list = f.size() == 5 && f[1] == "list";
      if (list ? !type_named(f[2], p.count) || !type_named(f[3], p.value) : f.size() != 3 || !type_named(f[1], p.value))
        unreadable(path, "a property line it does not understand");
      p.list = list;
      p.name = f.back();
      h.elements.back().properties.push_back(p);
    } else {
      unreadable(path, "a header line it does not understand");
    }
  }
  if (!ended || !formatted) unreadable(path, "no complete header");
  h.data = std::min(pos, file.size());

  // No count may pass what the data could hold (a value takes its size in binary, a
  // digit and a separator in ASCII, where the last separator may be missing), so nothing
  // is reserved for more.
  const std::size_t bytes = file.size() - h.data;
  const bool ascii = h.format == Values::Format::ascii;
  for (const Element& e : h.elements) {
    std::size_t least = 0;
    for (const Property& p : e.properties) least += ascii ? 2 : size_of(p.list ? p.count : p.value);
    if (least > 0 && std::size_t(e.count) > (bytes + (ascii ? 1 : 0)) / least)
      unreadable(path, "its header counts " + std::to_string(e.count) + " " + detail::quoted(e.name) +
                           " elements in " + std::to_string(bytes) + " bytes of data");
  }
  return h;
}

constexpr std::size_t kNoUvs = ~std::size_t(0);  // a polygon without coordinates of its own

// The polygons' texture, each fanned as the mesh is: from their corners' coordinates
// (from `first_uv`, kNoUvs: none) or their vertices' (`vertex_uvs`, one per vertex or
// none), into the images the header names (beside the file). A polygon of texnumber -1
// takes its colour (`colours`, one per polygon, or none) as the filters take a layer's
// (texture_of()). Empty unless every polygon has coordinates and names an image, or has a
// colour, and some polygon is textured.
FileTexture texture_of_polygons(const std::string& path, const std::vector<std::string>& images,
                                const std::vector<Index>& corners, const std::vector<std::size_t>& polygon_start,
                                const std::vector<std::size_t>& first_uv, const std::vector<TexCoord>& corner_uvs,
                                const std::vector<TexCoord>& vertex_uvs, const std::vector<int>& image,
                                const std::vector<Colour>& colours) {
  FileTexture t;
  if (images.empty() || polygon_start.size() < 2) return t;
  std::vector<TexCoord> by_vertex;  // a polygon's corners' coordinates, from their vertices'
  for (std::size_t i = 0; i + 1 < polygon_start.size(); ++i) {
    const std::size_t from = polygon_start[i], n = polygon_start[i + 1] - from;
    const bool coloured = image[i] == -1 && !colours.empty();  // its coordinates unread
    if (!coloured && (image[i] < 0 || std::size_t(image[i]) >= images.size())) return {};
    const TexCoord* uv = first_uv[i] != kNoUvs ? &corner_uvs[first_uv[i]] : nullptr;
    if (coloured) {
      by_vertex.assign(n, TexCoord{0, 0});
      uv = by_vertex.data();
    } else if (!uv) {
      by_vertex.clear();
      for (std::size_t k = 0; k < n; ++k) {
        const Index v = corners[from + k];
        if (v >= vertex_uvs.size()) return {};
        by_vertex.push_back(vertex_uvs[v]);
      }
      uv = by_vertex.data();
    }
    detail::fan(&corners[from], uv, n, image[i], t);
    if (!colours.empty()) t.colours.resize(t.triangles.size(), colours[i]);
  }
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  for (const std::string& name : images) t.images.push_back(detail::file_beside(folder, name));
  return kept_texture(std::move(t));
}

// The triangles of one "tristrips" entry: each run between restarts (-1), triangle k of a
// run corners k, k+1, k+2, every other one turned (vcglib's order, so that all face the
// same way).
template <class AddTriangle>
void strip_triangles(const std::vector<long long>& list, AddTriangle&& add_triangle) {
  std::size_t run = 0;
  for (std::size_t k = 0; k + 2 < list.size(); ++k) {
    if (list[k] < 0 || list[k + 1] < 0 || list[k + 2] < 0) {
      if (list[k] < 0) run = k + 1;
      continue;
    }
    if ((k - run) % 2)
      add_triangle(list[k + 1], list[k], list[k + 2]);
    else
      add_triangle(list[k], list[k + 1], list[k + 2]);
  }
}

// A range grid's cells (`grid`: the vertex at each point, row by row, -1 where none): two
// triangles joined by a faux diagonal (a quad) where all four points have a vertex, else a
// triangle on three: vcglib's SparseFaceGrid(), the same triangles in the same order.
template <class AddTriangle>
void range_grid_triangles(const std::vector<long long>& grid, long long rows, long long cols,
                          AddTriangle&& add_triangle) {
  for (long long r = 0; r + 1 < rows && !grid.empty(); ++r)
    for (long long c = 0; c + 1 < cols; ++c) {
      const long long v0 = grid[r * cols + c], v1 = grid[r * cols + c + 1];
      const long long v2 = grid[(r + 1) * cols + c], v3 = grid[(r + 1) * cols + c + 1];
      const std::uint8_t quad = v0 >= 0 && v1 >= 0 && v2 >= 0 && v3 >= 0 ? 4 : 0;  // edge 2: v0-v3
      if (v0 >= 0 && v3 >= 0 && (v1 >= 0 || v2 >= 0)) {
        if (v2 >= 0) add_triangle(v3, v2, v0, quad);
        if (v1 >= 0) add_triangle(v0, v1, v3, quad);
      } else if (v1 >= 0 && v2 >= 0) {
        if (v0 >= 0) add_triangle(v2, v0, v1);
        if (v3 >= 0) add_triangle(v1, v3, v2);
      }
    }
}

}  // namespace

MeshFile read_ply(const std::string& path) {
  const auto fail = [&path](const std::string& why) { unreadable(path, why); };
  std::ifstream in(path, std::ios::binary);
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const Header header = read_header(path, data);

  Values values(std::string_view(data).substr(header.data), header.format);
  std::vector<Vec3> positions;
  std::vector<Colour> colours, face_colours;  // face_colours: one per polygon
  std::vector<std::array<Index, 3>> triangles;
  std::vector<std::uint8_t> faux;
  // The texture: each polygon's corners' coordinates (per corner, or its vertices'), and
  // its image (texnumber, else the first), kept only if every polygon has them.
  std::vector<TexCoord> vertex_uvs, corner_uvs;
  std::vector<std::size_t> polygon_uvs;  // per polygon: its first in corner_uvs, or kNoUvs
  std::vector<int> polygon_image;
  // Faces, flat, checked and fanned once all vertices are known (they may come first).
  std::vector<Index> corners;
  std::vector<std::size_t> polygon_start{0};
  std::vector<std::uint8_t> flag_faux;  // the faces' faux bits from their flags
  const auto add_triangle = [&](long long a, long long b, long long c, std::uint8_t faux_bits = 0) {
    corners.insert(corners.end(), {Index(a), Index(b), Index(c)});
    polygon_start.push_back(corners.size());
    flag_faux.push_back(faux_bits);
    polygon_uvs.push_back(kNoUvs);
    polygon_image.push_back(0);
  };
  std::vector<long long> list;  // a strip's or a grid entry's indices (-1: none)
  std::vector<long long> grid;  // a range grid's vertex at each point, row by row (-1: none)
  bool have_vertices = false, have_faces = false, have_grid = false, textured = false;
  for (const Element& e : header.elements) {
    const bool vertex = e.name == "vertex", face = e.name == "face";
    const bool strips = e.name == "tristrips", range = e.name == "range_grid";
    if ((vertex && have_vertices) || (face && have_faces) || (range && have_grid))
      fail("two " + detail::quoted(e.name) + " elements");
    if (range && (header.grid_cols < 0 || header.grid_rows < 0 ||
                  double(header.grid_cols) * double(header.grid_rows) != double(e.count)))
      fail("a range grid of " + std::to_string(e.count) + " entries without num_cols and num_rows that many");
    const int xyz[3] = {e.find("x"), e.find("y"), e.find("z")};
    // Colours as MeshLab writes them (bytes; alpha optional), or as fractions in floats.
    const int rgba[4] = {e.find("red"), e.find("green"), e.find("blue"), e.find("alpha")};
    const bool coloured = (vertex || face) && rgba[0] >= 0 && rgba[1] >= 0 && rgba[2] >= 0;
    if (vertex && (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0)) fail("vertices without x, y and z");
    const bool indexed = face || strips || range;
    int list_at = indexed ? e.find("vertex_indices") : -1;
    if (face && list_at < 0) list_at = e.find("vertex_index");
    if (indexed && (list_at < 0 || !e.properties[std::size_t(list_at)].list))
      fail((face ? std::string("faces") : detail::quoted(e.name)) + " without a list of vertex indices");
    const int flags = face ? e.find("flags") : -1;
    // Texture coordinates per vertex (MeshLab writes texture_u, texture_v) or per corner
    // (texcoord: u, v for each), into the image texnumber names.
    int uv[2] = {-1, -1};
    for (const auto& [u, v] : {std::pair{"texture_u", "texture_v"}, {"texture_s", "texture_t"}, {"s", "t"}, {"u", "v"}})
      if (vertex && uv[0] < 0 && e.find(u) >= 0 && e.find(v) >= 0) uv[0] = e.find(u), uv[1] = e.find(v);
    const int texcoord = face ? e.find("texcoord") : -1, texnumber = face ? e.find("texnumber") : -1;
    textured |= uv[0] >= 0 || texcoord >= 0;
    have_vertices |= vertex;
    have_faces |= face;
    have_grid |= range;
    if (e.properties.empty()) continue;  // nothing to read, however many
    if (vertex) positions.reserve(std::size_t(e.count));
    if (coloured) (vertex ? colours : face_colours).reserve(std::size_t(e.count));
    if (face) polygon_start.reserve(std::size_t(e.count) + 1);

    for (long long i = 0; i < e.count; ++i) {
      Vec3 p = Vec3::Zero();
      Colour colour = {0, 0, 0, 255};
      std::uint32_t face_flags = 0;
      TexCoord vertex_uv = {0, 0};
      int image = 0;
      const std::size_t first_corner = corners.size(), first_uv = corner_uvs.size();
      std::size_t uv_values = 0;
      for (std::size_t k = 0; k < e.properties.size(); ++k) {
        const Property& prop = e.properties[k];
        double x;
        if (!prop.list) {
          if (!values.next(prop.value, x))
            fail("its data ends, or is not a number, in " + detail::quoted(e.name) + " " + std::to_string(i));
          for (int c = 0; c < 3; ++c)
            if (vertex && int(k) == xyz[c]) p[c] = x;
          for (int c = 0; c < 4; ++c)
            if (coloured && int(k) == rgba[c]) {
              const bool fraction = prop.value == Type::f32 || prop.value == Type::f64;
              colour[std::size_t(c)] = colour_byte(fraction ? 255 * x : x);
            }
          if (face && int(k) == flags) face_flags = std::uint32_t(std::int64_t(x));
          if (face && int(k) == texnumber) image = x >= 0 && x < 1e9 ? int(x) : -1;
          for (int c = 0; c < 2; ++c)
            if (vertex && int(k) == uv[c]) vertex_uv[std::size_t(c)] = float(x);
          continue;
        }
        double n;
        if (!values.next(prop.count, n) || n < 0 || n > double(values.left()))
          fail("a list that is not there, or longer than the file, in " + detail::quoted(e.name) + " " +
               std::to_string(i));
        if (int(k) == list_at) list.clear();
        for (long long j = 0; j < static_cast<long long>(n); ++j) {
          if (!values.next(prop.value, x))
            fail("its data ends, or is not a number, in " + detail::quoted(e.name) + " " + std::to_string(i));
          if (int(k) == texcoord) {
            if (uv_values++ % 2 == 0) corner_uvs.push_back({float(x), 0});
            else corner_uvs.back()[1] = float(x);
          }
          if (int(k) != list_at) continue;
          // Strips restart after a -1; every other index must name a vertex (checked below).
          if (!(x >= (strips ? -1 : 0) && x <= double(std::numeric_limits<Index>::max())))
            fail(e.name + " " + std::to_string(i) + ": corner " + std::to_string(static_cast<long long>(x)) +
                 " names no vertex");
          if (face) corners.push_back(Index(x));
          else list.push_back(static_cast<long long>(x));
        }
      }
      if (strips) {
        strip_triangles(list, add_triangle);
        continue;
      }
      if (range) {
        grid.push_back(list.empty() ? -1 : list[0]);
        continue;
      }
      if (vertex) positions.push_back(p);
      if (vertex && coloured) colours.push_back(colour);
      if (vertex && uv[0] >= 0) vertex_uvs.push_back(vertex_uv);
      if (face) {
        const std::size_t n = corners.size() - first_corner;
        if (n < 3) fail("face " + std::to_string(i) + " has " + std::to_string(n) + " corners");
        if (face_flags & 1u) {  // vcglib's deleted bit
          corners.resize(first_corner);
          corner_uvs.resize(first_uv);
          continue;
        }
        polygon_start.push_back(corners.size());
        flag_faux.push_back(std::uint8_t((face_flags >> 18) & 7u));  // FAUX0..2 = 0x40000 << k
        if (coloured) face_colours.push_back(colour);
        const bool has_uvs = uv_values == 2 * n;
        if (!has_uvs) corner_uvs.resize(first_uv);
        polygon_uvs.push_back(has_uvs ? first_uv : kNoUvs);
        polygon_image.push_back(image);
      }
    }
  }
  range_grid_triangles(grid, header.grid_rows, header.grid_cols, add_triangle);
  for (const Index c : corners)
    if (c >= positions.size())
      fail("a face corner " + std::to_string(c) + " names no vertex (the file has " + std::to_string(positions.size()) +
           ")");
  triangles.reserve(corners.size());
  faux.reserve(corners.size());
  // Face colours are kept if every face has one (a strip's or a grid's triangles have none).
  const bool face_coloured = !face_colours.empty() && face_colours.size() == flag_faux.size();
  std::vector<Colour> triangle_colours;
  for (std::size_t i = 0; i + 1 < polygon_start.size(); ++i) {
    const std::size_t first = faux.size();
    const std::size_t n = polygon_start[i + 1] - polygon_start[i];
    detail::fan(corners.data() + polygon_start[i], n, triangles, faux);
    if (n == 3) faux[first] |= flag_faux[i];  // the bits name a triangle's edges
    if (face_coloured) triangle_colours.resize(faux.size(), face_colours[i]);
  }
  const std::vector<Colour> none;
  FileTexture texture = texture_of_polygons(path, header.textures, corners, polygon_start, polygon_uvs, corner_uvs,
                                            vertex_uvs, polygon_image, face_coloured ? face_colours : none);
  MeshFile out = pair_faux_triangles(std::move(positions), std::move(triangles), faux, triangle_colours);
  out.colours = std::move(colours);
  out.texture_coordinates = textured;
  out.texture = std::move(texture);
  return out;
}

}  // namespace qs
