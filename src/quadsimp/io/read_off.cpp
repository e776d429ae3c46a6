// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
//
// OFF is read here, not by vcglib: its reader followed face corners it never checked
// (a corner past the vertices crashed, a face line cut short read past its tokens),
// put the triangles of a polygon of five or more corners on the file's first vertices,
// and split quads through a static set of diagonals shared by every call.
#include "quadsimp/io/read_off.h"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string_view>
#include <vector>

#include "quadsimp/io/text_fields.h"
#include "quadsimp/util/errors.h"

namespace qs {
namespace {

// Lines split into fields, '#' comments and blank lines skipped, numbered for messages.
class OffLines {
 public:
  explicit OffLines(const std::string& path) : path_(path), in_(path) {
    if (!in_) fail("cannot be opened for reading");
  }

  bool next() {
    while (std::getline(in_, line_)) {
      ++number_;
      detail::split_fields(std::string_view(line_).substr(0, line_.find('#')), fields_);
      if (!fields_.empty()) return true;
    }
    return false;
  }

  const std::vector<std::string_view>& fields() const { return fields_; }
  std::string_view operator[](std::size_t i) const { return fields_[i]; }
  std::size_t size() const { return fields_.size(); }

  [[noreturn]] void fail(const std::string& why) const {
    throw InvalidInput(path_ + ": line " + std::to_string(number_) + ": " + why);
  }
  [[noreturn]] void ends(const std::string& before) const {
    throw InvalidInput(path_ + ": the file ends " + before);
  }

 private:
  std::string path_;
  std::ifstream in_;
  std::string line_;
  long number_ = 0;
  std::vector<std::string_view> fields_;
};

}  // namespace

MeshFile read_off(const std::string& path) {
  OffLines in(path);
  if (!in.next()) in.ends("before its OFF header");

  // "[ST][C][N]OFF", then the counts on the same line or the next (some writers leave
  // out the space: "OFF490 518 0").
  const std::string_view word = in[0];
  const std::size_t off = word.find("OFF");
  if (off == std::string_view::npos) in.fail("'" + std::string(word) + "' is not an OFF header");
  for (const char c : word.substr(0, off))
    if (c == '4' || c == 'n') in.fail("'" + std::string(word) + "': only three-dimensional OFF is read");
  std::vector<std::string_view> counts(in.fields().begin() + 1, in.fields().end());
  if (off + 3 < word.size()) counts.insert(counts.begin(), word.substr(off + 3));
  if (!counts.empty() && counts[0] == "BINARY") in.fail("binary OFF is not read (ASCII only)");
  if (counts.empty()) {
    if (!in.next()) in.ends("before its vertex and face counts");
    counts = in.fields();
  }
  long long nv = -1, nf = -1;
  if (counts.size() < 2 || !detail::parse_number(counts[0], nv) || !detail::parse_number(counts[1], nf) || nv < 0 || nf < 0)
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

  for (long long i = 0; i < nv; ++i) {
    if (!in.next()) in.ends("after " + std::to_string(i) + " of its " + std::to_string(nv) + " vertices");
    if (in.size() < 3) in.fail("a vertex needs three coordinates");
    Vec3 p;
    for (int k = 0; k < 3; ++k)
      if (!detail::parse_number(in[k], p[k])) in.fail("'" + std::string(in[k]) + "' is not a number (a vertex coordinate)");
    positions.push_back(p);
  }

  std::vector<Index> corners;
  for (long long f = 0; f < nf; ++f) {
    if (!in.next()) in.ends("after " + std::to_string(f) + " of its " + std::to_string(nf) + " faces");
    long long n;
    if (!detail::parse_number(in[0], n)) in.fail("'" + std::string(in[0]) + "' is not a corner count (a face)");
    if (n < 2) in.fail("a face listed with only " + std::to_string(n) + " corner(s)");
    std::size_t first = 1;
    if (in.size() == 1) {  // the count alone, the corners on the next line
      if (!in.next()) in.ends("before the corners of its last face");
      first = 0;
    }
    // Fields after the corners are the face's colour.
    if (in.size() - first < std::size_t(n))
      in.fail("a face of " + std::to_string(n) + " corners lists " + std::to_string(in.size() - first));
    corners.clear();
    for (std::size_t k = first; k < first + std::size_t(n); ++k) {
      long long c;
      if (!detail::parse_number(in[k], c)) in.fail("'" + std::string(in[k]) + "' is not a vertex number (a face corner)");
      if (c < 0 || c >= nv)
        in.fail("face corner " + std::to_string(c) + " names no vertex (the file has " + std::to_string(nv) + ")");
      corners.push_back(Index(c));
    }
    if (n == 2) continue;  // an edge, not a face
    // A fan from the first corner; bit k of the flags marks edge k (corner k to k+1) as
    // inside the polygon, as vcglib's readers mark them.
    for (std::size_t i = 1; i + 1 < corners.size(); ++i) {
      triangles.push_back({corners[0], corners[i], corners[i + 1]});
      faux.push_back(std::uint8_t((i > 1 ? 1u : 0u) | (i + 2 < corners.size() ? 4u : 0u)));
    }
  }
  return pair_faux_triangles(std::move(positions), std::move(triangles), faux);
}

}  // namespace qs
