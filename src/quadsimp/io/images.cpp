// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/io/images.h"

#include <png.h>
#include <turbojpeg.h>

#include <algorithm>
#include <cctype>
#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <system_error>

#include "quadsimp/util/errors.h"

// PNG and JPEG, nearly every texture, are decoded by libpng and libjpeg-turbo, which
// Debian keeps patched. stb's single-file decoders (Debian's libstb-dev, a 2022 snapshot)
// read only BMP and TGA here: fuzzing found its JPEG decoder writing past a Huffman table,
// and its PNM reader reading 16-bit files past their texels (scripts/fuzz.sh image).
// Its allocations are zeroed, so that texels a file is too short for hold no heap bytes
// of ours. stb's writer still writes our PNGs. USERMSG: failure reasons read "Corrupt BMP".
#define STBI_MALLOC(size) std::calloc(1, size)
#define STBI_REALLOC(p, size) std::realloc(p, size)
#define STBI_FREE(p) std::free(p)
#define STB_IMAGE_STATIC
#define STBI_FAILURE_USERMSG
#define STBI_NO_STDIO
#define STBI_ONLY_BMP
#define STBI_ONLY_TGA
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

namespace qs {
namespace {

bool starts_with(const std::vector<std::uint8_t>& bytes, const char* magic, std::size_t n) {
  return bytes.size() >= n && std::memcmp(bytes.data(), magic, n) == 0;
}

// An image of w x h texels, or why not: checked from the header, before the texels are
// allocated, since a few bytes of header can ask for gigabytes.
std::string size_refused(std::size_t w, std::size_t h) {
  if (w == 0 || h == 0) return "an image of no texels";
  if (w * h <= kMaxImageTexels) return {};
  return "an image of " + std::to_string(w) + " x " + std::to_string(h) + " texels, more than the " +
         std::to_string(kMaxImageTexels) + " (16,384 squared) read";
}

// A header asking for more texels than the file's data can hold, however packed.
std::string too_short(std::size_t w, std::size_t h) {
  return "its data too short for its " + std::to_string(w) + " x " + std::to_string(h) + " texels";
}

// A w x h image of zeroed texels to decode into, if size_refused() allows it.
Image sized(const std::string& path, std::size_t w, std::size_t h) {
  if (const std::string why = size_refused(w, h); !why.empty()) fail_file(path, why);
  Image im;
  im.width = int(w), im.height = int(h);
  im.rgba.resize(w * h * 4);
  return im;
}

// libpng's errors do not return: the handler keeps the message and jumps back to
// decode_png()'s setjmp.
struct PngSource {
  const std::uint8_t* data;
  std::size_t size, at;
  char error[200];
};

[[noreturn]] void on_png_error(png_structp png, png_const_charp message) {
  std::snprintf(static_cast<PngSource*>(png_get_error_ptr(png))->error, sizeof(PngSource::error), "%s", message);
  png_longjmp(png, 1);
}

// A warning (a damaged ancillary chunk, a gamma out of range) leaves the texels readable.
void on_png_warning(png_structp, png_const_charp) {}

void read_png_bytes(png_structp png, png_bytep out, std::size_t n) {
  auto* source = static_cast<PngSource*>(png_get_io_ptr(png));
  if (n > source->size - source->at) png_error(png, "file cut short");
  std::memcpy(out, source->data + source->at, n);
  source->at += n;
}

// Why a PNG's header is refused, from its size alone: too many texels, or more rows
// (filter bytes included) than a file of `size` bytes holds, since deflate packs at most
// 1,032 bytes into one: a header of a few bytes asking for a gigabyte is cut short.
std::string png_size_refused(png_structp png, png_infop info, std::size_t size) {
  const std::size_t w = png_get_image_width(png, info), h = png_get_image_height(png, info);
  if (std::string why = size_refused(w, h); !why.empty()) return why;
  const std::size_t row_bits = w * png_get_channels(png, info) * png_get_bit_depth(png, info);
  if (h * (1 + (row_bits + 7) / 8) <= 1032 * size + 1024) return {};
  return too_short(w, h);
}

// Every libpng call that can fail is made in here, whose frame holds no C++ object, so
// that an error's longjmp skips no destructor. False with the reason in source's error.
bool decode_png(png_structp png, png_infop info, PngSource* source, Image* im, std::vector<png_bytep>* rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_info(png, info);
  const std::size_t w = png_get_image_width(png, info), h = png_get_image_height(png, info);
  if (const std::string why = png_size_refused(png, info, source->size); !why.empty()) {
    std::snprintf(source->error, sizeof(source->error), "%s", why.c_str());
    return false;  // `why` is gone before any later libpng call could jump
  }
  // The texels as stored, as MeshLab (Qt) reads them: no gamma or colour-space
  // conversion; 16-bit samples keep their high byte.
  png_set_expand(png);  // palettes and grey under 8 bits to 8 bits, tRNS to alpha
  png_set_strip_16(png);
  png_set_gray_to_rgb(png);
  png_set_add_alpha(png, 0xff, PNG_FILLER_AFTER);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  if (png_get_rowbytes(png, info) != w * 4) png_error(png, "unexpected row size after the conversion to RGBA");
  im->width = int(w), im->height = int(h);
  im->rgba.resize(w * h * 4);
  rows->resize(h);
  for (std::size_t y = 0; y < h; ++y) (*rows)[y] = im->rgba.data() + y * w * 4;
  png_read_image(png, rows->data());
  return true;  // what follows the texels (png_read_end) is not needed
}

struct PngReader {
  png_structp png = nullptr;
  png_infop info = nullptr;
  ~PngReader() {
    if (png) png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
  }
};

Image read_png(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  PngSource source{bytes.data(), bytes.size(), 0, "out of memory"};
  PngReader r;
  r.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &source, on_png_error, on_png_warning);
  if (r.png) r.info = png_create_info_struct(r.png);
  if (!r.info) fail_file(path, "cannot be read as a PNG image (out of memory)");
  png_set_read_fn(r.png, &source, read_png_bytes);
  Image im;
  std::vector<png_bytep> rows;
  if (!decode_png(r.png, r.info, &source, &im, &rows))
    fail_file(path, std::string("cannot be read as a PNG image (") + source.error + ")");
  return im;
}

Image read_jpeg(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  const std::unique_ptr<void, int (*)(tjhandle)> tj(tjInitDecompress(), tjDestroy);
  if (!tj) fail_file(path, "cannot be read as a JPEG image (libjpeg-turbo could not start)");
  const auto failed = [&] {
    fail_file(path, std::string("cannot be read as a JPEG image (") + tjGetErrorStr2(tj.get()) + ")");
  };
  int w = 0, h = 0, subsampling = 0, colour_space = 0;
  if (tjDecompressHeader3(tj.get(), bytes.data(), bytes.size(), &w, &h, &subsampling, &colour_space) != 0) failed();
  if (w <= 0 || h <= 0) fail_file(path, "cannot be read as a JPEG image (its header cut short)");
  Image im = sized(path, std::size_t(w), std::size_t(h));
  // CMYK and YCCK files (Adobe's, their samples inverted) are decoded as CMYK, four bytes
  // a texel as RGBA, and each channel is multiplied by K, as Qt (MeshLab) and stb read them.
  const bool cmyk = colour_space == TJCS_CMYK || colour_space == TJCS_YCCK;
  // A warning (data cut short, an extra byte) leaves what was decoded, as MeshLab shows
  // it; a progressive file of over 500 scans, which takes minutes to decode, is refused.
  if (tjDecompress2(tj.get(), bytes.data(), bytes.size(), im.rgba.data(), w, 0, h, cmyk ? TJPF_CMYK : TJPF_RGBA,
                    TJFLAG_LIMITSCANS) != 0 &&
      tjGetErrorCode(tj.get()) != TJERR_WARNING)
    failed();
  if (cmyk)
    for (std::size_t i = 0; i < im.rgba.size(); i += 4) {
      const unsigned k = im.rgba[i + 3];
      for (std::size_t c = 0; c < 3; ++c) im.rgba[i + c] = std::uint8_t((im.rgba[i + c] * k + 127) / 255);
      im.rgba[i + 3] = 255;
    }
  return im;
}

// What the file's first bytes say it is, for the message about a format not read.
const char* format_not_read(const std::vector<std::uint8_t>& bytes) {
  if (starts_with(bytes, "GIF8", 4)) return "GIF";
  if (starts_with(bytes, "8BPS", 4)) return "PSD";
  if (starts_with(bytes, "#?RADIANCE", 10) || starts_with(bytes, "#?RGBE", 6)) return "Radiance HDR";
  if (starts_with(bytes, "II*\0", 4) || starts_with(bytes, "MM\0*", 4)) return "TIFF";
  if (starts_with(bytes, "RIFF", 4) && bytes.size() >= 12 && std::memcmp(bytes.data() + 8, "WEBP", 4) == 0)
    return "WebP";
  return nullptr;
}

// Netpbm's six kinds (P1 to P6: bitmaps, grey and RGB, each written in decimal or in
// bytes) are read here, as Qt (MeshLab) reads them all: stb read P5 and P6 only, and
// overflowed on long numbers in their header, read 16-bit files past their texels and
// left files cut short black. Samples are scaled from the file's largest value to 255, as
// Qt reads them; a bitmap's 1 is black.
Image read_pnm(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  const auto refused = [&](const char* why) {
    fail_file(path, std::string("cannot be read as a PNM image (") + why + ")");
  };
  const char kind = char(bytes[1]);
  const bool decimal = kind <= '3', bitmap = kind == '1' || kind == '4';
  const std::size_t channels = kind == '3' || kind == '6' ? 3 : 1;
  std::size_t at = 2;
  // Whitespace and comments, which Netpbm allows between any two numbers.
  const auto skip_space = [&] {
    while (at < bytes.size() && (std::isspace(bytes[at]) || bytes[at] == '#'))
      if (bytes[at++] == '#')
        while (at < bytes.size() && bytes[at] != '\n' && bytes[at] != '\r') ++at;
  };
  // A decimal number of at most `digits` digits; false where there is none, or a longer one.
  const auto number = [&](std::size_t& value, std::size_t digits) {
    skip_space();
    const std::size_t start = at;
    value = 0;
    while (at < bytes.size() && std::isdigit(bytes[at]) && at - start < digits)
      value = value * 10 + (bytes[at++] - '0');
    return at > start && !(at < bytes.size() && std::isdigit(bytes[at]));
  };
  std::size_t w = 0, h = 0, largest = 1;
  if (!number(w, 9) || !number(h, 9) || (!bitmap && !number(largest, 9)))
    refused("a header of no width, height or largest value");
  if (largest == 0 || largest > 65535) refused("a largest value not from 1 to 65535");
  if (!decimal && (at >= bytes.size() || !std::isspace(bytes[at++]))) refused("cut short");
  if (const std::string why = size_refused(w, h); !why.empty()) fail_file(path, why);
  // Each sample takes a byte at least (a bit in P4), so a file too short is refused before
  // its texels are allocated.
  const std::size_t sample = largest > 255 ? 2 : 1;  // in bytes, big-endian
  const std::size_t row = kind == '4' ? (w + 7) / 8 : w * channels * sample;
  if (bytes.size() - at < (decimal ? w * channels : row) * h) refused("cut short");
  Image im = sized(path, w, h);
  std::size_t v[3] = {0, 0, 0};
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0, i = y * w; x < w; ++x, ++i) {
      for (std::size_t c = 0; c < channels; ++c) {
        if (kind == '1') {  // digits 0 and 1, spaces optional
          skip_space();
          if (at >= bytes.size() || (bytes[at] != '0' && bytes[at] != '1'))
            refused("cut short, or a sample not 0 or 1");
          v[c] = bytes[at++] - '0';
        } else if (decimal) {
          if (!number(v[c], 5)) refused("cut short, or a sample not a number of 5 digits at most");
        } else if (kind == '4') {
          v[c] = bytes[at + y * row + x / 8] >> (7 - x % 8) & 1;
        } else {
          const std::uint8_t* s = &bytes[at + y * row + (x * channels + c) * sample];
          v[c] = sample == 2 ? s[0] << 8 | s[1] : s[0];
        }
      }
      for (std::size_t c = 0; c < 3; ++c) {
        const std::size_t value = v[channels == 3 ? c : 0];
        im.rgba[4 * i + c] =
            bitmap ? (value ? 0 : 255) : std::uint8_t((std::min(value, largest) * 255 + largest / 2) / largest);
      }
      im.rgba[4 * i + 3] = 255;
    }
  return im;
}

Image read_with_stb(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  const int n = int(std::min<std::size_t>(bytes.size(), std::numeric_limits<int>::max()));
  int w = 0, h = 0, channels = 0;
  if (!stbi_info_from_memory(bytes.data(), n, &w, &h, &channels)) {
    if (const char* format = format_not_read(bytes))
      fail_file(path,
                std::string("a ") + format + " image: quadsimp reads PNG, JPEG, BMP, TGA and PNM; save it as PNG");
    fail_file(path, "cannot be read as an image (not PNG, JPEG, BMP, TGA or PNM, or corrupt)");
  }
  if (const std::string why = size_refused(std::size_t(std::max(w, 0)), std::size_t(std::max(h, 0))); !why.empty())
    fail_file(path, why);
  // No BMP stb reads (uncompressed) or TGA (runs of 128 texels at most) holds more than
  // 64 texels a byte: one that claims more is cut short, and stb would allocate its texels
  // and fill them with black, a texel at a time.
  if (std::size_t(w) * std::size_t(h) > 64 * bytes.size()) fail_file(path, too_short(std::size_t(w), std::size_t(h)));
  int loaded_w = 0, loaded_h = 0;
  const std::unique_ptr<stbi_uc, void (*)(void*)> data(
      stbi_load_from_memory(bytes.data(), n, &loaded_w, &loaded_h, &channels, 4), stbi_image_free);
  if (!data || loaded_w != w || loaded_h != h) {
    const char* why = stbi_failure_reason();  // none on some of stb's failures
    fail_file(path, std::string("cannot be read as an image (") + (why ? why : "corrupt") + ")");
  }
  Image im;
  im.width = w, im.height = h;
  im.rgba.assign(data.get(), data.get() + std::size_t(w) * std::size_t(h) * 4);
  return im;
}

}  // namespace

Image read_image(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail_file(path, "no such image file");
  std::ifstream in(path, std::ios::binary);
  const std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (!in && !in.eof()) fail_file(path, "cannot be read");
  if (starts_with(bytes, "\x89PNG\r\n\x1a\n", 8)) return read_png(path, bytes);
  if (starts_with(bytes, "\xff\xd8\xff", 3)) return read_jpeg(path, bytes);
  if (bytes.size() >= 2 && bytes[0] == 'P' && bytes[1] >= '1' && bytes[1] <= '6') return read_pnm(path, bytes);
  return read_with_stb(path, bytes);
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
