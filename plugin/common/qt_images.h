// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// Images between Qt, which MeshLab keeps textures in, and the core's RGBA Image.
#pragma once

#include <QImage>

#include <algorithm>

#include "quadsimp/texture/texture_bake.h"

namespace qs::plugin {

//! A QImage as RGBA, or an empty Image for a null one (a texture MeshLab could not load).
inline Image image_of(const QImage& q) {
  if (q.isNull()) return {};
  const QImage rgba = q.convertToFormat(QImage::Format_RGBA8888);
  Image im;
  im.width = rgba.width(), im.height = rgba.height();
  im.rgba.resize(std::size_t(im.width) * std::size_t(im.height) * 4);
  for (int y = 0; y < im.height; ++y)  // rows may be padded in a QImage
    std::copy_n(rgba.constScanLine(y), std::size_t(im.width) * 4, &im.rgba[std::size_t(y) * std::size_t(im.width) * 4]);
  return im;
}

inline QImage qimage_of(const Image& im) {
  QImage q(im.width, im.height, QImage::Format_RGBA8888);
  for (int y = 0; y < im.height; ++y)
    std::copy_n(&im.rgba[std::size_t(y) * std::size_t(im.width) * 4], std::size_t(im.width) * 4, q.scanLine(y));
  return q;
}

}  // namespace qs::plugin
