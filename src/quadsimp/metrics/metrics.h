// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <string>
#include <vector>

#include "quadsimp/mesh/quad_mesh.h"
#include "quadsimp/reference/reference_surface.h"

namespace qs {

//! The connectivity and shape measures of the paper's tables.
struct QuadQuality {
  Index faces = 0, vertices = 0;
  int max_valence = 0;           //!< over all vertices
  int max_valence_interior = 0;
  double regular_percent = 0;    //!< valence 4 inside, 3 on the border
  double valence4_percent = 0;   //!< valence 4 anywhere (the paper's ambiguous reading)
  double mu = 0;                 //!< mean edge length
  //! Homeometry [TPC*10]: edge length / mu and diagonal / (sqrt(2) mu); ideal 1.
  double homeometry_min = 0, homeometry_max = 0;
  double edge_ratio_min = 0, edge_ratio_max = 0;  //!< edges only
  Index nonconvex_faces = 0;     //!< some corner turns against the face normal
  Index flipped_faces = 0;       //!< facing against the input nearest its centre and two or more corners (needs ref)
  Index folded_faces = 0;        //!< bent by more than 90 degrees along both diagonals
  //! Closed pieces of two quads on the same four corners: the least quad mesh of a tiny
  //! closed part (a tetrahedron of scan debris), folded by nature.
  Index two_quad_pieces = 0;
  Index border_vertices = 0;     //!< vertices on the border
  Index border_loops = 0;        //!< closed runs of border edges: holes, and a patch's outline
};

//! With `flawed`, the ids of the faces counted non-convex, flipped or folded are
//! appended to it, each once and in id order: what the MeshLab filters select in their
//! result so that a user can find them.
QuadQuality quad_quality(const QuadMesh& mesh, const ReferenceSurface* ref = nullptr,
                         std::vector<Index>* flawed = nullptr);

//! How far along the output's normal the projectability measure looks for the reference
//! (SurfaceDistance::projectability), as a share of the reference's bounding-box diagonal.
inline constexpr double kProjectabilityReach = 0.05;

//! Distances between the quad mesh (quads split along their shorter diagonal) and the
//! reference surface, relative to the reference's bounding-box diagonal.
struct SurfaceDistance {
  double hausdorff = 0;      //!< symmetric max
  double rms = 0;            //!< symmetric: both sample sets pooled
  double mean_to_ref = 0;    //!< one-sided mean, output -> reference (MeshLab-like)
  double max_to_ref = 0, max_from_ref = 0;
  double rms_to_ref = 0, rms_from_ref = 0;
  double projectability = 0; //!< share of output samples whose normal ray hits the reference consistently
  Index samples = 0;         //!< per side, besides the vertices
};

//! Area-weighted samples on both surfaces plus all vertices, exact closest points
//! through Embree, in parallel; deterministic for a given sample count.
SurfaceDistance surface_distance(const QuadMesh& mesh, const ReferenceSurface& ref, Index samples_per_side = 1000000);

//! The two as one JSON object (values in the units above; distances x 1e-3 of the diagonal
//! too), with `flawed` as "flawed_faces" if given: quad_quality()'s list, of a compacted
//! mesh, so the quads' indices in the order files list them.
std::string to_json(const QuadQuality& q, const SurfaceDistance* d, const std::vector<Index>* flawed = nullptr);

//! Triangles of a quad mesh, each quad split along its shorter diagonal.
TriMesh triangulate(const QuadMesh& mesh);

}  // namespace qs
