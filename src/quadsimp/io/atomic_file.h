// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <filesystem>
#include <string>
#include <system_error>

#include "quadsimp/util/errors.h"

namespace qs::detail {

//! Calls write(tmp) for a temporary file beside `path`, then renames it to `path`: readers
//! never see a partial file, and a failed write (write() throwing, or the rename refused)
//! leaves nothing behind. \throw InvalidInput "PATH: cannot be written (why)".
template <class WriteFn>
void write_atomically(const std::string& path, WriteFn&& write) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  fs::path tmp = target;
  tmp += ".part";
  tmp.replace_filename("." + tmp.filename().string());
  try {
    write(tmp.string());
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    fail_file(path, "cannot be written (" + ec.message() + ")");
  }
}

}  // namespace qs::detail
