// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "cli/commands.h"

#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "quadsimp/fitmap/anisotropy.h"
#include "quadsimp/fitmap/fitmap.h"
#include "quadsimp/fitmap/tips.h"
#include "quadsimp/io/images.h"
#include "quadsimp/io/load_input.h"
#include "quadsimp/io/mesh_io.h"
#include "quadsimp/metrics/metrics.h"
#include "quadsimp/reference/reference_surface.h"
#include "quadsimp/remesh/isotropic_remesh.h"
#include "quadsimp/simplify/pipeline.h"
#include "quadsimp/util/errors.h"

#include <unistd.h>

namespace qs::cli {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

LogFn stderr_log(bool quiet) {
  if (quiet) return {};
  return [](std::string_view m) { std::cerr << "note: " << m << "\n"; };
}

// A one-line bar on a terminal, nothing when stderr is piped.
ProgressFn progress_bar(bool quiet) {
  if (quiet || !::isatty(STDERR_FILENO)) return {};
  return [last = -1](float f, std::string_view stage) mutable {
    const int pct = int(f * 100);
    if (pct == last) return true;
    last = pct;
    const int w = 40, filled = pct * w / 100;
    std::fprintf(stderr, "\r%-10.*s [%.*s%*s] %3d%%", int(stage.size()), stage.data(), filled,
                 "########################################", w - filled, "", pct);
    if (pct >= 100) std::fprintf(stderr, "\n");
    return true;
  };
}

void print_quality(const QuadQuality& q, const SurfaceDistance* d) {
  std::printf("faces %u, vertices %u (%u on the border, in %u loops), pure quad: yes\n", q.faces, q.vertices,
              q.border_vertices, q.border_loops);
  std::printf("valence: max %d (interior %d), regular %.1f%% (valence 4 inside, 3 on the border), valence-4 %.1f%%\n",
              q.max_valence, q.max_valence_interior, q.regular_percent, q.valence4_percent);
  std::printf("homeometry: min %.3f max %.3f (edges only: %.3f .. %.3f)\n", q.homeometry_min, q.homeometry_max,
              q.edge_ratio_min, q.edge_ratio_max);
  std::printf("non-convex faces %u, flipped faces %u, folded faces %u (bent over 90 degrees)\n", q.nonconvex_faces,
              q.flipped_faces, q.folded_faces);
  if (d)
    std::printf("distance x1e-3 of the bbox diagonal: Hausdorff %.3f, RMS %.3f, mean out->in %.3f "
                "(max out->in %.3f, in->out %.3f), projectability %.2f%%\n",
                1e3 * d->hausdorff, 1e3 * d->rms, 1e3 * d->mean_to_ref, 1e3 * d->max_to_ref, 1e3 * d->max_from_ref,
                100 * d->projectability);
}

// The input's triangles remeshed (--remesh) for the conversion, or nothing to do. Sharp
// edges stay edges at the crease angle, if one is given, so that the conversion finds them.
Retriangulate remesher(const RemeshArgs& r, double crease_angle, Index target_quads, double target_edge,
                       const std::string& name, const LogFn& log) {
  if (!r.on) return {};
  RemeshOptions o;
  o.edge_share = r.edge_percent / 100;
  o.target_quads = target_quads;
  if (crease_angle > 0) o.feature_angle_deg = crease_angle;
  return [=](const TriMesh& surface) {
    const auto t0 = std::chrono::steady_clock::now();
    RemeshOptions options = o;
    if (target_edge > 0) options.target_quads = faces_for_edge_length(surface_area(surface), target_edge);
    RemeshReport report;
    TriMesh out = remesh_isotropic(surface, options, &report);
    if (log) {
      char line[160];
      std::snprintf(line, sizeof line, ": remeshed %u triangles into %u, edges of %.3g%% of the diagonal (%.2f s)",
                    report.input_triangles, report.triangles, 100 * report.edge_length / report.diagonal,
                    seconds_since(t0));
      log(name + line);
    }
    return out;
  };
}

// Why the quads' texture may not be written where `output`'s goes: over an image of the
// input's texture (a scan.obj whose map_Kd is scan_texture.png, written as scan.ply), which
// would be lost. Empty if it may.
std::string texture_clash(const std::string& output, const Input& in) {
  namespace fs = std::filesystem;
  const std::string ours = texture_path_of(output);
  std::error_code ec;
  for (const std::string& image : in.source.texture.images)
    if (fs::exists(ours, ec) && fs::equivalent(ours, image, ec))
      return "the quads' texture " + ours + " would be written over the input's texture image; choose another "
             "output name";
  return {};
}

// The input's texture baked onto the quads, where the output keeps one (OBJ, PLY). An
// image that cannot be read leaves the texture out, and says so.
QuadTexture texture_for(const std::string& output, const Input& in, int size, const LogFn& log) {
  if (in.source.texture.empty()) return {};
  if (extension_of(output) == "off") {
    if (log) log(output + ": OFF keeps no texture; the input's is written with .obj or .ply output");
    return {};
  }
  try {
    TextureBakeOptions options;
    options.max_side = size;
    QuadTexture t = texture_of_quads(in.source, in.quads, options);
    if (const std::string note = oversize_note(t, size); log && !note.empty()) log(output + ": " + note);
    return t;
  } catch (const InvalidInput& e) {
    if (log) log(std::string(e.what()) + ": the quads are written without a texture");
    return {};
  }
}

// The quads with their colours and texture, as the output keeps them. Where the texture
// is not written, an OBJ's faces coloured beside it keep their colour: only the texture
// held it (a PLY keeps its face colours beside its texture).
void write_result(const std::string& output, const Input& in, int texture_size, const LogFn& log) {
  const QuadTexture texture = texture_for(output, in, texture_size, log);
  const MeshFile& from = in.source;
  const bool colours_left = texture.empty() && !from.texture.colours.empty() && !from.has_face_colours();
  if (colours_left && log)
    log(output + ": its quads take the colours of the input's faces instead (a textured face's is its material's)");
  write_quad_mesh(output, in.quads, colours_of_quads(colours_left ? texture_colours_as_faces(from) : from, in.quads),
                  texture);
}

void print_summary(const std::string& input, const std::string& output, const QuadQuality& q, double seconds,
                   const SimplifyReport& r) {
  std::printf("%s -> %s: %u faces, regular %.1f%%, max valence %d, %.2f s (%s)\n", input.c_str(), output.c_str(),
              q.faces, q.regular_percent, q.max_valence, seconds, operations_done(r).c_str());
}

// simplify --json: the result's quality and distance, and what the run did. `seconds`: the
// run's time through this level, the distance sampling of the levels before left out;
// `converted`: the quads the input converted to.
std::string simplify_json(const QuadQuality& q, const SurfaceDistance& d, const std::vector<Index>& flawed,
                          const SimplifyReport& r, double seconds, Index converted) {
  std::string j = to_json(q, &d, &flawed);
  const auto n = [](Index x) { return std::to_string(x); };
  char share[32], time[32];
  std::snprintf(share, sizeof share, "%.4f", r.blocked_share);
  std::snprintf(time, sizeof time, "%.4f", seconds);
  j.pop_back();
  return j + ", \"seconds\": " + time + ", \"threads\": " +
         n(Index(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism))) +
         ", \"collapses\": " + n(r.collapses) + ", \"border_collapses\": " + n(r.border_collapses) +
         ", \"border_insets\": " + n(r.border_insets) + ", \"tips\": " + n(r.tips) +
         ", \"chord_collapses\": " + n(r.chord_collapses) + ", \"rotations\": " + n(r.rotations) +
         ", \"crease_collapses\": " + n(r.crease_collapses) + ", \"crease_vertices\": " + n(r.crease_vertices) +
         ", \"unfolds\": " + n(r.unfolds) + ", \"converted_faces\": " + n(converted) +
         ", \"input_faces\": " + n(r.initial_faces) + ", \"target_faces\": " + n(r.target_faces) +
         ", \"refused\": {\"topology\": " + n(r.refused_topology) + ", \"valence\": " + n(r.refused_valence) +
         ", \"geometry\": " + n(r.refused_geometry) + ", \"fitmap\": " + n(r.refused_fitmap) +
         ", \"reach\": " + n(r.refused_reach) + "}, \"blocked_share\": " + share +
         ", \"predicted_faces\": " + n(Index(std::lround(r.predicted_faces))) + "}";
}

// The levels' parameters: a.params with each of a.targets in turn (a.params alone with
// none: automatic halting).
std::vector<SimplifyParams> level_params(const SimplifyArgs& a) {
  if (a.targets.empty()) return {a.params};
  std::vector<SimplifyParams> levels;
  for (const Target& t : a.targets) {
    SimplifyParams p = a.params;
    p.target_faces = t.faces, p.target_share = t.share, p.target_edge = t.edge;
    levels.push_back(p);
  }
  return levels;
}

// Where the level of `count` quads goes when there are several: OUT with _count before
// its extension (out.ply: out_2000.ply).
std::string level_path(const std::string& output, Index count) {
  const std::filesystem::path p(output);
  return (p.parent_path() / (p.stem().string() + "_" + std::to_string(count) + p.extension().string())).string();
}

}  // namespace

std::string check_output_path(const std::string& input, const std::string& output) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(output, ec) && fs::equivalent(input, output, ec))
    return "refusing to write the output over the input file " + input;
  const std::string ext = extension_of(output);
  if (ext != "ply" && ext != "obj" && ext != "off")
    return "output " + output + " must end in .ply, .obj or .off";
  const fs::path dir = fs::absolute(output).parent_path();
  if (!fs::is_directory(dir, ec)) return "output folder " + dir.string() + " does not exist";
  return {};
}

int run_convert(const ConvertArgs& a) {
  if (auto err = check_output_path(a.input, a.output); !err.empty()) {
    std::cerr << "quadsimp convert: " << err << "\n";
    return kBadArguments;
  }
  try {
    const auto t0 = std::chrono::steady_clock::now();
    const LogFn log = stderr_log(a.quiet);
    ConvertOptions options;
    options.crease_angle_deg = a.crease_angle;
    options.convex_pairs = true;  // the quads are the result here
    Input in = load_input(a.input, options, log, remesher(a.remesh, a.crease_angle, 0, 0, a.input, log));
    if (const std::string why = texture_clash(a.output, in); !why.empty()) {
      std::cerr << "quadsimp convert: " << why << "\n";
      return kBadArguments;
    }
    write_result(a.output, in, a.texture_size, log);
    const double s = seconds_since(t0);
    if (in.was_pure_quad) {
      std::printf("%s: already pure quad, %u quads written to %s (%.2f s)\n", a.input.c_str(),
                  in.quads.n_faces(), a.output.c_str(), s);
    } else {
      const auto& r = in.convert;
      const std::string creases =
          a.crease_angle > 0 ? "; crease splits: " + std::to_string(r.crease_splits) + " parity, " +
                                   std::to_string(r.crease_midpoints) + " unmatchable"
                             : "";
      const std::string rims = r.rim_splits ? "; cone rims split: " + std::to_string(r.rim_splits) : "";
      std::printf(
          "%s: %u triangles -> %u quads (paired %.2f%%: greedy %u, re-paired %u; %u non-convex or bent over %g "
          "degrees, after %u re-paired; border splits: %u parity, %u unmatchable%s%s%s), written to %s (%.2f s)\n",
          a.input.c_str(), r.input_triangles, r.quads, 100.0 * r.pairing_rate(), r.paired_greedy, r.paired_augmented,
          r.not_mended, options.max_dihedral_deg, r.mended, r.parity_splits, r.border_splits, creases.c_str(),
          rims.c_str(), r.refined ? "; refined once" : "", a.output.c_str(), s);
    }
    return kOk;
  } catch (const InvalidInput& e) {
    std::cerr << "quadsimp convert: " << e.what() << "\n";
    return kBadInput;
  }
}

int run_simplify(const SimplifyArgs& a) {
  const auto refuse = [](const std::string& why) {
    std::cerr << "quadsimp simplify: " << why << "\n";
    return kBadArguments;
  };
  if (auto err = check_output_path(a.input, a.output); !err.empty()) return refuse(err);
  const std::vector<SimplifyParams> levels = level_params(a);
  for (const SimplifyParams& p : levels)
    if (const std::string why = check_params(p); !why.empty()) return refuse(why + " (see --help)");
  const SimplifyParams& params = levels.front();  // the levels differ in their targets alone
  // The remeshing makes triangles enough for the finest level.
  Index most = 0;
  double finest = 0;
  for (const SimplifyParams& p : levels) {
    most = std::max(most, p.target_faces);
    if (p.target_edge > 0) finest = finest > 0 ? std::min(finest, p.target_edge) : p.target_edge;
  }
  try {
    const auto t0 = std::chrono::steady_clock::now();
    const LogFn log = stderr_log(a.quiet);
    Input in = load_input(a.input, convert_options(params), log,
                          remesher(a.remesh, params.crease_angle, most, finest, a.input, log));
    const Index converted = in.quads.n_faces();  // what a share of the quads is of
    const double area = surface_area(in.reference);  // the reference surface's area()
    // The levels' counts, most quads first, and the files they go to.
    std::vector<Index> counts;
    for (const SimplifyParams& p : levels) {
      counts.push_back(target_faces_of(p, converted, area));
      if (log && p.target_edge > 0) {  // before the run, which may be long; the count the pipeline takes
        char line[200];
        std::snprintf(line, sizeof line,
                      ": --edge-length %g: a target of %u quads (the surface's area, %g, over %g squared)",
                      p.target_edge, counts.back(), area, p.target_edge);
        log(a.input + line);
      }
    }
    std::sort(counts.begin(), counts.end(), std::greater<>());
    if (const auto twice = std::adjacent_find(counts.begin(), counts.end()); twice != counts.end())
      return refuse("two levels ask for " + std::to_string(*twice) + " quads");
    std::vector<std::string> outputs;
    for (Index count : counts) {
      outputs.push_back(counts.size() == 1 ? a.output : level_path(a.output, count));
      if (auto err = check_output_path(a.input, outputs.back()); !err.empty()) return refuse(err);
      if (const std::string why = texture_clash(outputs.back(), in); !why.empty()) return refuse(why);
    }
    const ProgressFn progress = progress_bar(a.quiet);
    const Fitmaps fitmaps = input_fitmaps(in, params, progress);  // before ref: input_fitmaps()
    const ReferenceSurface ref(std::move(in.reference));
    // Distances from the input as given, as `quadsimp stats` measures them, not from its
    // remeshing. The quads' orientation is still judged against the remeshing: the normals
    // a coarse CAD mesh interpolates across its sharp edges face away from its flat sides (a
    // 33-sided cone at automatic halting: 38 of 2,388 quads "flipped" against its file, none
    // against the remeshing).
    std::optional<ReferenceSurface> input_ref;
    if ((a.json || a.stats) && !in.input_surface.faces.empty()) input_ref.emplace(std::move(in.input_surface));
    double measuring = 0;  // the levels' distance sampling, left out of the run's time
    const auto level_done = [&](std::size_t level, const SimplifyReport& r) {
      const std::string& output = outputs[level];
      write_result(output, in, a.texture_size, log);
      const double s = seconds_since(t0) - measuring;
      std::vector<Index> flawed;  // ids of the compacted quads: the written file's faces
      const QuadQuality q = quad_quality(in.quads, &ref, &flawed);
      flawed = noted_faces(flawed, r);
      if (log)
        for (const std::string& note : result_notes(r, q, r.target_faces))
          log(outputs.size() > 1 ? output + ": " + note : note);
      if (!a.json && !a.stats) {
        print_summary(a.input, output, q, s, r);
        return;
      }
      const auto t1 = std::chrono::steady_clock::now();
      const SurfaceDistance d = surface_distance(in.quads, input_ref ? *input_ref : ref, a.samples);
      measuring += seconds_since(t1);
      if (a.json) {
        std::printf("%s\n", simplify_json(q, d, flawed, r, s, converted).c_str());
      } else {
        print_summary(a.input, output, q, s, r);
        print_quality(q, &d);
      }
    };
    simplify_levels(in, ref, params, counts, level_done, progress, &fitmaps);
    return kOk;
  } catch (const InvalidInput& e) {
    std::cerr << "quadsimp simplify: " << e.what() << "\n";
    return kBadInput;
  }
}

int run_fitmap(const FitmapArgs& a) {
  if (auto err = check_output_path(a.input, a.output); !err.empty() || extension_of(a.output) != "ply") {
    std::cerr << "quadsimp fitmap: " << (err.empty() ? "the output must be a .ply file" : err) << "\n";
    return kBadArguments;
  }
  try {
    const auto t0 = std::chrono::steady_clock::now();
    TriMesh tri = cleaned_surface(read_mesh(a.input), a.input, stderr_log(a.quiet));
    FitmapOptions fo;
    fo.tau = a.tau;
    fo.progress = progress_bar(a.quiet);
    const Fitmaps f = compute_fitmaps(tri, fo);
    std::vector<VertexField> fields = {{"fitmap_s", f.s}, {"fitmap_m", f.m}};
    std::string names = "fitmap_s, fitmap_m", notes;  // for the summary
    // "auto": the count simplify --adaptive --auto-halt takes its tips and stretch at.
    Index predicted = 0;
    if (a.tips_at == "auto" || a.metric_at == "auto") {
      SimplifyParams p;
      p.adaptive = p.auto_halt = true;
      p.m_factor = a.m_factor;
      predicted = Index(std::lround(predicted_halting_faces(tri, simplify_options(p, &f))));
      if (predicted == 0)
        throw InvalidInput(a.input + ": automatic halting predicts under half a quad here; give --tips and "
                                     "--metric a face count");
      notes += "; automatic halting predicted at " + std::to_string(predicted) + " quads";
    }
    auto count_at = [&](const std::string& at) {
      return at == "auto" ? predicted : at.empty() ? 0 : Index(std::stoul(at));
    };
    const Index tips_for = count_at(a.tips_at), metric_for = count_at(a.metric_at);
    if (tips_for > 0) {
      const std::vector<Index> found = find_tips(tri, tip_options_for(tri, tips_for));
      fields.push_back({"tip", std::vector<float>(tri.n_vertices(), 0.f)});
      for (Index v : found) fields.back().values[v] = 1.f;
      names += ", tip";
      notes += "; " + std::to_string(found.size()) + " tips at " + std::to_string(tips_for) + " quads";
    }
    if (metric_for > 0) {
      const Anisotropy an = anisotropy_for(tri, triangle_adjacency(tri), metric_for, a.max_aspect);
      std::vector<float> aspect(tri.n_vertices()), along[3];
      for (auto& x : along) x.resize(tri.n_vertices());
      for (Index v = 0; v < tri.n_vertices(); ++v) {
        const Stretch s = stretch_at(an, v);
        aspect[v] = float(s.aspect);
        for (int k = 0; k < 3; ++k) along[k][v] = float(s.along[k]);
      }
      std::vector<float> sorted = aspect;
      std::sort(sorted.begin(), sorted.end());
      char summary[96];
      std::snprintf(summary, sizeof summary, "; aspect at %u quads: median %.2f, largest %.2f", metric_for,
                    sorted.empty() ? 1.0 : sorted[sorted.size() / 2], sorted.empty() ? 1.0 : sorted.back());
      fields.push_back({"aspect", std::move(aspect)});
      for (int k = 0; k < 3; ++k) fields.push_back({std::string("long_") + "xyz"[k], std::move(along[k])});
      names += ", aspect, long_x, long_y, long_z";
      notes += summary;
    }
    write_tri_mesh_ply(a.output, tri, fields);
    const double s = seconds_since(t0);
    std::printf("%s: S and M fitmaps of %u vertices written to %s (per-vertex %s; colour = S%s), %.2f s\n",
                a.input.c_str(), tri.n_vertices(), a.output.c_str(), names.c_str(), notes.c_str(), s);
    return kOk;
  } catch (const InvalidInput& e) {
    std::cerr << "quadsimp fitmap: " << e.what() << "\n";
    return kBadInput;
  }
}

int run_stats(const StatsArgs& a) {
  try {
    MeshFile file = read_mesh(a.quads);
    if (!file.is_pure_quad()) {
      if (a.json) std::printf("{\"pure_quad\": false, \"faces\": %zu}\n", file.triangles.size() + file.quads.size());
      std::cerr << "quadsimp stats: " << a.quads << " is not a pure quad mesh (" << file.triangles.size()
                << " triangles)\n";
      return kBadInput;
    }
    QuadMesh quads;
    try {
      quads = QuadMesh::from_faces(std::move(file.positions), file.quads);
      validate(quads);
    } catch (const std::exception& e) {
      throw InvalidInput(a.quads + ": not a valid quad mesh (" + e.what() + ")");
    }
    TriMesh tri = cleaned_surface(read_mesh(a.reference), a.reference);
    const ReferenceSurface ref(std::move(tri));
    std::vector<Index> flawed;
    const QuadQuality q = quad_quality(quads, &ref, &flawed);
    const SurfaceDistance d = surface_distance(quads, ref, a.samples);
    if (a.json)
      std::printf("%s\n", to_json(q, &d, &flawed).c_str());
    else
      print_quality(q, &d);
    return kOk;
  } catch (const InvalidInput& e) {
    std::cerr << "quadsimp stats: " << e.what() << "\n";
    return kBadInput;
  }
}

}  // namespace qs::cli
