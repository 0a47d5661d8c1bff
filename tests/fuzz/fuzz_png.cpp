// Fuzz target: the PNG decoder (frontend/image/image_files.hpp, decode_image over decode_png_rgba8 and
// libspng, which is only reached for input with the PNG signature). Malformed input must end in vplkit::error; an
// image that decodes must have pixels in [0, 1] (sRGB bytes made linear), and its RGBA8 decoding
// must have the size it claims and be the same twice (an out-of-palette read of memory the file
// never gave would differ).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "frontend/core/error.hpp"
#include "frontend/image/image_files.hpp"
#include "frontend/image/png.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  vplkit::image_read_limits limits;
  limits.max_side = 1024;
  limits.max_pixels = std::size_t{1} << 16;  // fast runs; the limit's own check is exercised too
  try {
    const vplkit::image decoded = vplkit::decode_image(bytes, vplkit::image_file_format::png, "fuzz.png", limits);
    if (decoded.texels.size() != static_cast<std::size_t>(decoded.width) * static_cast<std::size_t>(decoded.height) ||
        decoded.texels.size() > limits.max_pixels) {
      std::fprintf(stderr, "fuzz_png: the decoded size does not match the image or exceeds the limit\n");
      std::abort();
    }
    for (const glm::vec4& p : decoded.texels)
      if (!(p.r >= 0.0f && p.r <= 1.0f && p.g >= 0.0f && p.g <= 1.0f && p.b >= 0.0f && p.b <= 1.0f)) {
        std::fprintf(stderr, "fuzz_png: a decoded pixel is outside [0, 1]\n");
        std::abort();
      }
    const vplkit::rgba8_image first = vplkit::decode_png_rgba8(bytes, "fuzz.png", limits), second = vplkit::decode_png_rgba8(bytes, "fuzz.png", limits);
    if (first.pixels.size() != static_cast<std::size_t>(decoded.width) * static_cast<std::size_t>(decoded.height) * 4 || first.pixels != second.pixels ||
        first.srgb != second.srgb) {
      std::fprintf(stderr, "fuzz_png: the RGBA8 decoding has the wrong size or differs between two runs\n");
      std::abort();
    }
  } catch (const vplkit::error&) {
  }
  return 0;
}
