// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <string>

#include "quadsimp/mesh/mesh_file.h"
#include "quadsimp/mesh/quad_mesh.h"
#include "quadsimp/texture/texture_bake.h"

namespace qs {

//! Reads a PNG, JPEG, BMP, TGA, GIF (its first frame), PSD, PNM or HDR image as RGBA.
//! \throw InvalidInput "PATH: why" for a file that is missing or not such an image.
Image read_image(const std::string& path);

//! Writes a PNG, RGB where every texel is opaque, RGBA otherwise (stb_image_write's
//! compression). \throw InvalidInput "PATH: why".
void write_png(const std::string& path, const Image& image);

//! The texture of `from` (read_mesh()'s) on the quads: its images read, and baked onto
//! them (bake_texture()). Empty where `from` has no texture.
//! \throw InvalidInput "IMAGE: why" for an image that cannot be read.
QuadTexture texture_of_quads(const MeshFile& from, const QuadMesh& quads, const TextureBakeOptions& options = {});

}  // namespace qs
