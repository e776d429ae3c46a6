// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
//
// Lines of a text mesh file (OBJ, OFF, a PLY header) split into fields, '#' comments and blank lines
// skipped, numbered for messages; numbers read from whole fields (parse_number()).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "quadsimp/mesh/mesh_file.h"
#include "quadsimp/util/errors.h"
#include "quadsimp/util/parse_number.h"
#include "quadsimp/util/types.h"

namespace qs::detail {

//! A field of the file quoted for a message: bytes that are not printable ASCII shown
//! as '?', and at most 40 of them, so that a binary file's bytes stay out of the terminal.
inline std::string quoted(std::string_view field) {
  std::string q = "'";
  for (std::size_t i = 0; i < std::min<std::size_t>(field.size(), 40); ++i)
    q += field[i] >= 0x20 && field[i] < 0x7f ? field[i] : '?';
  return q + (field.size() > 40 ? "...'" : "'");
}

inline void split_fields(std::string_view line, std::vector<std::string_view>& fields) {
  fields.clear();
  for (std::size_t b = line.find_first_not_of(" \t\r"); b != std::string_view::npos;) {
    const std::size_t e = std::min(line.find_first_of(" \t\r", b), line.size());
    fields.push_back(line.substr(b, e - b));
    b = line.find_first_not_of(" \t\r", e);
  }
}

class TextLines {
 public:
  //! With `continued_lines` (OBJ), a line whose last character outside a comment is a
  //! backslash goes on on the next one, as the format has it.
  explicit TextLines(const std::string& path, bool continued_lines = false)
      : path_(path), in_(path), continued_lines_(continued_lines) {
    if (!in_) throw InvalidInput(path_ + ": cannot be opened for reading");
  }

  //! Moves to the next line with a field; false at the end of the file. Messages give the
  //! line a statement starts on.
  bool next() {
    while (std::getline(in_, line_)) {
      number_ = ++read_;
      if (read_ == 1 && line_.rfind("\xEF\xBB\xBF", 0) == 0) line_.erase(0, 3);  // a UTF-8 byte order mark
      while (continued_lines_ && goes_on(line_) && std::getline(in_, more_)) {
        line_ += ' ';
        line_ += more_;
        ++read_;
      }
      split_fields(std::string_view(line_).substr(0, line_.find('#')), fields_);
      if (!fields_.empty()) return true;
    }
    return false;
  }

  //! Fields [from, from + 3) as a position.
  Vec3 position(std::size_t from) const {
    if (fields_.size() < from + 3) fail("a vertex needs three coordinates");
    Vec3 p;
    for (int k = 0; k < 3; ++k)
      if (!parse_number(fields_[from + k], p[k]))
        fail(quoted(fields_[from + k]) + " is not a number (a vertex coordinate)");
    return p;
  }

  //! Fields from `from` on as a colour (red, green, blue, and alpha if a fourth field
  //! follows): fractions of 1 if `fractions` or if any of them has a decimal point or an
  //! exponent ("1 0.5 0" is orange, not a byte of red), else bytes. False if three
  //! numbers are not there.
  bool colour(std::size_t from, bool fractions, Colour& c) const {
    if (fields_.size() < from + 3) return false;
    const std::size_t n = std::min<std::size_t>(4, fields_.size() - from);
    for (std::size_t k = 0; k < n; ++k)
      fractions |= fields_[from + k].find_first_of(".eE") != std::string_view::npos;
    c[3] = 255;
    for (std::size_t k = 0; k < n; ++k) {
      double x;
      if (!parse_number(fields_[from + k], x)) return false;
      c[k] = colour_byte(fractions ? 255 * x : x);
    }
    return true;
  }

  //! The first `length` characters of field i as a whole number; `what` names it in the
  //! message if they are not one.
  long long whole_number(std::size_t i, const char* what, std::size_t length = std::string_view::npos) const {
    long long x;
    if (!parse_number(fields_[i].substr(0, length), x)) fail(quoted(fields_[i]) + " is not " + what);
    return x;
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
  long line_number() const { return number_; }

 private:
  // Whether `line` ends in a backslash outside a comment; drops it if so.
  static bool goes_on(std::string& line) {
    const std::size_t end = line.find_last_not_of(" \t\r");
    if (end == std::string::npos || line[end] != '\\' || line.find('#') < end) return false;
    line.resize(end);
    return true;
  }
  std::string path_;
  std::ifstream in_;
  bool continued_lines_;
  std::string line_, more_;
  long number_ = 0, read_ = 0;  // the statement's first line, and the lines read
  std::vector<std::string_view> fields_;
};

//! Appends the polygon of corners c[0..n) fanned from its first corner, with bit k of
//! each flag marking edge k (corner k to k+1) as inside the polygon, as vcglib and
//! MeshLab mark them.
inline void fan(const Index* c, std::size_t n, std::vector<std::array<Index, 3>>& triangles,
                std::vector<std::uint8_t>& faux) {
  for (std::size_t i = 1; i + 1 < n; ++i) {
    triangles.push_back({c[0], c[i], c[i + 1]});
    faux.push_back(std::uint8_t((i > 1 ? 1u : 0u) | (i + 2 < n ? 4u : 0u)));
  }
}

//! The same with the corners' texture coordinates uv[0..n), into image `image`, appended
//! to a file's texture.
inline void fan(const Index* c, const TexCoord* uv, std::size_t n, int image, FileTexture& t) {
  for (std::size_t i = 1; i + 1 < n; ++i) {
    t.triangles.push_back({c[0], c[i], c[i + 1]});
    t.coords.push_back({uv[0], uv[i], uv[i + 1]});
    t.image.push_back(image);
  }
}

//! A file that a mesh file names (an image), as a path from `folder`, the mesh file's;
//! Windows' separators read as such.
inline std::string file_beside(const std::filesystem::path& folder, std::string name) {
  std::replace(name.begin(), name.end(), '\\', '/');
  return (folder / name).string();
}

}  // namespace qs::detail
