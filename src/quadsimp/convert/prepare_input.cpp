// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/convert/prepare_input.h"

#include "quadsimp/util/errors.h"

namespace qs {

Input prepare_input(MeshFile file, const std::string& name, const ConvertOptions& options, const LogFn& log) {
  Input in;
  in.reference = triangles_of(file);
  in.clean = clean(in.reference, name, log);
  sort_spatially(in.reference);
  in.was_pure_quad = file.is_pure_quad();
  if (in.was_pure_quad) {
    try {
      in.quads = QuadMesh::from_faces(std::move(file.positions), file.quads);
    } catch (const InvalidInput& e) {
      throw InvalidInput(name + ": " + e.what());
    }
    if (log) log(name + ": already a pure quad mesh (" + std::to_string(in.quads.n_faces()) + " quads)");
  } else {
    in.quads = tri_to_quad(in.reference, options, &in.convert);
  }
  return in;
}

}  // namespace qs
