// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <stdexcept>
#include <string>

namespace qs {

//! Input the library cannot work with (unreadable file, point cloud, NaN, non-manifold, ...).
//! The message is one sentence meant for the user.
class InvalidInput : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

//! Throws InvalidInput("PATH: why"), the form of every message about a mesh file.
[[noreturn]] inline void fail_file(const std::string& path, const std::string& why) {
  throw InvalidInput(path + ": " + why);
}

//! A broken internal invariant, found by validate(). Always a bug in quadsimp.
class TopologyError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

//! Thrown when a progress callback asks to stop.
class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("cancelled") {}
};

}  // namespace qs
