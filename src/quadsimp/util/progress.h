// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <functional>
#include <string_view>

namespace qs {

//! Called with the fraction done (0..1) of the named stage; returning false cancels.
using ProgressFn = std::function<bool(float fraction, std::string_view stage)>;

//! Log sink for notes the user should see (repairs applied to the input, fallbacks taken).
//! The core never prints; front ends decide where notes go.
using LogFn = std::function<void(std::string_view message)>;

}  // namespace qs
