// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <charconv>
#include <string_view>
#include <system_error>

namespace qs {

//! A number read from a whole field: "0.5x" is not a number (where atof takes it for 0.5),
//! a leading '+' is allowed (std::from_chars takes none, strtod does). Used by the mesh
//! readers and the CLI's option checks.
template <class T>
bool parse_number(std::string_view field, T& x) {
  if (!field.empty() && field[0] == '+') field.remove_prefix(1);
  const auto r = std::from_chars(field.data(), field.data() + field.size(), x);
  return r.ec == std::errc() && r.ptr == field.data() + field.size();
}

}  // namespace qs
