// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include "quadsimp/mesh/tri_mesh.h"

namespace qs {

//! Explicit isotropic remeshing (splits, collapses, flips and relaxation, each vertex put
//! back on the input), vcglib's, as MeshLab's "Remeshing: Isotropic Explicit Remeshing".
//! The conversion pairs the triangles it is given: CAD tessellations' long, thin ones give
//! long, thin quads round poles of high valence (README, Limits), even ones give even quads.
struct RemeshOptions {
  //! The edges' target length as a share of the bounding box's diagonal; 0: chosen by
  //! remesh_edge_length() for target_quads.
  double edge_share = 0;
  Index target_quads = 0;         //!< the quads the remeshing is for (0: not known)
  double feature_angle_deg = 30;  //!< edges sharper than this stay edges (MeshLab's default)
  int iterations = 10;            //!< rounds of the five operations (MeshLab's default)
};

struct RemeshReport {
  Index input_triangles = 0, triangles = 0;
  double edge_length = 0;  //!< the target length used
  double diagonal = 0;     //!< the surface's bounding box's
};

//! Triangles remesh_edge_length() keeps to, unless the quads asked for need more.
inline constexpr double kMostTriangles = 2e5;

//! The edge length remeshing aims at when the quads asked for are `target_quads` (0: not
//! known): 1% of the bounding box's diagonal (longer where that would make more than
//! kMostTriangles triangles), or shorter where that would give fewer than about four and a
//! half quads per quad asked for, so that the simplifier has some to take.
double remesh_edge_length(const TriMesh& surface, Index target_quads);

//! `surface` remeshed; it is left as it is, and is the surface every vertex is put back on.
//! \pre surface is clean (clean()); the result may need cleaning again (vcglib's
//! collapses can leave a triangle of no area).
TriMesh remesh_isotropic(const TriMesh& surface, const RemeshOptions& options = {}, RemeshReport* report = nullptr);

}  // namespace qs
