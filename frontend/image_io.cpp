#include "frontend/image_io.hpp"

#include <stb/stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>

#include "frontend/error.hpp"

namespace vplkit {
namespace fs = std::filesystem;

namespace {

float linear_to_srgb(float value) {
  value = std::clamp(value, 0.0f, 1.0f);
  return value <= 0.0031308f ? 12.92f * value : 1.055f * std::pow(value, 1.0f / 2.4f) - 0.055f;
}

void append_bytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(context);
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  out->insert(out->end(), bytes, bytes + size);
}

}  // namespace

void write_bytes_atomically(const fs::path& path, const std::vector<std::uint8_t>& bytes) {
  std::error_code code;
  const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
  fs::create_directories(parent, code);
  if (code || !fs::is_directory(parent))
    throw error("cannot write " + path.string() + ": cannot create folder " + parent.string() +
                (code ? " (" + code.message() + ")" : std::string(" (a file is in the way)")));
  std::random_device entropy;
  // Built with += rather than "." + string: GCC 12 gives a false -Wrestrict on the latter (bug 105329).
  std::string temporary_name = ".";
  temporary_name += path.filename().string();
  temporary_name += ".partial-";
  temporary_name += std::to_string(entropy());
  const fs::path temporary = parent / temporary_name;
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw error("cannot write " + path.string() + ": cannot create a file in " + parent.string());
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) {
      fs::remove(temporary, code);
      throw error("cannot write " + path.string() + ": the write failed (disk full?)");
    }
  }
  fs::rename(temporary, path, code);
  if (code) {
    fs::remove(temporary, code);
    throw error("cannot write " + path.string() + ": " + code.message());
  }
}

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

void write_png(const fs::path& path, int width, int height, const std::vector<std::uint8_t>& rgba8) {
  if (width < 1 || height < 1 || rgba8.size() != static_cast<std::size_t>(width) * height * 4)
    throw error("cannot write " + path.string() + ": image size does not match its pixels");
  std::vector<std::uint8_t> encoded;
  if (!stbi_write_png_to_func(append_bytes, &encoded, width, height, 4, rgba8.data(), width * 4))
    throw error("cannot write " + path.string() + ": PNG encoding failed");
  write_bytes_atomically(path, encoded);
}

}  // namespace vplkit
