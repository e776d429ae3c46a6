// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "quadsimp/mesh/tri_mesh.h"
#include "quadsimp/util/progress.h"

namespace qs {

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
  //! A non-orientable surface cut open: the edges cut, and the vertices copied for their
  //! other side.
  Index cut_edges = 0, cut_vertices = 0;
  Index flipped_edges = 0;     //!< edges flipped to mend caps and single folded-back triangles
  Index unfolded_patches = 0;  //!< small patches folded back (folded_patches()), laid flat
  Index moved_vertices = 0;    //!< the vertices moved to lay them flat
  double farthest_move = 0;    //!< the longest of those moves
  //! Patches left as they were because laying them flat would move a vertex further than
  //! CleanOptions::longest_fold_move, and the least such move among them.
  Index kept_far_folds = 0;
  double least_kept_move = 0;
  //! Whether the faces themselves changed (a vertex merged, split or moved, a face
  //! removed or turned); dropping unreferenced vertices does not count.
  bool changed_faces() const {
    return merged_duplicate_vertices + merged_close_vertices + zipped_t_junctions + removed_degenerate_faces +
               removed_duplicate_faces + removed_nonmanifold_faces + split_nonmanifold_vertices + flipped_faces +
               cut_edges + flipped_edges + moved_vertices > 0;
  }
};

//! Which of the small patches folded back onto the surface clean() lays flat.
struct CleanOptions {
  //! Unset: all of them. Set: only those with a vertex at one of these points, so none if
  //! it is empty (cleaned_surface(): the corners of a quad mesh's quads that fold over
  //! themselves; a quad mesh is someone's surface, whose sharp thin parts only look like
  //! folds).
  std::optional<std::vector<Vec3>> folds_only_at;
  //! A patch whose laying flat would move a vertex further than this share of the bounding
  //! box's diagonal stays as it is. A scan's folds, noisy or not, needed at most 2.8%; a
  //! coarse mesh's sharp thin parts taken for folds up to 32% (bench/RESULTS.md).
  double longest_fold_move = 0.05;
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
//! re-oriented consistently within each component (a non-orientable one cut open along
//! the edges where its orientation meets itself reversed, their vertices copied), caps
//! (height under 1e-3 of the longest edge) and single triangles folded back onto their neighbours mended by
//! flipping an edge, small patches folded back (folded_patches()) laid flat by moving
//! their vertices, and if need be up to eight rings of vertices around them while the
//! region faces the way the patch's own surroundings do (not those on the border). Only patches that are discs
//! are tried: a band round a post with an overhanging wall stays. `options` can keep
//! some or all such patches as they are (CleanOptions).
//! \throw std::invalid_argument if options.longest_fold_move is negative or NaN.
//! \throw InvalidInput for: no vertices, no faces (point cloud), NaN/Inf coordinates,
//!        out-of-range indices, a size outside 1e-30 to 1e30 across (the faces' bounding
//!        box). `what` is one sentence;
//!        `source` (a file name) prefixes it.
CleanReport clean(TriMesh& mesh, const std::string& source = "mesh", const LogFn& log = {},
                  const CleanOptions& options = {});

}  // namespace qs
