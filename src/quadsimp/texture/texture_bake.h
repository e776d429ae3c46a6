// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "quadsimp/mesh/mesh_file.h"
#include "quadsimp/mesh/quad_mesh.h"

namespace qs {

//! An RGBA image, 8 bits a channel, its top row first.
struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
  bool empty() const { return rgba.empty(); }
};

//! A quad mesh's own texture: an atlas with a square tile per quad, and each quad corner's
//! coordinates into it (per face id; corner k of the face's vertex(f, k)).
struct QuadTexture {
  Image image;
  std::vector<std::array<TexCoord, 4>> corners;
  bool empty() const { return image.empty(); }
};

struct TextureBakeOptions {
  //! Texels along a tile's side, a one-texel border round it included; 0: the input's
  //! texel density (as many texels as its images spend on the surface), 6 to 256.
  int tile = 0;
  //! The atlas's largest width and height: tiles shrink to fit (to kLeastTile texels at
  //! least, so that many quads can pass it). 4,096: 64 MB in memory, which graphics cards
  //! and MeshLab's default texture memory take whole.
  int max_side = 4096;
  //! The range the CLI and the filters accept for max_side.
  static constexpr int kSmallestSide = 16, kLargestSide = 16384;
  //! Texels along a tile's side at the least (one inside its border), however many quads
  //! share max_side: oversize_note() says when that passes it.
  static constexpr int kLeastTile = 3;
  //! Per face id, nonzero where the quad is drawn as two triangles split at corners 1-3
  //! (MeshLab's layers: split_diagonals()); none: every quad split at corners 0-2.
  std::vector<std::uint8_t> split = {};
};

//! Bakes a file's texture onto quads whose vertices lie on (or near) its surface: each
//! quad gets its own tile, and each texel the colour of `images` (bilinear, repeating
//! past [0, 1]) at the point of the file's textured triangles closest to the texel's point
//! on the quad, among those facing the quad's way. A quad is read as the two triangles it
//! is drawn as (split at corners 0-2, as OBJ readers fan it, or as options.split says),
//! so that the texture follows the drawn surface.
//! A texture's seams need no care: every quad has a tile to itself.
//! \pre texture.image[t] < images.size() for every triangle, none of those images empty.
QuadTexture bake_texture(const std::vector<Vec3>& positions, const FileTexture& texture,
                         const std::vector<Image>& images, const QuadMesh& quads,
                         const TextureBakeOptions& options = {});

//! A note for the log where `t` came out wider or taller than `max_side` (too many quads
//! for it at the least a tile takes, TextureBakeOptions::kLeastTile); else "".
std::string oversize_note(const QuadTexture& t, int max_side);

}  // namespace qs
