// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/io/load_input.h"

#include "quadsimp/io/mesh_io.h"

namespace qs {

Input load_input(const std::string& path, const ConvertOptions& options, const LogFn& log,
                 const Retriangulate& retriangulate) {
  return prepare_input(read_mesh(path), path, options, log, retriangulate);
}

}  // namespace qs
