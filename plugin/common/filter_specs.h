// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// The filters and parameters every front end shows: plain data, mapped to each MeshLab
// generation's Rich* types by its adapter, and matched by the CLI's options.
#pragma once

#include <string>
#include <vector>

namespace qs::plugin {

enum FilterId : int { kSimplify = 0, kConvert = 1, kFitmaps = 2, kQuality = 3 };

struct FilterSpec {
  FilterId id;
  const char* name;         //!< menu entry and .mlx name
  const char* python_name;  //!< pymeshlab's name
  std::string info;         //!< HTML description shown above the parameters
};

enum class ParamKind { Bool, Int, Float, Mesh };

struct ParamSpec {
  FilterId filter;
  const char* key;    //!< .mlx name; pymeshlab lowercases it
  const char* label;  //!< dialog label
  ParamKind kind;
  double value;       //!< default (for TargetFaceNum: see default_target_faces())
  double min, max;    //!< accepted range (checked before running)
  const char* help;   //!< tooltip
};

const std::vector<FilterSpec>& filter_specs();
const FilterSpec& filter_spec(FilterId id);
//! The parameters of one filter, in dialog order.
std::vector<ParamSpec> params_of(FilterId id);

//! Default target of the simplification: a tenth of the input's quads (about a
//! twentieth of its triangles), at least 6.
int default_target_faces(int n_triangles);

}  // namespace qs::plugin
