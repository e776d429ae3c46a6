// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/convert/prepare_input.h"

#include <algorithm>
#include <cmath>

#include "quadsimp/mesh/quad_geometry.h"
#include "quadsimp/util/errors.h"

namespace qs {
namespace {

// A triangle whose height over its longest edge is under this is long and thin.
constexpr double kThinTriangle = 0.1;
// Loading says so when such triangles cover more than this share of the surface. CAD
// tessellations made of them came out poorly: a cylinder of one row of triangles round
// its side (fans on its caps), a cone of four rows round its tip, a sphere of 30 rings of
// 1,000 triangles are all thin and ended with vertices of valence 22 to 605, folded quads,
// or far above their targets (the cone of 4,000 round its tip after two minutes). The
// datasets have under 0.1% of their area in such triangles; a sphere of 100 rings of 400
// has 2%, a cylinder of eight rows 33% (its caps): those three give even quads.
constexpr double kThinShare = 0.5;

double thin_area_share(const TriMesh& t) {
  double thin = 0, total = 0;
  Index longest;
  for (const auto& f : t.faces) {
    const double area2 = t.area_normal(f).norm();
    total += area2;
    if (thinness(t, f, longest) < kThinTriangle) thin += area2;
  }
  return total > 0 ? thin / total : 0.0;
}

}  // namespace

TriMesh cleaned_surface(const MeshFile& file, const std::string& name, const LogFn& log, CleanReport* report) {
  // First: the repairs that follow may come of it.
  if (file.skipped_lines && log)
    log(name + ": " + std::to_string(file.skipped_lines) + " line(s) that begin with no OBJ statement skipped (the " +
        "first: " + file.first_skipped + "); if a vertex's 'v' was lost, every later vertex is out of place");
  // A quad mesh is someone's surface, not a raw scan, and a coarse one's thin parts have
  // edges as sharp as a fold's bounds: the armadillo simplified to 1,000 quads, loaded
  // again, had a claw's tip laid flat, its vertices moved by up to 28% of the diagonal
  // (bench/RESULTS.md). Only its folds at a quad that folds over itself are laid flat, a
  // defect whoever made the mesh: a scan paired into quads keeps its Z-folds' quads
  // folded. Any folded quad once let every fold of the file be laid flat: the armadillo's
  // 800 uniform quads, one folded at a foot, had an ear's tip moved by 10% of the diagonal.
  CleanOptions options;
  if (file.is_pure_quad()) {
    const auto& P = file.positions;
    auto& points = options.folds_only_at.emplace();
    for (const auto& q : file.quads)  // indices out of range: clean() refuses them
      if (std::all_of(q.begin(), q.end(), [&](Index v) { return v < P.size(); }) &&
          quad_folds(P[q[0]], P[q[1]], P[q[2]], P[q[3]]))
        for (Index v : q) points.push_back(P[v]);
  }
  TriMesh t = triangles_of(file);
  const CleanReport r = clean(t, name, log, options);
  if (report) *report = r;
  return t;
}

Input prepare_input(MeshFile file, const std::string& name, const ConvertOptions& options, const LogFn& log,
                    const Retriangulate& retriangulate) {
  Input in;
  in.reference = cleaned_surface(file, name, log, &in.clean);
  if (retriangulate) {
    // Kept as cleaned_surface() gives it, so that it is measured as `quadsimp stats` does.
    in.input_surface = std::move(in.reference);
    in.reference = retriangulate(in.input_surface);
    clean(in.reference, name + " (remeshed)", log);
  }
  sort_spatially(in.reference);
  const double thin = log && !retriangulate ? thin_area_share(in.reference) : 0.0;
  if (thin > kThinShare)
    log(name + ": " + std::to_string(int(std::lround(100 * thin))) +
        "% of the surface is long, thin triangles (height under a tenth of the longest edge), as CAD "
        "tessellations write them: the quads made of them are long and thin too, and simplifying them leaves "
        "vertices of high valence and stops early; remesh first for even quads (quadsimp's --remesh; MeshLab: "
        "\"Remeshing: Isotropic Explicit Remeshing\")");
  // Quads that cleaning had to repair (vertices merged, faces removed, vertices split, faces
  // re-oriented) no longer match the repaired triangles: an unwelded quad soup stayed 100
  // separate quads that no collapse could join, one flipped quad refused the whole file.
  // Their triangles are paired again instead, as for a triangle mesh.
  const bool repaired = in.clean.changed_faces();
  in.was_pure_quad = file.is_pure_quad() && !repaired && !retriangulate;
  if (file.is_pure_quad() && repaired && log)
    log(name + ": the quads needed the repairs above; their triangles are paired into quads again");
  if (file.texture_coordinates && file.texture.empty() && log)
    log(name + ": its texture coordinates are not carried to the quads (not every face has coordinates and an "
               "image); MeshLab's \"Transfer: Texture to Vertex Color (1 or 2 meshes)\" colours the quads from the "
               "texture (pymeshlab: transfer_texture_to_color_per_vertex)");
  if (!file.texture.colours.empty() && log) {
    // Faces left out of a texture are often an exporter's slip (a part without UVs).
    const auto plain = std::count(file.texture.image.begin(), file.texture.image.end(), -1);
    log(name + ": " + std::to_string(plain) + " of its " + std::to_string(file.texture.image.size()) +
        " triangles have no texture (no coordinates, or a material without an image): the quads' texture shows "
        "their face colour there");
  }
  // Kept whole (Input::source).
  const bool coloured = !file.colours.empty() || file.has_face_colours() || !file.texture.empty();
  if (in.was_pure_quad) {
    try {
      in.quads = QuadMesh::from_faces(coloured ? file.positions : std::move(file.positions), file.quads);
    } catch (const InvalidInput& e) {
      throw InvalidInput(name + ": " + e.what());
    }
    if (log) log(name + ": already a pure quad mesh (" + std::to_string(in.quads.n_faces()) + " quads)");
  } else {
    in.quads = tri_to_quad(in.reference, options, &in.convert);
  }
  if (coloured) in.source = std::move(file);
  return in;
}

}  // namespace qs
