// PNG files through libspng (Debian's libspng-dev), decoded to 8-bit RGBA with every claim of the
// file checked before anything is allocated for it; the one PNG decoder of vplkit, for the images
// `compare` reads and for textures (a glTF's or an MTL's base colour):
//   - the signature, then the size in IHDR against image_read_limits (sides, pixels: the output's
//     memory) before the decoder starts; every chunk up to IEND must lie inside the file;
//   - the compressed image data (all IDAT chunks) may be at most 1.25 x the raw image's size +
//     4 KiB: no encoder needs more (stored deflate blocks add 0.01 %, fixed Huffman codes 12.5 %),
//     so an inflate bomb (a 1 MB IDAT that inflates to 1 GiB behind a 1 x 1 image) is refused
//     before a byte is inflated;
//   - ancillary chunks (text, ICC profiles) within spng's chunk limits, decompressed too;
//   - a palette image's every index within its palette (spng would read entries that the file
//     never gave).
// The caller's `name` starts every message; it says which file and what in it ("scene.gltf:
// image 2 (textures/wood.png)").
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "frontend/image/image.hpp"

namespace vplkit {

/// 8-bit RGBA, rows top-down, as a texture is uploaded.
struct rgba8_image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  ///< width x height x 4 bytes, rows top-down
  /// Whether RGB are sRGB-encoded: true when the file has an sRGB chunk or says nothing of its
  /// encoding (the web's and glTF's default for colour), false when its gAMA chunk says linear
  /// (gamma 1.0). Alpha is always linear.
  bool srgb = true;
};

/// Decodes a PNG of any colour type, bit depth and interlacing to RGBA8 (16-bit channels keep
/// their high byte; grey becomes RGB; a tRNS colour key or palette alpha becomes alpha, else 255).
/// Throws vplkit::error starting with `name` and saying what is wrong.
rgba8_image decode_png_rgba8(std::string_view bytes, const std::string& name, const image_read_limits& limits = {});

/// RGBA8 rows top-down encoded as a PNG file's bytes with an sRGB chunk. Throws vplkit::error
/// when the size does not match the pixels.
std::vector<std::uint8_t> encode_png_rgba8(int width, int height, const std::vector<std::uint8_t>& rgba8);

}  // namespace vplkit
