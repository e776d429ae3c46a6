// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// What each filter does, in plain C++ on the core's types: both MeshLab adapters call
// these after converting their layer, so the two generations (and the CLI, which runs
// the same core functions) give the same results.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "quadsimp/mesh/mesh_file.h"
#include "quadsimp/mesh/quad_mesh.h"
#include "quadsimp/simplify/pipeline.h"

namespace qs::plugin {

//! Lines for the MeshLab log and named values to return.
struct Outcome {
  std::vector<std::string> log;
  std::map<std::string, double> values;
};

//! Prepares `layer` (cleaning, conversion) and simplifies it. \throw InvalidInput.
QuadMesh run_simplification(MeshFile layer, const std::string& name, const SimplifyParams& params,
                            const ProgressFn& progress, Outcome& outcome);

//! Prepares `layer` and returns its quads. \throw InvalidInput.
QuadMesh run_conversion(MeshFile layer, const std::string& name, Outcome& outcome);

//! S and M fitmaps at the layer's own vertices (cleaning may merge or drop vertices,
//! so each one reads the field at its closest point on the cleaned surface).
Fitmaps run_fitmaps(const MeshFile& layer, const std::string& name, double tau, const ProgressFn& progress,
                    Outcome& outcome);

//! Quality of a pure quad layer and its distance to a reference layer.
//! \throw InvalidInput if `quads` is not a pure quad mesh.
void run_quality(const MeshFile& quads, const std::string& quads_name, const MeshFile& reference,
                 const std::string& reference_name, unsigned samples, Outcome& outcome);

}  // namespace qs::plugin
