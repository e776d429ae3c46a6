// The README's library example: a mesh file simplified to N quads, written out.
// Usage: simplify_file IN OUT N [adaptive|remeshed]
#include <cstdio>
#include <cstdlib>
#include <string>

#include <quadsimp/io/load_input.h>
#include <quadsimp/io/mesh_io.h>
#include <quadsimp/remesh/isotropic_remesh.h>
#include <quadsimp/simplify/pipeline.h>
#include <quadsimp/util/errors.h>

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: %s IN OUT N [adaptive|remeshed]\n", argv[0]);
    return 2;
  }
  try {
    const std::string mode = argc > 4 ? argv[4] : "";
    qs::Retriangulate remesh;  // the CLI's --remesh
    if (mode == "remeshed") remesh = [](const qs::TriMesh& surface) { return qs::remesh_isotropic(surface); };
    qs::Input in = qs::load_input(argv[1], {}, {}, remesh);  // cleaned, converted to quads
    qs::SimplifyParams params;
    params.target_faces = qs::Index(std::atoi(argv[3]));
    params.adaptive = mode == "adaptive";
    const qs::Fitmaps fitmaps = qs::input_fitmaps(in, params);  // adaptive mode's; before the surface
    const qs::ReferenceSurface reference(std::move(in.reference));
    const qs::SimplifyReport report = qs::simplify_input(in, reference, params, {}, &fitmaps);
    qs::write_quad_mesh(argv[2], in.quads);
    const qs::QuadQuality quality = qs::quad_quality(in.quads, &reference);
    std::printf("%u quads, %.1f%% regular, %u collapses\n", quality.faces, quality.regular_percent,
                report.collapses);
  } catch (const qs::InvalidInput& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
