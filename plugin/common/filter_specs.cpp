// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "filter_specs.h"

#include <algorithm>
#include <stdexcept>

#include "quadsimp/simplify/pipeline.h"
#include "quadsimp/texture/texture_bake.h"

namespace qs::plugin {

namespace {
const double kTextureSide = TextureBakeOptions().max_side;
const char* const kTextureSizeHelp =
    "A textured layer only: the largest width and height, in texels, of the texture baked onto the quads (the "
    "CLI's --texture-size). Their tiles shrink alike to fit, down to 3 texels a side: the texture of very many "
    "quads can be larger, and the log then says so. 4096: 64 MB in memory, which graphics cards and MeshLab's "
    "default texture memory take whole.";
const std::string kCitation =
    "<br><br>See: <i>G. Bozzo, D. Panozzo, E. Puppo, N. Pietroni, L. Rocca</i>, <b>\"Adaptive Quad Mesh "
    "Simplification\"</b>, Eurographics Italian Chapter Conference 2010.";
}

const std::vector<FilterSpec>& filter_specs() {
  static const std::vector<FilterSpec> specs = {
      {kSimplify, "Quad Mesh Simplification", "meshing_quad_mesh_simplification",
       "Simplifies a triangle or quad mesh into a coarser <b>pure quad mesh</b> (quadsimp). Triangles are first "
       "paired into quads; then, one diagonal collapse at a time, the mesh is coarsened, with edge rotations that "
       "favour valence 4, doublet and singlet removal, and tangent-space smoothing that keeps every vertex on the "
       "input surface; where no diagonal collapse is left above the target, whole chords of quads are collapsed (a "
       "strip one quad wide loses one quad at a time). <br><b>Uniform</b> mode collapses the shortest diagonal "
       "first and stops at the target number of faces. <b>Adaptive</b> mode weights diagonals by the S-fitmap "
       "(small faces where the surface is curved), refuses collapses that would make a face larger than the "
       "M-fitmap allows or leave parts of a large face without the input along its normal within the reach (4.5% "
       "of the bounding-box diagonal by default, so that the result stays projectable onto the input), and can "
       "stop by itself once these block the halting share of the surface (15% by default). <b>Keep tips</b> holds "
       "a vertex on each point the input ends in (a claw, a nose), which the smoothing would cut back. <b>Crease "
       "angle</b> keeps the input's edges sharper than it (a machined part's) as edges of the quads, and their "
       "corners in place. <b>Fit vertices to the input</b> then moves the vertices off the input, along their "
       "normals, so that the quads lie closer to it. <br>The result goes to a new layer; the input layer is not "
       "changed. The quads take the input layer's vertex colours, if it has any, interpolated at each vertex's "
       "closest point on it (as <i>Vertex Attribute Transfer</i> does), its face colours, each quad the colour of "
       "the face closest to its centre, and its texture, baked into a texture of the quads' own (a tile for each "
       "quad; MeshLab 2020.09 writes it beside the input's file, as its own texture filters do); other attributes "
       "are not carried over. Quads the log counts as non-convex, flipped, folded or beyond the reach are "
       "selected in the result, so that they can be found. Quads are stored the MeshLab way, as triangle pairs "
       "with a faux shared edge: save as PLY with per-face flags, or as OBJ/OFF with polygons, to keep them." +
           kCitation},
      {kConvert, "Convert to Pure Quad Mesh", "meshing_tri_to_pure_quad",
       "Turns a triangle mesh into a <b>pure quad mesh</b> without moving any vertex: triangles are paired "
       "greedily into the best-shaped quads, every leftover is re-paired along an alternating path (through "
       "convex pairs where there is one), pairs left non-convex or bent by more than 60 degrees are re-paired "
       "where convex pairs can take their place (the log counts those left), and where no complete pairing "
       "exists a border edge is split at its midpoint; with a <b>Crease angle</b>, no "
       "triangles are paired across an edge sharper than it. The input is cleaned first (duplicate vertices, "
       "degenerate and duplicate faces, unreferenced vertices; cracks of T-junctions, and the slits faces of no "
       "area leave, closed; at an edge with more than two faces, all but the two across which the surface runs on "
       "straightest are removed; non-manifold vertices split; caps and single triangles folded back onto their "
       "neighbours mended by flipping an edge; small patches folded back onto the surface laid flat), and the log "
       "lists each repair. The layer is replaced by its quads, with its vertex and face colours and its texture "
       "(baked into a texture of the quads' own) if it has any."},
      {kFitmaps, "Compute Fitmaps", "compute_scalar_by_fitmap_per_vertex",
       "Computes the <b>S-fitmap</b> (how fast the error of fitting a plane grows with the radius around each "
       "vertex) and the <b>M-fitmap</b> (the largest radius around each vertex where a plane still faces the same "
       "way as the surface, up to a tolerance tau) on the current mesh. Both are stored as per-vertex attributes "
       "<i>FitmapS</i> and <i>FitmapM</i>; S is also copied to the vertex quality (use <i>Colorize by vertex "
       "quality</i> to see it)." +
           kCitation},
      {kQuality, "Quad Mesh Quality", "get_quad_mesh_quality_measures",
       "Measures a pure quad mesh: face and vertex counts, maximum valence, share of regular vertices (valence 4 "
       "inside, 3 on the border), homeometry (edge length / mean edge and diagonal / (sqrt(2) mean edge), ideal "
       "1), non-convex faces, faces bent by more than 90 degrees whichever diagonal splits them, and its distance "
       "to a reference layer (symmetric Hausdorff and RMS, and the one-sided mean from the quads to the reference, "
       "in units of 1e-3 of the reference's bounding-box diagonal). The values are printed in the log and returned."},
  };
  return specs;
}

const FilterSpec& filter_spec(FilterId id) {
  for (const auto& s : filter_specs())
    if (s.id == id) return s;
  throw std::out_of_range("unknown quadsimp filter");
}

std::vector<ParamSpec> params_of(FilterId id) {
  static const std::vector<ParamSpec> all = {
      {kSimplify, "Adaptive", "Adaptive (fitmaps)", ParamKind::Bool, 0, 0, 1,
       "Uniform (off): equal-sized quads, stop at the target. Adaptive (on): quad sizes follow the fitmaps."},
      {kSimplify, "TargetFaceNum", "Target number of quads", ParamKind::Int, -1, 0, 1e9,
       "Stop when the mesh has at most this many quads. Required in uniform mode (unless the target share is set); "
       "in adaptive mode it is ignored when automatic halting is on. A mesh of several pieces shares it among them "
       "by area: pieces that cannot shrink to their share (scan debris) leave the result above it, and the log "
       "says so. Default: a tenth of the input's quads."},
      {kSimplify, "TargetPerc", "Target share of the quads", ParamKind::Float, 0, 0, 1,
       "If above 0, the target is this share of the quads the layer converts to (0.1: a tenth), in place of the "
       "target number of quads, as in MeshLab's quadric decimation: one script then suits meshes of different "
       "sizes. 0: the target number of quads is used."},
      {kSimplify, "AutoHalt", "Automatic halting (adaptive)", ParamKind::Bool, 0, 0, 1,
       "Adaptive mode only: ignore the target and stop once the faces whose collapses the M-fitmap (or the reach "
       "check, see Reach) refuses cover the halting share of the surface (the paper runs until none is allowed, "
       "which coarsens the rest far past its error balance). Where every remaining collapse is refused first (a "
       "noisy scan, a small mesh), it stops there, and the log says so. A mesh of several pieces then shares the "
       "count it stopped at among them, and pieces above their share (scan debris) go on down towards it."},
      {kSimplify, "HaltShare", "Halting share (automatic halting)", ParamKind::Float, SimplifyParams().halt_share,
       0.001, 1,
       "Automatic halting: the share of the surface the M-fitmap may block, beyond what it blocked before the "
       "first collapse, before simplification stops (0.15: the gargoyle's and armadillo's scans stop within 2% of "
       "the paper's counts, the bunny's 20% above). Smaller stops earlier, with more quads; 1 runs until no "
       "collapse is allowed, the paper's rule."},
      {kSimplify, "MaxAspect", "Largest aspect (adaptive)", ParamKind::Float, SimplifyParams().max_aspect, 1, 100,
       "Adaptive mode: how many times longer than wide a quad may grow along the surface's flatter direction "
       "(along a tube or a limb, across a crease), where the error of a quad is least for its size; the M-fitmap's "
       "bound lets it reach as many times further that way. 1: quads as square as in uniform mode and the paper's "
       "bound. 3: on the scans we measured, 10% lower RMS distance than square quads at the same count on average "
       "(up to 19%)."},
      {kSimplify, "Reach", "Reach (adaptive)", ParamKind::Float, SimplifyParams().reach, 0, 1,
       "Adaptive mode: refuse a collapse that would leave a large quad's centre or an edge's midpoint without the "
       "input along the quad's normal within this share of the bounding box diagonal (ours). With it the scans we "
       "measured are at least 99.5% projectable onto the input (the smooth moai halts at 103 quads, 100%); "
       "without it the moai halts at 71 quads, 99.7% projectable, and with square quads (Largest aspect 1) at 59, "
       "98.2% (122 quads, 100%, with it). Faces smaller than the reach may grow 1.1 times past the M-fitmap's "
       "bound, which keeps thin parts from taking too many quads. 0: no check, as in the paper (with Largest "
       "aspect 1 and Halting share 1: the paper's square quads, bound and halting rule)."},
      {kSimplify, "Tau", "Fitmap tolerance tau", ParamKind::Float, SimplifyParams().tau, 0.001, 0.5,
       "Adaptive mode: share of a neighbourhood allowed to face against its fitted plane in the M-fitmap (0.05 in "
       "the paper). Larger values allow larger faces."},
      {kSimplify, "PreserveBoundary", "Preserve boundary", ParamKind::Bool, 0, 0, 1,
       "Keep the mesh border exactly: no collapse touches a border vertex and smoothing leaves them in place. Off: "
       "border vertices slide along the border, and where a ragged outline leaves a border edge over nothing, move "
       "inwards by about one edge of the input at most."},
      {kSimplify, "KeepTips", "Keep tips", ParamKind::Bool, 0, 0, 1,
       "Hold a vertex at each point the input ends in at the scale of the quads (a claw, a toe, a nose; ours): the "
       "smoothing leaves it in place and collapses keep it there. Off: the smoothing can cut such tips back (the "
       "armadillo at 2,000 quads: 25% lower RMS distance with it in uniform mode, 4% in adaptive mode). Uniform "
       "mode then refuses to fold quads round thin parts, as adaptive mode always does."},
      {kSimplify, "CreaseAngle", "Crease angle", ParamKind::Float, SimplifyParams().crease_angle, 0, 179,
       "Keep the input's edges sharper than this many degrees (the angle between the normals of the faces beside "
       "them; ours): triangles are not paired across them, their vertices slide only along them, and where they "
       "meet or end the vertices stay put, so that a CAD part keeps its edges and corners (a cube of 3,072 "
       "triangles at 150 quads: no distance to it, against 9% of its diagonal rounded off). 0: none, as in the "
       "paper. 30 to 60 suits machined parts; scans have few edges this sharp."},
      {kSimplify, "Fast", "Fast (one pass)", ParamKind::Bool, 0, 0, 1,
       "One rotation and smoothing pass after each collapse, as in the paper: about 20% faster, with a few points "
       "fewer regular vertices. Off: a second pass over the smoothed zone once the mesh has less than twice the "
       "target faces."},
      {kSimplify, "FitToInput", "Fit vertices to the input", ParamKind::Bool, 0, 0, 1,
       "Afterwards, move each vertex along its normal, off the input surface, so that the quads lie as close to it "
       "as they can both ways (least squares, ours): about 30% lower RMS distance. Off: every vertex stays on the "
       "input, as in the paper."},
      {kSimplify, "TextureSize", "Texture size", ParamKind::Int, kTextureSide, TextureBakeOptions::kSmallestSide,
       TextureBakeOptions::kLargestSide, kTextureSizeHelp},
      {kConvert, "CreaseAngle", "Crease angle", ParamKind::Float, SimplifyParams().crease_angle, 0, 179,
       "Pair no triangles across edges sharper than this many degrees (the angle between the normals of the faces "
       "beside them), so that they are edges of the quads. 0: none."},
      {kConvert, "TextureSize", "Texture size", ParamKind::Int, kTextureSide, TextureBakeOptions::kSmallestSide,
       TextureBakeOptions::kLargestSide, kTextureSizeHelp},
      {kFitmaps, "Tau", "Fitmap tolerance tau", ParamKind::Float, FitmapOptions().tau, 0.001, 0.5,
       "Share of a neighbourhood allowed to face against its fitted plane before the M-fitmap stops growing."},
      {kQuality, "ReferenceMesh", "Reference mesh", ParamKind::Mesh, 0, 0, 0,
       "The layer the distance is measured to (usually the original triangle mesh)."},
      {kQuality, "SampleNum", "Distance samples", ParamKind::Int, 200000, 1000, 1e8,
       "Random points sampled on each surface (plus all vertices) for the distances."},
  };
  std::vector<ParamSpec> out;
  for (const auto& p : all)
    if (p.filter == id) out.push_back(p);
  return out;
}

int default_target_faces(int n_triangles) { return std::max(6, n_triangles / 20); }

}  // namespace qs::plugin
