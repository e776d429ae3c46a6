// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <limits>

namespace qs {

using Vec3 = Eigen::Vector3d;
using Index = std::uint32_t;
inline constexpr Index kNone = std::numeric_limits<Index>::max();

}  // namespace qs
