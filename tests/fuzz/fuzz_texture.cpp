// Fuzz target: the texture decoders (frontend/image/texture_decode.hpp): PNG through libspng and
// JPEG through TurboJPEG, chosen by the signature. Malformed input must end in vplkit::error; a
// texture that decodes must be within the limits and have width x height x 4 bytes.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "frontend/core/error.hpp"
#include "frontend/image/texture_decode.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  vplkit::texture_limits limits;
  limits.max_side = 1024;
  limits.max_pixels = std::size_t{1} << 16;  // fast runs; the limit's own check is exercised too
  try {
    const vplkit::texture_pixels decoded = vplkit::decode_texture(bytes, "fuzz texture", limits);
    const std::size_t pixels = static_cast<std::size_t>(decoded.width) * static_cast<std::size_t>(decoded.height);
    if (decoded.width < 1 || decoded.height < 1 || pixels > limits.max_pixels || decoded.rgba8.size() != 4 * pixels) {
      std::fprintf(stderr, "fuzz_texture: the decoded size does not match the image or exceeds the limits\n");
      std::abort();
    }
  } catch (const vplkit::error&) {
  }
  return 0;
}
