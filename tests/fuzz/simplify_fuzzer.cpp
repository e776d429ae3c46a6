// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: a small mesh file is loaded (cleaned, converted) and simplified with
// options its first two bytes choose, and measured as the CLI measures it: the result must
// pass validate(), its vertices and distances be finite, its report say its count, a
// second run give the same quads, and a textured input's texture be baked onto them; the
// conversion filter's pairing of the same triangles must be sound too.
// Refusing the file (InvalidInput) is fine; any other exception, a TopologyError above
// all, a crash, a sanitizer report or a hang is a bug.
// The meshes are small (odd geometry, not size, is what breaks operators), so each input
// takes milliseconds.
#include <cmath>

#include "fuzz_input.h"
#include "quadsimp/convert/tri_to_quad.h"
#include "quadsimp/io/images.h"
#include "quadsimp/io/load_input.h"
#include "quadsimp/metrics/metrics.h"
#include "quadsimp/reference/reference_surface.h"
#include "quadsimp/simplify/pipeline.h"
#include "quadsimp/util/errors.h"

namespace {

using qs::fuzz::require;

bool same_quads(const qs::QuadMesh& a, const qs::QuadMesh& b) {
  if (a.vertex_capacity() != b.vertex_capacity() || a.face_capacity() != b.face_capacity()) return false;
  for (qs::Index v = 0; v < a.vertex_capacity(); ++v)
    if (a.is_vertex_live(v) != b.is_vertex_live(v) || (a.is_vertex_live(v) && a.position(v) != b.position(v)))
      return false;
  for (qs::Index f = 0; f < a.face_capacity(); ++f)
    if (a.is_face_live(f) != b.is_face_live(f) || (a.is_face_live(f) && a.face_vertices(f) != b.face_vertices(f)))
      return false;
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 3) return 0;
  // Byte 0: the format (fuzz_input.h), the mode, and the target in sixteenths of the quads.
  // Byte 1: one bit per option, and the M-fitmap's tolerance.
  const std::uint8_t mode = data[0], flags = data[1];
  qs::SimplifyParams params;
  params.adaptive = mode & 4;
  params.auto_halt = params.adaptive && (mode & 8);
  params.preserve_boundary = flags & 1;
  params.keep_tips = flags & 2;
  params.crease_angle = (flags & 4) ? 30 : 0;
  params.fast = flags & 8;
  params.fit_to_input = flags & 16;
  params.max_aspect = (flags & 32) ? 1 : params.max_aspect;
  params.tau = (flags & 64) ? 0.2 : (flags & 128) ? 0.01 : params.tau;
  qs::Input in;
  try {
    in = qs::load_input(qs::fuzz::write_mesh(data, size, 2), qs::convert_options(params));
  } catch (const qs::InvalidInput&) {
    return 0;
  }
  if (in.quads.n_faces() > 2000) return 0;
  // The conversion filter's pairing of the same triangles (ConvertOptions::convex_pairs): a
  // sound mesh, as many quads where both made the same splits. (Pairs left across creases,
  // split into two quads each, may differ: the first search can find a pairing within the
  // parts between creases where the plain one does not.)
  if (!in.was_pure_quad) {
    qs::ConvertOptions options = qs::convert_options(params);
    options.convex_pairs = true;
    qs::ConvertReport convex;
    const qs::QuadMesh q = qs::tri_to_quad(in.reference, options, &convex);
    qs::validate(q);
    const qs::ConvertReport& plain = in.convert;
    require(convex.refined || plain.refined || convex.border_splits != plain.border_splits ||
                convex.crease_midpoints != plain.crease_midpoints || q.n_faces() == in.quads.n_faces(),
            "the convex pairing made another number of quads");
  }
  if (!params.auto_halt) params.target_faces = 1 + (mode >> 4) * in.quads.n_faces() / 16;
  // Every eighth input (by size) is simplified twice: the same quads, bit for bit, though
  // the fitmaps and the distances run on TBB's threads.
  const bool twice = size % 8 == 0;
  qs::Input again = twice ? in : qs::Input{};
  const qs::ReferenceSurface ref(std::move(in.reference));
  const qs::SimplifyReport report = qs::simplify_input(in, ref, params);
  qs::validate(in.quads);
  if (twice) {
    qs::simplify_input(again, ref, params);
    require(same_quads(in.quads, again.quads), "two runs on one input gave different quads");
  }
  // What the CLI does with the result: its measures and the log's notes.
  require(report.faces == in.quads.n_faces(), "the report's face count is not the mesh's");
  for (qs::Index v = 0; v < in.quads.vertex_capacity(); ++v)
    require(!in.quads.is_vertex_live(v) || in.quads.position(v).allFinite(), "a vertex is not finite");
  const qs::QuadQuality quality = qs::quad_quality(in.quads, &ref);
  const qs::SurfaceDistance d = qs::surface_distance(in.quads, ref, 1000);
  require(std::isfinite(d.hausdorff) && std::isfinite(d.rms) && d.projectability >= 0 && d.projectability <= 1,
          "a distance is not finite, or projectability is not a share");
  qs::result_notes(report, quality, params.target_faces);
  // A textured input's texture baked onto the quads, as the CLI writes it (a small atlas:
  // its size does not change the code that runs). An image that cannot be read (a
  // material naming a missing file) is refused, and the CLI writes no texture.
  if (!in.source.texture.empty()) {
    qs::TextureBakeOptions small;
    small.max_side = qs::TextureBakeOptions::kSmallestSide;
    qs::QuadTexture t;
    try {
      t = qs::texture_of_quads(in.source, in.quads, small);
    } catch (const qs::InvalidInput&) {
      return 0;
    }
    require(!t.empty() && t.corners.size() == in.quads.face_capacity(), "a texture without a tile per quad");
    for (qs::Index f = 0; f < in.quads.face_capacity(); ++f)
      for (const qs::TexCoord& c : t.corners[f])
        require(!in.quads.is_face_live(f) || (c[0] >= 0 && c[0] <= 1 && c[1] >= 0 && c[1] <= 1),
                "a quad corner's texture coordinates outside the atlas");
  }
  return 0;
}
