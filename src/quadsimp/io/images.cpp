// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/io/images.h"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <system_error>

#include "quadsimp/util/errors.h"

// stb's single-file libraries (Debian's libstb-dev), compiled here, their functions kept
// to this file. USERMSG: stb's failure reasons read "Corrupt PNG", not "outofdata".
#define STB_IMAGE_STATIC
#define STBI_FAILURE_USERMSG
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

namespace qs {

Image read_image(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail_file(path, "no such image file");
  int w = 0, h = 0, channels = 0;
  const std::unique_ptr<stbi_uc, void (*)(void*)> data(stbi_load(path.c_str(), &w, &h, &channels, 4), stbi_image_free);
  if (!data) fail_file(path, std::string("cannot be read as an image (") + stbi_failure_reason() + ")");
  Image im;
  im.width = w, im.height = h;
  im.rgba.assign(data.get(), data.get() + std::size_t(w) * std::size_t(h) * 4);
  return im;
}

void write_png(const std::string& path, const Image& im) {
  bool opaque = true;
  for (std::size_t i = 3; i < im.rgba.size() && opaque; i += 4) opaque = im.rgba[i] == 255;
  std::vector<std::uint8_t> rgb;
  if (opaque) {
    rgb.reserve(im.rgba.size() / 4 * 3);
    for (std::size_t i = 0; i < im.rgba.size(); i += 4) rgb.insert(rgb.end(), &im.rgba[i], &im.rgba[i] + 3);
  }
  const int channels = opaque ? 3 : 4;
  const std::uint8_t* data = opaque ? rgb.data() : im.rgba.data();
  if (!stbi_write_png(path.c_str(), im.width, im.height, channels, data, im.width * channels))
    fail_file(path, "cannot be written");
}

QuadTexture texture_of_quads(const MeshFile& from, const QuadMesh& quads, const TextureBakeOptions& options) {
  if (from.texture.empty()) return {};
  std::vector<Image> images;
  images.reserve(from.texture.images.size());
  for (const std::string& path : from.texture.images) images.push_back(read_image(path));
  return bake_texture(from.positions, from.texture, images, quads, options);
}

}  // namespace qs
