// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstddef>
#include <string>

#include "quadsimp/mesh/mesh_file.h"
#include "quadsimp/mesh/quad_mesh.h"
#include "quadsimp/texture/texture_bake.h"

namespace qs {

//! The most texels read_image() takes (16,384 squared: 1 GiB as RGBA).
inline constexpr std::size_t kMaxImageTexels = std::size_t(1) << 28;

//! Reads a PNG (libpng), JPEG (libjpeg-turbo), BMP or TGA (stb), or PNM image of any
//! kind (ours: PBM, PGM, PPM, plain or raw) as RGBA, the texels as stored (no gamma
//! conversion), as MeshLab shows them: a CMYK JPEG's channels times K, PNM's samples
//! scaled from its largest value to 255, a PBM's 1 black.
//! \throw InvalidInput "PATH: why" for a file that is missing, not such an image (GIF,
//! PSD, HDR, TIFF and WebP named as such), corrupt, or over kMaxImageTexels.
Image read_image(const std::string& path);

//! Writes a PNG, RGB where every texel is opaque, RGBA otherwise (stb_image_write's
//! compression). \throw InvalidInput "PATH: why".
void write_png(const std::string& path, const Image& image);

//! The texture of `from` (read_mesh()'s) on the quads: its images read, and baked onto
//! them (bake_texture()). Empty where `from` has no texture.
//! \throw InvalidInput "IMAGE: why" for an image that cannot be read.
QuadTexture texture_of_quads(const MeshFile& from, const QuadMesh& quads, const TextureBakeOptions& options = {});

}  // namespace qs
