// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
//
// Fields of a line of a text mesh file (OBJ, OFF), and numbers read from them whole:
// "0.5x" is not a number, where atof, which vcglib's readers use, takes it for 0.5.
#pragma once

#include <algorithm>
#include <charconv>
#include <string_view>
#include <system_error>
#include <vector>

namespace qs::detail {

inline void split_fields(std::string_view line, std::vector<std::string_view>& fields) {
  fields.clear();
  for (std::size_t b = line.find_first_not_of(" \t\r"); b != std::string_view::npos;) {
    const std::size_t e = std::min(line.find_first_of(" \t\r", b), line.size());
    fields.push_back(line.substr(b, e - b));
    b = line.find_first_not_of(" \t\r", e);
  }
}

template <class T>
bool parse_number(std::string_view field, T& x) {
  if (!field.empty() && field[0] == '+') field.remove_prefix(1);  // from_chars takes no '+', strtod does
  const auto r = std::from_chars(field.data(), field.data() + field.size(), x);
  return r.ec == std::errc() && r.ptr == field.data() + field.size();
}

}  // namespace qs::detail
