// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "quadsimp/util/progress.h"
#include "quadsimp/util/types.h"

namespace qs {

//! An indexed triangle mesh: the reference surface M0 and the input of the
//! tri-to-quad conversion. Plain data; invariants are established by clean().
struct TriMesh {
  std::vector<Vec3> positions;
  std::vector<std::array<Index, 3>> faces;

  Index n_vertices() const { return Index(positions.size()); }
  Index n_faces() const { return Index(faces.size()); }
  //! The cross product of triangle t's edges from its first corner: its normal, as long
  //! as twice its area.
  Vec3 area_normal(const std::array<Index, 3>& t) const {
    return (positions[t[1]] - positions[t[0]]).cross(positions[t[2]] - positions[t[0]]);
  }
};

//! Neighbouring triangles whose normals' cosine is under this are turned back onto each
//! other (by over 120 degrees): clean() mends a single triangle so turned against all its
//! neighbours, and ReferenceSurface marks the small patches bounded by such edges
//! (folded_patches()) that clean() could not lay flat.
inline constexpr double kFoldedBackCos = -0.5;

//! clean() lays flat the patches folded back that cover under this share of their piece
//! (folded_patches()); ReferenceSurface marks those it left under a smaller one.
inline constexpr double kLaidFlatShare = 1e-2;

//! The patches clean() tries to lay flat are bounded by edges turning by over about 101.5
//! degrees, less than kFoldedBackCos asks: where a fold's layers meet the surface at a
//! slant, its ends turn by as little as 108 degrees (a column of a wave grid pushed past
//! its neighbours). ReferenceSurface's marking keeps kFoldedBackCos.
inline constexpr double kLaidFlatCos = -0.2;

inline double triangle_area(const Vec3& a, const Vec3& b, const Vec3& c) { return 0.5 * (b - a).cross(c - a).norm(); }

//! Thinness of triangle t: twice its area over its longest edge squared (its height over
//! that edge, in edge lengths); `longest` is set to that edge (k: corners k, k+1).
double thinness(const TriMesh& mesh, const std::array<Index, 3>& t, Index& longest);

//! The triangles' unit normals.
std::vector<Vec3> unit_normals(const TriMesh& mesh);

//! What clean() repaired. Every count is also reported through the log function.
struct CleanReport {
  Index merged_duplicate_vertices = 0;
  Index merged_close_vertices = 0;  //!< border vertices within 1e-6 of the bbox diagonal of another
  Index zipped_t_junctions = 0;     //!< border vertices on a border edge across a crack, split into it
  Index removed_degenerate_faces = 0;
  Index removed_duplicate_faces = 0;
  Index removed_nonmanifold_faces = 0;  //!< at edges with more than two triangles, all but the straightest pair
  Index removed_unreferenced_vertices = 0;
  Index split_nonmanifold_vertices = 0;
  Index flipped_faces = 0;     //!< faces re-oriented to agree with their component
  Index flipped_edges = 0;     //!< edges flipped to mend caps and single folded-back triangles
  Index unfolded_patches = 0;  //!< small patches folded back (folded_patches()), laid flat
  Index moved_vertices = 0;    //!< the vertices moved to lay them flat
  //! Whether the faces themselves changed (a vertex merged, split or moved, a face
  //! removed or turned); dropping unreferenced vertices does not count.
  bool changed_faces() const {
    return merged_duplicate_vertices + merged_close_vertices + zipped_t_junctions + removed_degenerate_faces +
               removed_duplicate_faces + removed_nonmanifold_faces + split_nonmanifold_vertices + flipped_faces +
               flipped_edges + moved_vertices > 0;
  }
};

//! Makes `mesh` a clean, oriented, edge- and vertex-manifold triangle mesh, or throws.
//!
//! Repairs (each logged): exact-duplicate vertices merged (those on a border, or all of
//! a piece written twice; interior vertices of two sheets that touch stay apart), border
//! vertices closer than 1e-6 of the bounding-box diagonal merged, cracks closed where the
//! border vertices of one side lie along the border edges of the other (T-junctions: each
//! such edge is split at them; the slit a removed face of no area leaves is one), faces
//! with a repeated vertex or zero area removed, duplicate faces removed, at an edge with
//! more than two triangles all removed but the two across which the surface runs on straightest,
//! unreferenced vertices removed, non-manifold vertices split (one copy per fan), faces
//! re-oriented consistently within each component, caps (height under 1e-3 of the
//! longest edge) and single triangles folded back onto their neighbours mended by
//! flipping an edge, small patches folded back (folded_patches()) laid flat by moving
//! their vertices, and if need be up to eight rings of vertices around them while the
//! region faces the way the patch's own surroundings do (not those on the border). Only patches that are discs
//! are tried: a band round a post with an overhanging wall stays.
//! \throw InvalidInput for: no vertices, no faces (point cloud), NaN/Inf coordinates,
//!        out-of-range indices, a size outside 1e-30 to 1e30 across (the faces' bounding
//!        box), a non-orientable component. `what` is one sentence;
//!        `source` (a file name) prefixes it.
CleanReport clean(TriMesh& mesh, const std::string& source = "mesh", const LogFn& log = {});

//! For each position, the lowest index of the positions equal to it (itself if none
//! comes before it); non-finite positions map to themselves. clean() merges by it.
std::vector<Index> first_equal_positions(const std::vector<Vec3>& positions);

//! Renumbers faces along a Morton curve of their centroids, and vertices in the order
//! the faces first use them; the surface is unchanged. The simplifier's queries jump
//! from collapse to collapse and each one reads M0 and the quads around one place:
//! with neighbours close in memory the bunny ran 10% faster.
//! \pre no unreferenced vertices (they are dropped).
void sort_spatially(TriMesh& mesh);

//! Length of the diagonal of the axis-aligned bounding box.
double bbox_diagonal(const std::vector<Vec3>& positions);

//! The axis-aligned bounding box of the vertices the faces use: a stray vertex no face
//! uses, far off, must not set the size tolerances are relative to.
std::pair<Vec3, Vec3> used_bbox(const TriMesh& mesh);

//! The point to subtract before float or moment arithmetic: the bounding box's centre
//! when it lies farther from the origin than the box's diagonal (a scan in survey
//! coordinates, a million units out: float rounds it to a quarter unit, and moments
//! cancel every digit), else the origin itself, where a shift would only change rounding.
Vec3 working_origin(const std::vector<Vec3>& positions);

//! Neighbour triangle across edge k (corner k to k+1) of each triangle; kNone on the
//! border. \pre edge-manifold (see clean()).
std::vector<std::array<Index, 3>> triangle_adjacency(const TriMesh& mesh);

//! Connected component id per face (faces sharing an edge), and their count, from
//! the mesh's triangle_adjacency(); with `joined`, only neighbours f, g for which
//! joined(f, g) holds are in the same component.
Index face_components(const std::vector<std::array<Index, 3>>& adjacency, std::vector<Index>& component,
                      const std::function<bool(Index, Index)>& joined = {});

//! Small patches folded back onto the surface, as a scan's Z-fold leaves them (three
//! layers, the middle one facing the other way). Triangles form patches across edges
//! that do not turn back (normals' cosine at least `turned_cos`); a patch under
//! `largest_share` of its connected piece's area is taken for folded back, while a sheet
//! with a sharp rim (two sides alike in area) is not. Sets patch[f] to the number of f's
//! patch, kNone for other triangles (or leaves `patch` empty), and returns how many there
//! are.
//! `unit_normals` are the triangles' unit normals.
Index folded_patches(const TriMesh& mesh, const std::vector<std::array<Index, 3>>& adjacency,
                     const std::vector<Vec3>& unit_normals, std::vector<Index>& patch, double largest_share,
                     double turned_cos);

//! Every triangle split into four at its edges' midpoints (the same surface, four times
//! the triangles): how the benchmarks and tests make a large mesh of a shared one.
TriMesh split_in_four(const TriMesh& mesh);

}  // namespace qs
