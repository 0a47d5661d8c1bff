// Fuzz target: the PFM decoder (frontend/image/image_files.hpp, decode_image). Malformed input must
// end in vplkit::error; an image that decodes must have the size it claims and finite pixels.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "frontend/core/error.hpp"
#include "frontend/image/image_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  vplkit::image_read_limits limits;
  limits.max_side = 4096;
  limits.max_pixels = std::size_t{1} << 20;
  try {
    const vplkit::image decoded = vplkit::decode_image(bytes, vplkit::image_file_format::pfm, "fuzz.pfm", limits);
    if (decoded.width < 1 || decoded.height < 1 || decoded.texels.size() != static_cast<std::size_t>(decoded.width) * static_cast<std::size_t>(decoded.height) ||
        size < decoded.texels.size() * 12) {
      std::fprintf(stderr, "fuzz_pfm: the decoded size does not match the input\n");
      std::abort();
    }
    for (const glm::vec4& p : decoded.texels)
      if (!std::isfinite(p.r) || !std::isfinite(p.g) || !std::isfinite(p.b)) {
        std::fprintf(stderr, "fuzz_pfm: a decoded pixel is not finite\n");
        std::abort();
      }
  } catch (const vplkit::error&) {
  }
  return 0;
}
