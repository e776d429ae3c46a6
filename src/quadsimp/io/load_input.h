// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <string>

#include "quadsimp/convert/prepare_input.h"

namespace qs {

//! read_mesh() then prepare_input(): a mesh file made ready for simplification.
//! \throw InvalidInput "PATH: reason" for anything that cannot be used.
Input load_input(const std::string& path, const ConvertOptions& options = {}, const LogFn& log = {},
                 const Retriangulate& retriangulate = {});

}  // namespace qs
