// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/texture/texture_bake.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "quadsimp/reference/reference_surface.h"
#include "quadsimp/util/parallel.h"

namespace qs {
namespace {

// Bilinear, repeating: coordinates past [0, 1] tile the image, as OBJ's do by default.
std::array<double, 4> sample(const Image& im, TexCoord uv) {
  // Wrapped into the image first, so that coordinates far out stay exact enough and
  // whole; ones that are not numbers read its first texel.
  const auto wrap = [](double x, int n) { return std::isfinite(x) ? x - n * std::floor(x / n) : 0.0; };
  const double x = wrap(double(uv[0]) * im.width - 0.5, im.width);
  const double y = wrap((1.0 - double(uv[1])) * im.height - 0.5, im.height);
  const auto x0 = std::size_t(x), y0 = std::size_t(y);
  const std::size_t xs[2] = {x0 % std::size_t(im.width), (x0 + 1) % std::size_t(im.width)};
  const std::size_t ys[2] = {y0 % std::size_t(im.height), (y0 + 1) % std::size_t(im.height)};
  const double fx = x - double(x0), fy = y - double(y0);
  std::array<double, 4> c{};
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) {
      const double w = (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy);
      const std::size_t at = 4 * (ys[dy] * std::size_t(im.width) + xs[dx]);
      for (int k = 0; k < 4; ++k) c[k] += w * im.rgba[at + k];
    }
  return c;
}

// Texels the images spend on a unit of the surface they cover: its textured triangles'
// areas in texture space over their areas on `surface` (the texture's triangles; 0 where
// none is textured).
double texels_per_area(const TriMesh& surface, const FileTexture& t, const std::vector<Image>& images) {
  double texels = 0, area = 0;
  for (std::size_t i = 0; i < t.triangles.size(); ++i) {
    if (t.image[i] < 0) continue;
    const auto& c = t.coords[i];
    const double uv_area = 0.5 * std::abs(double(c[1][0] - c[0][0]) * (c[2][1] - c[0][1]) -
                                          double(c[2][0] - c[0][0]) * (c[1][1] - c[0][1]));
    const Image& im = images[std::size_t(t.image[i])];
    texels += uv_area * im.width * im.height;
    area += 0.5 * surface.area_normal(surface.faces[i]).norm();
  }
  return area > 0 ? texels / area : 0.0;
}

// A quad's square in the atlas, its one-texel border included.
struct Tile {
  int x = 0, y = 0, size = 0;
};

// The tiles' places, and the atlas's size.
struct Atlas {
  std::vector<Tile> tiles;
  int width = 0, height = 0;
};

// Tiles of `sizes` on shelves at most `width` wide, largest first (then by quad), each shelf
// as tall as its first.
Atlas pack(const std::vector<int>& sizes, int width) {
  std::vector<std::size_t> order(sizes.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return sizes[a] > sizes[b]; });
  Atlas atlas;
  atlas.tiles.resize(sizes.size());
  int x = 0, y = 0, shelf = 0;
  for (const std::size_t i : order) {
    if (x + sizes[i] > width && x > 0) x = 0, y += shelf, shelf = 0;
    atlas.tiles[i] = {x, y, sizes[i]};
    x += sizes[i];
    shelf = std::max(shelf, sizes[i]);
    atlas.width = std::max(atlas.width, x);
  }
  atlas.height = y + shelf;
  return atlas;
}

// Where each quad's tile goes. A tile holds as many texels as the input's images spend on
// the quad's area (`texels_per_area`, the input's texel density), so that a large quad's
// texture is no coarser than a small one's: 6 to 256 texels a side. Where the atlas would pass
// options.max_side, every tile shrinks alike (to kLeastTile texels at least). options.tile
// gives every quad that size, in a square grid.
Atlas layout(const QuadMesh& quads, const std::vector<Index>& faces, const TextureBakeOptions& options,
             double texels_per_area) {
  const std::size_t n = faces.size();
  if (options.tile > 0) {
    const int columns = int(std::ceil(std::sqrt(double(n))));
    const int rows = int((n + std::size_t(columns) - 1) / std::size_t(columns));
    const int fit = options.max_side / std::max(columns, rows);
    const int tile = std::max(TextureBakeOptions::kLeastTile, std::min(options.tile, fit));
    return pack(std::vector<int>(n, tile), columns * tile);
  }
  std::vector<double> side(n);  // each quad's size: the root of its area
  for (std::size_t i = 0; i < n; ++i) side[i] = std::sqrt(0.5 * quads.face_area_normal(faces[i]).norm());
  double density = std::sqrt(texels_per_area);  // texels along a unit of length
  std::vector<int> sizes(n);
  for (int attempt = 0;; ++attempt) {
    double texels = 0;
    int largest = 0;
    for (std::size_t i = 0; i < n; ++i) {
      // Inside the border: 4 texels at least, down to 1 (a tile of kLeastTile) once the atlas
      // has had to shrink.
      sizes[i] = 2 + std::clamp(int(std::lround(density * side[i])), attempt == 0 ? 4 : 1, 254);
      texels += double(sizes[i]) * sizes[i];
      largest = std::max(largest, sizes[i]);
    }
    // Shelves about as wide as the atlas is tall, in whole largest tiles.
    const int width = std::max(1, int(std::ceil(std::sqrt(texels) / largest))) * largest;
    Atlas atlas = pack(sizes, width);
    const int extent = std::max(atlas.width, atlas.height);
    if (extent <= options.max_side || largest <= TextureBakeOptions::kLeastTile || attempt == 30) return atlas;
    density *= 0.97 * options.max_side / extent;
  }
}

}  // namespace

QuadTexture bake_texture(const std::vector<Vec3>& positions, const FileTexture& texture,
                         const std::vector<Image>& images, const QuadMesh& quads, const TextureBakeOptions& options) {
  for (int i : texture.image)
    if (i < 0 ? texture.colours.size() != texture.triangles.size()
              : std::size_t(i) >= images.size() || images[std::size_t(i)].empty())
      throw std::invalid_argument("bake_texture: a triangle's image (or colour) is missing");
  if (!options.split.empty() && options.split.size() != quads.face_capacity())
    throw std::invalid_argument("bake_texture: one split per face id expected");
  std::vector<Index> faces;
  for (Index f = 0; f < quads.face_capacity(); ++f)
    if (quads.is_face_live(f)) faces.push_back(f);
  QuadTexture out;
  if (faces.empty() || texture.empty()) return out;

  TriMesh soup;
  soup.positions = positions;
  soup.faces = texture.triangles;
  const double density = texels_per_area(soup, texture, images);
  const ReferenceSurface surface(std::move(soup));
  const Atlas atlas = layout(quads, faces, options, density);
  const std::vector<Tile>& tiles = atlas.tiles;
  Image& im = out.image;
  im.width = atlas.width, im.height = atlas.height;
  // Opaque black where no tile is: an opaque input gives an opaque atlas (written as RGB).
  im.rgba.assign(std::size_t(im.width) * std::size_t(im.height) * 4, 0);
  for (std::size_t i = 3; i < im.rgba.size(); i += 4) im.rgba[i] = 255;
  out.corners.assign(quads.face_capacity(), {});
  parallel_for_as_here(std::size_t(0), faces.size(), [&](std::size_t i) {
    const Index f = faces[i];
    const auto p = quads.positions_of(quads.face_vertices(f));
    const int x0 = tiles[i].x, y0 = tiles[i].y, tile = tiles[i].size, inner = tile - 2;
    // Tile coordinates (s, t) in [0, 1]^2, t upwards: corner 0 at (0, 0), 1 at (1, 0), 2 at (1, 1).
    const double W = im.width, H = im.height;
    out.corners[f] = {TexCoord{float((x0 + 1) / W), float(1 - (y0 + 1 + inner) / H)},
                      TexCoord{float((x0 + 1 + inner) / W), float(1 - (y0 + 1 + inner) / H)},
                      TexCoord{float((x0 + 1 + inner) / W), float(1 - (y0 + 1) / H)},
                      TexCoord{float((x0 + 1) / W), float(1 - (y0 + 1) / H)}};
    const Vec3 normal = quads.face_area_normal(f);
    const bool split_13 = !options.split.empty() && options.split[f];
    const double reach = std::max((p[2] - p[0]).norm(), (p[3] - p[1]).norm());
    // A texel's closest point lies within the last one's distance and a texel's width: a
    // search bounded by that prunes more of the BVH (20% faster on BM_BakeTexture), and
    // finds the same point, but for ties.
    const double step = reach / inner;
    double last = reach;
    for (int b = 0; b < inner; ++b)
      for (int a = 0; a < inner; ++a) {
        const double s = (a + 0.5) / inner, t = 1 - (b + 0.5) / inner;
        Vec3 at;
        if (split_13)
          at = s + t <= 1 ? Vec3(p[0] + s * (p[1] - p[0]) + t * (p[3] - p[0]))
                          : Vec3(p[2] + (1 - s) * (p[3] - p[2]) + (1 - t) * (p[1] - p[2]));
        else
          at = s >= t ? Vec3(p[0] + s * (p[1] - p[0]) + t * (p[2] - p[1]))
                      : Vec3(p[0] + t * (p[3] - p[0]) + s * (p[2] - p[3]));
        SurfacePoint foot = surface.closest(at, std::min(reach, last + 2 * step), normal);
        if (!foot.found()) foot = surface.closest(at, reach, normal);
        if (!foot.found()) foot = surface.closest(at);
        if (!foot.found()) continue;  // every triangle without area: the texel stays black
        last = foot.distance;
        const std::size_t k = std::size_t(foot.face);
        const std::size_t at_texel = std::size_t(y0 + 1 + b) * std::size_t(im.width) + std::size_t(x0 + 1 + a);
        std::uint8_t* texel = &im.rgba[4 * at_texel];
        if (texture.image[k] < 0) {
          std::copy_n(texture.colours[k].begin(), 4, texel);
          continue;
        }
        const auto& c = texture.coords[k];
        const double w0 = 1 - foot.u - foot.v;
        const TexCoord uv{float(w0 * c[0][0] + foot.u * c[1][0] + foot.v * c[2][0]),
                          float(w0 * c[0][1] + foot.u * c[1][1] + foot.v * c[2][1])};
        const auto colour = sample(images[std::size_t(texture.image[k])], uv);
        for (int j = 0; j < 4; ++j) texel[j] = colour_byte(colour[j]);
      }
    // The border: each texel a copy of the nearest inner one.
    for (int y = 0; y < tile; ++y)
      for (int x = 0; x < tile; ++x) {
        if (x > 0 && x < tile - 1 && y > 0 && y < tile - 1) continue;
        const int xi = std::clamp(x, 1, tile - 2), yi = std::clamp(y, 1, tile - 2);
        const std::size_t from = 4 * (std::size_t(y0 + yi) * std::size_t(im.width) + std::size_t(x0 + xi));
        const std::size_t to = 4 * (std::size_t(y0 + y) * std::size_t(im.width) + std::size_t(x0 + x));
        std::copy_n(&im.rgba[from], 4, &im.rgba[to]);
      }
  });
  return out;
}

std::string oversize_note(const QuadTexture& t, int max_side) {
  if (std::max(t.image.width, t.image.height) <= max_side) return {};
  return "the quads' texture is " + std::to_string(t.image.width) + " x " + std::to_string(t.image.height) +
         " texels, past the texture size of " + std::to_string(max_side) +
         ": too many quads for it at " + std::to_string(TextureBakeOptions::kLeastTile) +
         " texels a side, the least a tile takes";
}

}  // namespace qs
