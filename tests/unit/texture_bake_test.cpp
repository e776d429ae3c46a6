// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/texture/texture_bake.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "fixtures/shapes.h"

using namespace qs;
using namespace qs::fixtures;

namespace {

// An image whose texel (x, y) has red x, green y and blue `blue` (x from the left, y from the top).
Image gradient(int size, std::uint8_t blue) {
  Image im;
  im.width = im.height = size;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) im.rgba.insert(im.rgba.end(), {std::uint8_t(x), std::uint8_t(y), blue, 255});
  return im;
}

// The texel of `t` at texture coordinates (u, v), nearest.
const std::uint8_t* texel(const QuadTexture& t, TexCoord uv) {
  const int x = std::clamp(int(uv[0] * t.image.width), 0, t.image.width - 1);
  const int y = std::clamp(int((1 - uv[1]) * t.image.height), 0, t.image.height - 1);
  return &t.image.rgba[4 * (std::size_t(y) * std::size_t(t.image.width) + std::size_t(x))];
}

// The texture coordinates of the point (s, t) of quad f's tile, from its corners' coordinates.
TexCoord in_tile(const QuadTexture& t, Index f, double s, double u) {
  const auto& c = t.corners[f];
  return {float(c[0][0] + s * (c[1][0] - c[0][0])), float(c[0][1] + u * (c[3][1] - c[0][1]))};
}

}  // namespace

// A unit square of 8 x 8 cells whose left half maps to one image and its right half to
// another, as a texture's charts do across a seam; 3 x 3 quads over it, lifted a little
// off it. Every texel away from the seam has the colour the input's texture has under it.
TEST(TextureBake, each_texel_takes_the_texture_under_it) {
  const TriMesh plane = tri_grid(8, 8);
  FileTexture tex;
  tex.images = {"left", "right"};
  for (const auto& f : plane.faces) {
    double cx = 0;
    for (Index v : f) cx += plane.positions[v].x() / 3;
    std::array<TexCoord, 3> uv;
    // Left: (x, y) scaled to the first image's middle half; right: the second image, mirrored.
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = plane.positions[f[k]];
      uv[k] = cx < 0.5 ? TexCoord{float(0.25 + 0.5 * p.x()), float(0.25 + 0.5 * p.y())}
                       : TexCoord{float(1 - p.x()), float(p.y())};
    }
    tex.triangles.push_back(f);
    tex.coords.push_back(uv);
    tex.image.push_back(cx < 0.5 ? 0 : 1);
  }
  const std::vector<Image> images = {gradient(256, 0), gradient(256, 200)};
  QuadMesh quads = quad_grid(3, 3);
  for (Index v = 0; v < quads.n_vertices(); ++v) quads.position(v) = quads.position(v) / 3 + Vec3(0, 0, 0.01);

  const QuadTexture t = bake_texture(plane.positions, tex, images, quads, {12});
  ASSERT_FALSE(t.empty());
  EXPECT_EQ(t.image.width, 3 * 12);
  EXPECT_EQ(t.image.height, 3 * 12);
  int checked = 0;
  for (Index f = 0; f < quads.n_faces(); ++f) {
    const auto p = quads.positions_of(quads.face_vertices(f));
    for (double s = 0.05; s < 1; s += 0.1)
      for (double u = 0.05; u < 1; u += 0.1) {
        // The grid's quads are squares: (s, u) is at p0 + s (p1 - p0) + u (p3 - p0).
        const Vec3 at = p[0] + s * (p[1] - p[0]) + u * (p[3] - p[0]);
        if (std::abs(at.x() - 0.5) < 0.06) continue;  // a texel across the seam blends both sides
        const bool left = at.x() < 0.5;
        const double tu = left ? 0.25 + 0.5 * at.x() : 1 - at.x(), tv = left ? 0.25 + 0.5 * at.y() : at.y();
        const std::uint8_t* c = texel(t, in_tile(t, f, s, u));
        SCOPED_TRACE(testing::Message() << "quad " << f << " at " << at.transpose());
        // A tile's texel is a tenth of a quad here: the point under it is within half of one.
        EXPECT_NEAR(c[0], 256 * tu, 256 * 0.5 * 0.34 / 10 * (left ? 0.5 : 1) + 2);
        EXPECT_NEAR(c[1], 256 * (1 - tv), 256 * 0.5 * 0.34 / 10 * (left ? 0.5 : 1) + 2);
        EXPECT_EQ(c[2], left ? 0 : 200);
        ++checked;
      }
  }
  EXPECT_GT(checked, 700);
}

// Each tile's border texels copy the inner ones beside them, so that filtering at a
// quad's edge does not read the next tile; the corners' coordinates lie inside the image.
TEST(TextureBake, tiles_have_a_border_of_their_own_texels) {
  const TriMesh plane = tri_grid(4, 4);
  FileTexture tex;
  tex.images = {"a"};
  for (const auto& f : plane.faces) {
    tex.triangles.push_back(f);
    std::array<TexCoord, 3> uv;
    for (int k = 0; k < 3; ++k) uv[k] = {float(plane.positions[f[k]].x()), float(plane.positions[f[k]].y())};
    tex.coords.push_back(uv);
    tex.image.push_back(0);
  }
  QuadMesh quads = quad_grid(2, 2);
  for (Index v = 0; v < quads.n_vertices(); ++v) quads.position(v) /= 2;
  const QuadTexture t = bake_texture(plane.positions, tex, {gradient(64, 9)}, quads, {8});
  ASSERT_EQ(t.image.width, 16);
  const auto at = [&](int x, int y) { return &t.image.rgba[4 * std::size_t(y * t.image.width + x)]; };
  for (int tile = 0; tile < 4; ++tile) {
    const int x0 = tile % 2 * 8, y0 = tile / 2 * 8;
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) {
        const int xi = std::clamp(x, 1, 6), yi = std::clamp(y, 1, 6);
        EXPECT_TRUE(std::equal(at(x0 + x, y0 + y), at(x0 + x, y0 + y) + 4, at(x0 + xi, y0 + yi)))
            << "tile " << tile << " texel " << x << ", " << y;
      }
  }
  for (Index f = 0; f < quads.n_faces(); ++f)
    for (const TexCoord& c : t.corners[f]) {
      EXPECT_GE(c[0], 1.f / 16);
      EXPECT_LE(c[0], 15.f / 16);
      EXPECT_GE(c[1], 1.f / 16);
      EXPECT_LE(c[1], 15.f / 16);
    }
  // No tile wider than the largest side allows.
  EXPECT_EQ(bake_texture(plane.positions, tex, {gradient(64, 9)}, quads, {8, 10}).image.width, 10);
  // Refused: an image missing or empty, a split for the wrong number of faces.
  EXPECT_THROW(bake_texture(plane.positions, tex, {}, quads), std::invalid_argument);
  EXPECT_THROW(bake_texture(plane.positions, tex, {Image{}}, quads), std::invalid_argument);
  TextureBakeOptions wrong;
  wrong.split = {0, 1};
  EXPECT_THROW(bake_texture(plane.positions, tex, {gradient(64, 9)}, quads, wrong), std::invalid_argument);
  // Triangles without area under the quads only: a texture all the same, no reading past them.
  FileTexture flat;
  flat.images = {"a"};
  flat.triangles = {{0, 1, 2}};  // three points of the grid's first row: collinear
  flat.coords = {{TexCoord{0, 0}, TexCoord{1, 0}, TexCoord{1, 1}}};
  flat.image = {0};
  EXPECT_EQ(bake_texture(plane.positions, flat, {gradient(64, 9)}, quads, {8}).image.width, 16);
  // Nothing to bake: no texture, or no quad.
  EXPECT_TRUE(bake_texture(plane.positions, FileTexture{}, {}, quads).empty());
  EXPECT_TRUE(bake_texture(plane.positions, tex, {gradient(64, 9)}, QuadMesh()).empty());
}

// A quad halfway between the two sheets of a thin plate takes the texture of the sheet that
// faces its way, not of whichever is nearer by rounding.
TEST(TextureBake, quads_take_the_sheet_facing_their_way) {
  TriMesh plate = tri_grid(2, 2);
  const Index n = plate.n_vertices();
  for (Index v = 0; v < n; ++v) plate.positions.push_back(plate.positions[v] - Vec3(0, 0, 0.02));
  const std::size_t top = plate.faces.size();
  for (std::size_t f = 0; f < top; ++f)
    plate.faces.push_back({plate.faces[f][0] + n, plate.faces[f][2] + n, plate.faces[f][1] + n});
  plate.positions[0].z() += 1e-9;  // the top sheet a hair nearer at one corner
  FileTexture tex;
  tex.images = {"top", "bottom"};
  for (std::size_t f = 0; f < plate.faces.size(); ++f) {
    tex.triangles.push_back(plate.faces[f]);
    tex.coords.push_back({TexCoord{0.5f, 0.5f}, TexCoord{0.5f, 0.5f}, TexCoord{0.5f, 0.5f}});
    tex.image.push_back(f < top ? 0 : 1);
  }
  Image red, green;
  red.width = red.height = green.width = green.height = 1;
  red.rgba = {255, 0, 0, 255};
  green.rgba = {0, 255, 0, 255};
  QuadMesh up = single_quad();
  for (Index v = 0; v < 4; ++v) up.position(v) -= Vec3(0, 0, 0.01);
  for (const bool facing_up : {true, false}) {
    QuadMesh q = facing_up ? up : QuadMesh::from_faces(up.positions(), {{0, 3, 2, 1}});
    const QuadTexture t = bake_texture(plate.positions, tex, {red, green}, q, {6});
    for (std::size_t i = 0; i < t.image.rgba.size(); i += 4) {
      ASSERT_EQ(t.image.rgba[i], facing_up ? 255 : 0) << "facing up " << facing_up;
      ASSERT_EQ(t.image.rgba[i + 1], facing_up ? 0 : 255) << "facing up " << facing_up;
    }
  }
}

// A quad that is not flat is drawn as two triangles, split at corners 0-2 (OBJ) or 1-3
// (MeshLab's layers, where split_diagonals() says so): the texture follows the split it is
// told. The input here is the quad itself, split at 1-3, its texture its own (s, t).
TEST(TextureBake, texels_follow_the_split_the_quad_is_drawn_with) {
  QuadMesh quad = single_quad();
  quad.position(1).z() = 0.6;  // corners 1 and 3 up: the two splits differ by 0.6 in the middle
  quad.position(3).z() = 0.6;
  TriMesh input;
  input.positions = quad.positions();
  input.faces = {{0, 1, 3}, {1, 2, 3}};
  const TexCoord st[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  FileTexture tex;
  tex.images = {"st"};
  for (const auto& f : input.faces) {
    tex.triangles.push_back(f);
    tex.coords.push_back({st[f[0]], st[f[1]], st[f[2]]});
    tex.image.push_back(0);
  }
  const std::vector<Image> image = {gradient(256, 0)};
  double worst[2] = {0, 0};
  for (const bool split_13 : {true, false}) {
    TextureBakeOptions options{18};
    options.split = {std::uint8_t(split_13)};
    const QuadTexture t = bake_texture(input.positions, tex, image, quad, options);
    for (int b = 0; b < 16; ++b)
      for (int a = 0; a < 16; ++a) {
        const double s = (a + 0.5) / 16, u = 1 - (b + 0.5) / 16;
        const std::uint8_t* c = texel(t, in_tile(t, 0, s, u));
        worst[split_13] = std::max({worst[split_13], std::abs(c[0] - (256 * s - 0.5)),
                                    std::abs(c[1] - (256 * (1 - u) - 0.5))});
      }
  }
  EXPECT_LT(worst[1], 2);
  EXPECT_GT(worst[0], 20);
}

// A quad twice as wide as another gets a tile twice as wide, so that both have the input's
// texel density; tiles never overlap, and a smaller largest side shrinks them alike.
TEST(TextureBake, tiles_follow_the_quads_sizes) {
  TriMesh plane = tri_grid(6, 4);  // [0, 3] x [0, 2]
  for (Vec3& p : plane.positions) p = Vec3(3 * p.x(), 2 * p.y(), 0);
  FileTexture tex;
  tex.images = {"a"};
  for (const auto& f : plane.faces) {
    tex.triangles.push_back(f);
    std::array<TexCoord, 3> uv;
    for (int k = 0; k < 3; ++k) uv[k] = {float(plane.positions[f[k]].x() / 3), float(plane.positions[f[k]].y() / 2)};
    tex.coords.push_back(uv);
    tex.image.push_back(0);
  }
  // A unit square and a square of side 2 beside it, 0.01 above the plane.
  const QuadMesh quads = QuadMesh::from_faces(
      {{0, 0, 0.01}, {1, 0, 0.01}, {1, 1, 0.01}, {0, 1, 0.01}, {1, 0, 0.01}, {3, 0, 0.01}, {3, 2, 0.01}, {1, 2, 0.01}},
      {{0, 1, 2, 3}, {4, 5, 6, 7}});
  const auto inner_width = [](const QuadTexture& t, Index f) {
    return std::lround((t.corners[f][1][0] - t.corners[f][0][0]) * float(t.image.width));
  };
  for (const int side : {512, 128, 40}) {
    SCOPED_TRACE(side);
    const QuadTexture t = bake_texture(plane.positions, tex, {gradient(side, 0)}, quads);
    // The image spends side^2 / 6 texels on each unit of area: side / sqrt(6) along a unit.
    const double small = std::max(4.0, side / std::sqrt(6.0));
    EXPECT_NEAR(inner_width(t, 0), std::min(254.0, small), 1);
    EXPECT_NEAR(inner_width(t, 1), std::min(254.0, 2 * side / std::sqrt(6.0)), 1);
    // The two tiles, borders included, do not overlap: [x0, x1) x [y0, y1) in texels.
    const auto rect = [&](Index f) {
      const long x0 = std::lround(t.corners[f][0][0] * float(t.image.width)) - 1;
      const long y0 = std::lround((1 - t.corners[f][3][1]) * float(t.image.height)) - 1;
      const long w = inner_width(t, f) + 2;
      return std::array<long, 4>{x0, y0, x0 + w, y0 + w};
    };
    const auto a = rect(0), b = rect(1);
    EXPECT_TRUE(a[2] <= b[0] || b[2] <= a[0] || a[3] <= b[1] || b[3] <= a[1]);
    EXPECT_LE(std::max(a[2], b[2]), t.image.width);
    EXPECT_LE(std::max(a[3], b[3]), t.image.height);
  }
  TextureBakeOptions small_atlas;
  small_atlas.max_side = 60;
  const QuadTexture t = bake_texture(plane.positions, tex, {gradient(512, 0)}, quads, small_atlas);
  EXPECT_LE(std::max(t.image.width, t.image.height), 60);
  EXPECT_NEAR(double(inner_width(t, 1)) / double(inner_width(t, 0)), 2.0, 0.25);
}

// Triangles without an image (an OBJ's faces whose material has only a colour, beside
// textured ones) are baked in their colour, alpha included; the tiles' texel density is
// the textured part's alone.
TEST(TextureBake, faces_without_an_image_are_baked_in_their_colour) {
  TriMesh plane = tri_grid(6, 4);  // [0, 3] x [0, 2]
  for (Vec3& p : plane.positions) p = Vec3(3 * p.x(), 2 * p.y(), 0);
  const Colour green{10, 200, 30, 255}, red{250, 0, 0, 128};
  FileTexture tex;
  tex.images = {"a"};
  for (const auto& f : plane.faces) {
    double cx = 0;
    for (Index v : f) cx += plane.positions[v].x() / 3;
    std::array<TexCoord, 3> uv{};
    if (cx < 1)
      for (int k = 0; k < 3; ++k) uv[k] = {float(plane.positions[f[k]].x()), float(plane.positions[f[k]].y() / 2)};
    tex.triangles.push_back(f);
    tex.coords.push_back(uv);
    tex.image.push_back(cx < 1 ? 0 : -1);
    tex.colours.push_back(cx < 2 ? green : red);
  }
  // Three unit squares along x, 0.01 above the plane.
  std::vector<Vec3> p;
  std::vector<std::array<Index, 4>> faces;
  for (int i = 0; i < 3; ++i) {
    for (const auto& [x, y] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 1}}) p.emplace_back(i + x, y, 0.01);
    faces.push_back({Index(4 * i), Index(4 * i + 1), Index(4 * i + 2), Index(4 * i + 3)});
  }
  const QuadMesh quads = QuadMesh::from_faces(p, faces);
  const QuadTexture t = bake_texture(plane.positions, tex, {gradient(128, 0)}, quads);
  // The image spends 128^2 texels on the textured area of 2: 128 / sqrt(2) along a unit.
  const float inner = (t.corners[0][1][0] - t.corners[0][0][0]) * float(t.image.width);
  EXPECT_NEAR(inner, 128 / std::sqrt(2.0), 1);
  for (double s = 0.05; s < 1; s += 0.1)
    for (double u = 0.05; u < 1; u += 0.1) {
      SCOPED_TRACE(testing::Message() << s << ", " << u);
      const std::uint8_t* c = texel(t, in_tile(t, 0, s, u));
      EXPECT_NEAR(c[0], 128 * s, 2);  // the gradient: x along the quad
      EXPECT_EQ(c[2], 0);
      const std::uint8_t *g = texel(t, in_tile(t, 1, s, u)), *r = texel(t, in_tile(t, 2, s, u));
      EXPECT_EQ(Colour({g[0], g[1], g[2], g[3]}), green);
      EXPECT_EQ(Colour({r[0], r[1], r[2], r[3]}), red);
    }
  tex.colours.clear();
  EXPECT_THROW(bake_texture(plane.positions, tex, {gradient(128, 0)}, quads), std::invalid_argument);
}
