// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <vector>

#include "quadsimp/mesh/tri_mesh.h"
#include "quadsimp/simplify/simplify.h"  // Fitmaps
#include "quadsimp/util/progress.h"

namespace qs {

//! Fitmaps of [Bozzo et al. 2010, 3.3], linear version.
//!
//! Radii r_0..r_h (h = levels), r_0 = mean edge length, r_h = bbox diagonal / 4,
//! spaced exponentially. The neighbourhood of p at radius r is the part of the
//! Euclidean ball around p that is connected to p through mesh edges inside the ball:
//! intrinsic like a geodesic disc, but as cheap as a ball, and it does not mix two
//! sheets that are close in space (fingers, ears, thin walls) which a full ball would
//! merge into one noisy fit. Its triangles are those with a corner reached and their
//! centroid in the ball (so it covers about pi r^2 of a flat surface from r_0 on). Each
//! neighbourhood is fitted with a plane by total least squares on exact, area-weighted
//! triangle moments (independent of the sampling density); E(r_i) = RMS distance to that
//! plane. F_S = sqrt(a) of the least-squares fit E(r) = a r^2. F_M = the largest radius,
//! before the first failure, at which the triangles whose normal disagrees with the
//! plane's (oriented like the area-weighted mean normal) cover less than tau of the area.
struct FitmapOptions {
  int levels = 8;        //!< h: radii r_0..r_h
  double tau = 0.05;     //!< M-fitmap tolerance
  //! Radii up to this multiple of r_0 are evaluated exactly per vertex; larger ones on
  //! a clustering of the mesh into cells of size r / cells_per_radius.
  double exact_up_to = 4.0;
  double cells_per_radius = 8.0;
  //! Vertices whose cell search starts in the same cell share the part of their balls
  //! that lies in all of them (the same cells, summed once). Off: one search per vertex,
  //! for comparisons; the sums then differ only in their rounding.
  bool share_cell_searches = true;
  int smooth_s = 1, smooth_m = 2;  //!< Laplacian passes afterwards (as vcglib does)
  //! Local S (ours): a = the median over the radii up to F_M(p) (at least three) of
  //! E_i / r_i^2, instead of the paper's least-squares fit over all radii. With all
  //! radii the r^4 weights let the largest neighbourhoods (a quarter of the model)
  //! decide, so F_S hardly varies: a flat point next to a bump gets nearly the bump's
  //! value (measured on the bump test: 0.21 at 0.5 away against 0.28 on it).
  bool local_s = true;
  ProgressFn progress;
};

//! The radii used for `mesh`.
std::vector<double> fitmap_radii(const TriMesh& mesh, int levels);

//! Fitmaps at every vertex of a clean triangle mesh, in parallel (TBB).
Fitmaps compute_fitmaps(const TriMesh& mesh, const FitmapOptions& options = {});

//! Brute-force reference at the given vertices: every radius exact, no smoothing.
//! For validating compute_fitmaps(); quadratic in the mesh size at large radii.
Fitmaps fitmaps_brute_force(const TriMesh& mesh, const std::vector<Index>& vertices,
                            const FitmapOptions& options = {});

//! The same as compute_fitmaps() without the final smoothing (for comparisons).
Fitmaps compute_fitmaps_unsmoothed(const TriMesh& mesh, const FitmapOptions& options = {});

}  // namespace qs
