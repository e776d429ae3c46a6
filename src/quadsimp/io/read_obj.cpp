// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
//
// OBJ is read here, not by vcglib: its reader took a coordinate that is not a number for
// 0, followed face corners naming no vertex into memory it did not own (a crash),
// dropped a triangle naming a later vertex without a word, and read a comment after a
// face's corners as more corners. It also took 2.7 s on a 1.1M-triangle file.
#include <string_view>
#include <vector>

#include "quadsimp/io/text_lines.h"
#include "quadsimp/io/text_readers.h"

namespace qs {

MeshFile read_obj(const std::string& path) {
  detail::TextLines in(path);
  std::vector<Vec3> positions;
  // Vertex colours after the coordinates, as fractions (MeshLab's extension); kept only if
  // every vertex has one.
  std::vector<Colour> colours;
  bool coloured = true;
  std::vector<std::array<Index, 3>> triangles;
  std::vector<std::uint8_t> faux;
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
      detail::fan(corners.data(), corners.size(), triangles, faux);  // fewer than three corners: no face
    }
  }
  MeshFile out = pair_faux_triangles(std::move(positions), std::move(triangles), faux);
  if (coloured) out.colours = std::move(colours);
  return out;
}

}  // namespace qs
