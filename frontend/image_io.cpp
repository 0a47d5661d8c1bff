#include "frontend/image_io.hpp"

#include <stb/stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "frontend/error.hpp"

namespace vplkit {
namespace fs = std::filesystem;

namespace {

float linear_to_srgb(float value) {
  if (!(value > 0.0f)) return 0.0f;  // negative, zero and NaN
  value = std::min(value, 1.0f);
  return value <= 0.0031308f ? 12.92f * value : 1.055f * std::pow(value, 1.0f / 2.4f) - 0.055f;
}

void append_bytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(context);
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  out->insert(out->end(), bytes, bytes + size);
}

}  // namespace

std::vector<std::uint8_t> to_srgb8(const std::vector<float>& linear_rgba, int width, int height, float exposure) {
  std::vector<std::uint8_t> out(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t source = (static_cast<std::size_t>(y) * width + x) * 4;
      const std::size_t target = (static_cast<std::size_t>(height - 1 - y) * width + x) * 4;
      for (int c = 0; c < 3; ++c)
        out[target + c] = static_cast<std::uint8_t>(std::lround(255.0f * linear_to_srgb(exposure * linear_rgba[source + c])));
      out[target + 3] = 255;
    }
  }
  return out;
}

std::vector<std::uint8_t> encode_png(int width, int height, const std::vector<std::uint8_t>& rgba8) {
  if (width < 1 || height < 1 || rgba8.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4)
    throw error("PNG encoding: a " + std::to_string(width) + "x" + std::to_string(height) + " image needs " +
                std::to_string(static_cast<std::size_t>(std::max(width, 0)) * static_cast<std::size_t>(std::max(height, 0)) * 4) +
                " bytes of RGBA8, got " + std::to_string(rgba8.size()));
  std::vector<std::uint8_t> encoded;
  if (!stbi_write_png_to_func(append_bytes, &encoded, width, height, 4, rgba8.data(), width * 4)) throw error("PNG encoding failed");
  return encoded;
}

void write_png(const fs::path& path, int width, int height, const std::vector<std::uint8_t>& rgba8) {
  std::vector<std::uint8_t> encoded;
  try {
    encoded = encode_png(width, height, rgba8);
  } catch (const error& failure) {
    throw error("cannot write " + path.string() + ": " + failure.what());
  }
  write_bytes_atomically(path, encoded);
}

}  // namespace vplkit
