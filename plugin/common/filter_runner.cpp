// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "filter_runner.h"

#include <chrono>
#include <cstdio>

#include "quadsimp/convert/prepare_input.h"
#include "quadsimp/fitmap/fitmap.h"
#include "quadsimp/metrics/metrics.h"
#include "quadsimp/reference/reference_surface.h"
#include "quadsimp/util/errors.h"

namespace qs::plugin {
namespace {

LogFn log_into(Outcome& o) {
  return [&o](std::string_view m) { o.log.emplace_back(m); };
}

std::string format(const char* fmt, double a, double b = 0, double c = 0, double d = 0) {
  char buf[512];
  std::snprintf(buf, sizeof buf, fmt, a, b, c, d);
  return buf;
}

void describe_input(const Input& in, const std::string& name, Outcome& o) {
  if (in.was_pure_quad) return;
  const auto& r = in.convert;
  o.log.push_back(name + format(": %g triangles paired into %g quads (%.2f%% paired; %g border splits)",
                                r.input_triangles, r.quads, 100 * r.pairing_rate(),
                                double(r.parity_splits + r.border_splits)) +
                  (r.rim_splits ? format(", %g cone rims split", r.rim_splits) : "") +
                  (r.refined ? ", refined once" : ""));
  if (r.mended || r.not_mended)
    o.log.push_back(name + format(": %g quads non-convex or bent over %g degrees, after %g re-paired", r.not_mended,
                                  ConvertOptions().max_dihedral_deg, r.mended));
}

// The prepared (and simplified) input's quads, each split as MeshLab will draw it, with the
// input's texture (Input::source) baked onto them that way.
LayerQuads quads_of(Input& in, const std::vector<Image>& images, int texture_size, Outcome& o) {
  LayerQuads out;
  TextureBakeOptions options;
  options.max_side = texture_size;
  options.split = split_diagonals(in.quads);
  if (!in.source.texture.empty()) {
    out.texture = bake_texture(in.source.positions, in.source.texture, images, in.quads, options);
    if (std::string note = oversize_note(out.texture, texture_size); !note.empty()) o.log.push_back(std::move(note));
  }
  out.split = std::move(options.split);
  out.mesh = std::move(in.quads);
  return out;
}

}  // namespace

LayerQuads run_simplification(MeshFile layer, const std::string& name, const SimplifyParams& params,
                              const ProgressFn& progress, Outcome& o, const std::vector<Image>& images,
                              int texture_size) {
  const auto t0 = std::chrono::steady_clock::now();
  Input in = prepare_input(std::move(layer), name, convert_options(params), log_into(o));
  describe_input(in, name, o);
  const Fitmaps fitmaps = input_fitmaps(in, params, progress);  // before ref: input_fitmaps()
  const ReferenceSurface ref(std::move(in.reference));
  const SimplifyReport r = simplify_input(in, ref, params, progress, &fitmaps);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::vector<Index> flawed;
  const QuadQuality q = quad_quality(in.quads, &ref, &flawed);
  o.log.push_back(format("quad mesh simplification: %g -> %g quads in %.2f s (", r.initial_faces, r.faces, s) +
                  operations_done(r) +
                  format("); regular %.1f%%, max valence %g", q.regular_percent, q.max_valence));
  for (std::string& note : result_notes(r, q, r.target_faces)) o.log.push_back(std::move(note));
  flawed = noted_faces(flawed, r);
  if (!flawed.empty())
    o.log.push_back(format("the %g quads counted above (non-convex, flipped, folded or beyond the reach) are "
                           "selected in the new layer",
                           double(flawed.size())));
  o.values = {{"faces", q.faces}, {"vertices", q.vertices}, {"regular_percent", q.regular_percent},
              {"max_valence", q.max_valence}, {"seconds", s}};
  LayerQuads out = quads_of(in, images, texture_size, o);
  out.flawed = std::move(flawed);
  return out;
}

LayerQuads run_conversion(MeshFile layer, const std::string& name, double crease_angle, Outcome& o,
                          const std::vector<Image>& images, int texture_size) {
  SimplifyParams params;  // checked as the simplification's
  params.target_faces = 1;
  params.crease_angle = crease_angle;
  if (const std::string why = check_params(params); !why.empty()) throw std::invalid_argument(why);
  ConvertOptions options = convert_options(params);
  options.convex_pairs = true;  // the quads are the result here
  Input in = prepare_input(std::move(layer), name, options, log_into(o));
  describe_input(in, name, o);
  o.values = {{"faces", in.quads.n_faces()}, {"pairing_rate", in.convert.pairing_rate()}};
  return quads_of(in, images, texture_size, o);
}

Fitmaps run_fitmaps(const MeshFile& layer, const std::string& name, double tau, const ProgressFn& progress,
                    Outcome& o) {
  TriMesh tri = cleaned_surface(layer, name, log_into(o));
  FitmapOptions fo;
  fo.tau = tau;
  fo.progress = progress;
  const Fitmaps on_clean = compute_fitmaps(tri, fo);
  const ReferenceSurface ref(std::move(tri));
  Fitmaps out;
  out.s.resize(layer.positions.size());
  out.m.resize(layer.positions.size());
  for (std::size_t v = 0; v < layer.positions.size(); ++v) {
    const SurfacePoint p = ref.closest(layer.positions[v]);
    out.s[v] = p.found() ? float(ref.interpolate(on_clean.s, p)) : 0.f;
    out.m[v] = p.found() ? float(ref.interpolate(on_clean.m, p)) : 0.f;
  }
  o.log.push_back(name + format(": fitmaps of %g vertices (tau %g)", double(layer.positions.size()), tau));
  return out;
}

void run_quality(const MeshFile& quads, const std::string& quads_name, const MeshFile& reference,
                 const std::string& reference_name, unsigned samples, Outcome& o) {
  if (!quads.is_pure_quad())
    throw InvalidInput(quads_name + ": not a pure quad mesh (" + std::to_string(quads.triangles.size()) +
                       " triangles that do not pair up through faux edges)");
  QuadMesh q;
  try {
    q = QuadMesh::from_faces(quads.positions, quads.quads);
  } catch (const InvalidInput& e) {
    throw InvalidInput(quads_name + ": " + e.what());
  }
  TriMesh tri = cleaned_surface(reference, reference_name, log_into(o));
  const ReferenceSurface ref(std::move(tri));
  const QuadQuality qq = quad_quality(q, &ref);
  const SurfaceDistance d = surface_distance(q, ref, samples);
  o.values = {{"faces", qq.faces},
              {"vertices", qq.vertices},
              {"max_valence", qq.max_valence},
              {"regular_percent", qq.regular_percent},
              {"valence4_percent", qq.valence4_percent},
              {"homeometry_min", qq.homeometry_min},
              {"homeometry_max", qq.homeometry_max},
              {"nonconvex_faces", qq.nonconvex_faces},
              {"flipped_faces", qq.flipped_faces},
              {"folded_faces", qq.folded_faces},
              {"two_quad_pieces", qq.two_quad_pieces},
              {"hausdorff_e3", 1e3 * d.hausdorff},
              {"rms_e3", 1e3 * d.rms},
              {"mean_to_reference_e3", 1e3 * d.mean_to_ref},
              {"max_to_reference_e3", 1e3 * d.max_to_ref},
              {"max_from_reference_e3", 1e3 * d.max_from_ref},
              {"rms_to_reference_e3", 1e3 * d.rms_to_ref},
              {"projectability", d.projectability},
              {"reference_diagonal", ref.bbox_diagonal()}};
  o.log.push_back(quads_name + format(": %g quads, max valence %g, regular %.1f%%, ", qq.faces, qq.max_valence,
                                      qq.regular_percent) +
                  format("homeometry %.3f .. %.3f, %g non-convex, %g folded", qq.homeometry_min, qq.homeometry_max,
                         qq.nonconvex_faces, qq.folded_faces));
  o.log.push_back("distance to " + reference_name +
                  format(" (x1e-3 of its diagonal): Hausdorff %.3f, RMS %.3f, mean quads->reference %.3f, "
                         "projectability %.2f%%",
                         1e3 * d.hausdorff, 1e3 * d.rms, 1e3 * d.mean_to_ref, 100 * d.projectability));
}

}  // namespace qs::plugin
