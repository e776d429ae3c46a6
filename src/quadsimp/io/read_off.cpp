// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
//
// OFF is read here, not by vcglib: its reader followed face corners it never checked
// (a corner past the vertices crashed, a face line cut short read past its tokens),
// put the triangles of a polygon of five or more corners on the file's first vertices,
// and split quads through a static set of diagonals shared by every call.
#include "quadsimp/io/text_readers.h"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string_view>
#include <vector>

#include "quadsimp/io/text_lines.h"

namespace qs {

MeshFile read_off(const std::string& path) {
  detail::TextLines in(path);
  if (!in.next()) in.ends("before its OFF header");

  // "[ST][C][N]OFF", then the counts on the same line or the next (some writers leave
  // out the space: "OFF490 518 0").
  // A copy: the fields are views of a line, which the next line replaces.
  const std::string header(in[0]);
  const std::string_view word = header;
  const std::size_t off = word.find("OFF");
  if (off == std::string_view::npos) in.fail(detail::quoted(word) + " is not an OFF header");
  for (const char c : word.substr(0, off))
    if (c == '4' || c == 'n') in.fail(detail::quoted(word) + ": only three-dimensional OFF is read");
  std::vector<std::string_view> counts(in.fields().begin() + 1, in.fields().end());
  if (off + 3 < word.size()) counts.insert(counts.begin(), word.substr(off + 3));
  if (!counts.empty() && counts[0] == "BINARY") in.fail("binary OFF is not read (ASCII only)");
  if (counts.empty()) {
    if (!in.next()) in.ends("before its vertex and face counts");
    counts = in.fields();
  }
  long long nv = -1, nf = -1;
  if (counts.size() < 2 || !parse_number(counts[0], nv) || !parse_number(counts[1], nf) || nv < 0 || nf < 0)
    in.fail("no vertex and face counts (two whole numbers) after the OFF header");
  if (nv > std::numeric_limits<Index>::max()) in.fail(std::to_string(nv) + " vertices are more than quadsimp indexes");

  // A count beyond what the file could hold is not reserved for: the lines run out first.
  std::error_code ec;
  const auto bytes = static_cast<long long>(std::filesystem::file_size(path, ec));
  std::vector<Vec3> positions;
  std::vector<std::array<Index, 3>> triangles;
  std::vector<std::uint8_t> faux;
  positions.reserve(std::size_t(std::min(nv, bytes / 6)));
  triangles.reserve(std::size_t(std::min(nf, bytes / 8)));
  faux.reserve(triangles.capacity());

  // COFF: each vertex's colour after its position (and its normal, in CNOFF); kept only
  // if every vertex has one.
  const std::string_view prefix = word.substr(0, off);
  bool coloured = prefix.find('C') != std::string_view::npos;
  const std::size_t colour_at = prefix.find('N') != std::string_view::npos ? 6 : 3;
  std::vector<Colour> colours;
  for (long long i = 0; i < nv; ++i) {
    if (!in.next()) in.ends("after " + std::to_string(i) + " of its " + std::to_string(nv) + " vertices");
    positions.push_back(in.position(0));
    Colour c;
    if (coloured && (coloured = in.colour(colour_at, false, c))) colours.push_back(c);
  }

  // A face's colour after its corners (bytes, or fractions with a decimal point); kept only
  // if every face has one (a single number there is an index into a colour map: none).
  // MeshLab leaves a face without one at whatever its memory held (pymeshlab 2025.7 gave
  // 130, 85, 0, 0 and 208, 28, 31, 119 in two files): there is no colour of its to follow.
  bool face_coloured = nf > 0;
  std::vector<Colour> face_colours;
  std::vector<Index> corners;
  for (long long f = 0; f < nf; ++f) {
    if (!in.next()) in.ends("after " + std::to_string(f) + " of its " + std::to_string(nf) + " faces");
    const long long n = in.whole_number(0, "a corner count (a face)");
    if (n < 2) in.fail("a face listed with only " + std::to_string(n) + " corner(s)");
    std::size_t first = 1;
    if (in.size() == 1) {  // the count alone, the corners on the next line
      if (!in.next()) in.ends("before the corners of its last face");
      first = 0;
    }
    if (in.size() - first < std::size_t(n))
      in.fail("a face of " + std::to_string(n) + " corners lists " + std::to_string(in.size() - first));
    corners.clear();
    for (std::size_t k = first; k < first + std::size_t(n); ++k) {
      const long long c = in.whole_number(k, "a vertex number (a face corner)");
      if (c < 0 || c >= nv)
        in.fail("face corner " + std::to_string(c) + " names no vertex (the file has " + std::to_string(nv) + ")");
      corners.push_back(Index(c));
    }
    if (n < 3) continue;  // two corners: an edge, not a face
    detail::fan(corners.data(), corners.size(), triangles, faux);
    Colour c;
    if (face_coloured && (face_coloured = in.colour(first + std::size_t(n), false, c)))
      face_colours.resize(triangles.size(), c);
  }
  if (!face_coloured) face_colours.clear();
  MeshFile out = pair_faux_triangles(std::move(positions), std::move(triangles), faux, face_colours);
  if (coloured) out.colours = std::move(colours);
  out.texture_coordinates = prefix.find("ST") != std::string_view::npos;  // each vertex's after its position
  return out;
}

}  // namespace qs
