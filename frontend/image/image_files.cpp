#include "frontend/image/image_files.hpp"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <limits>
#include <memory>
#include <cmath>
#include <string>

#include "frontend/core/error.hpp"
#include "frontend/core/files.hpp"
#include "frontend/image/png.hpp"

namespace vplkit {
namespace fs = std::filesystem;

std::vector<std::uint8_t> encode_png(int width, int height, const std::vector<std::uint8_t>& rgba8) { return encode_png_rgba8(width, height, rgba8); }

void require_finite_pixels(const image& linear) {
  for (int y = linear.height - 1; y >= 0; --y)
    for (int x = 0; x < linear.width; ++x) {
      const glm::vec4& p = linear.at(x, y);
      for (const float value : {p.r, p.g, p.b})
        if (!std::isfinite(value))
          throw error("pixel (" + std::to_string(x) + ", " + std::to_string(linear.height - 1 - y) + ") (from the top left) is " +
                      (std::isnan(value) ? "NaN" : "infinite") + "; vplkit writes finite images only");
    }
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

std::vector<std::uint8_t> encode_pfm(const image& linear) {
  require_finite_pixels(linear);
  const std::string header = "PF\n" + std::to_string(linear.width) + " " + std::to_string(linear.height) + "\n-1.0\n";
  std::vector<std::uint8_t> bytes;
  bytes.reserve(header.size() + linear.texels.size() * 12);
  bytes.insert(bytes.end(), header.begin(), header.end());
  // Rows bottom-up in both; -1.0 marks little-endian floats.
  for (const glm::vec4& texel : linear.texels) {
    const float values[3] = {texel.r, texel.g, texel.b};
    const auto* raw = reinterpret_cast<const std::uint8_t*>(values);
    bytes.insert(bytes.end(), raw, raw + sizeof values);
  }
  return bytes;
}

namespace {

bool is_pfm_space(char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t'; }

// The PFM header "PF <width> <height> <scale>" and the one whitespace byte that ends it, read by
// hand with bounded tokens (no stream extraction that could skip megabytes of whitespace).
struct pfm_header {
  int width = 0, height = 0;
  double scale = 0.0;
  std::size_t data_offset = 0;
};

pfm_header parse_pfm_header(const std::string& bytes, const std::string& name) {
  std::size_t at = 0;
  const auto fail = [&](const std::string& what) -> void { throw error(name + ": not an RGB PFM file (" + what + ")"); };
  const auto token = [&](const char* what) {
    std::size_t skipped = 0;
    while (at < bytes.size() && is_pfm_space(bytes[at]) && skipped < 64) ++at, ++skipped;
    const std::size_t begin = at;
    while (at < bytes.size() && !is_pfm_space(bytes[at]) && at - begin <= 32) ++at;
    if (at == begin || at - begin > 32 || at >= bytes.size()) fail(std::string("expected the header 'PF width height scale', the ") + what + " is missing or malformed");
    return std::string_view(bytes).substr(begin, at - begin);
  };
  if (bytes.size() < 2 || bytes.compare(0, 2, "PF") != 0) {
    if (bytes.size() >= 2 && bytes.compare(0, 2, "Pf") == 0) throw error(name + ": greyscale PFM files ('Pf') are not supported; vplkit reads RGB ('PF')");
    fail("it does not start with 'PF'");
  }
  at = 2;
  if (at >= bytes.size() || !is_pfm_space(bytes[at])) fail("it does not start with 'PF' and a space");
  pfm_header header;
  const auto side = [&](const char* what) {
    const std::string_view text = token(what);
    int value = 0;
    const auto [end, code] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (code != std::errc() || end != text.data() + text.size() || value < 1)
      throw error(name + ": PFM " + what + " '" + std::string(text) + "' is not a whole number >= 1");
    return value;
  };
  header.width = side("width");
  header.height = side("height");
  const std::string_view scale_text = token("scale");
  const auto [end, code] = std::from_chars(scale_text.data(), scale_text.data() + scale_text.size(), header.scale);
  if (code != std::errc() || end != scale_text.data() + scale_text.size() || !std::isfinite(header.scale) || header.scale == 0.0)
    throw error(name + ": PFM scale '" + std::string(scale_text) + "' is not a finite non-zero number");
  if (header.scale > 0.0) throw error(name + ": big-endian PFM files (positive scale) are not supported");
  header.data_offset = at + 1;  // exactly one whitespace byte ends the header
  return header;
}

void check_size(int width, int height, const std::string& name, const image_read_limits& limits) {
  if (width > limits.max_side || height > limits.max_side ||
      static_cast<std::size_t>(width) * static_cast<std::size_t>(height) > limits.max_pixels)
    throw error(name + ": the image claims " + std::to_string(width) + "x" + std::to_string(height) + " pixels, more than vplkit reads (sides up to " +
                std::to_string(limits.max_side) + ", " + std::to_string(limits.max_pixels) + " pixels in all)");
}

image decode_pfm(const std::string& bytes, const std::string& name, const image_read_limits& limits) {
  const pfm_header header = parse_pfm_header(bytes, name);
  check_size(header.width, header.height, name, limits);
  const std::size_t pixel_count = static_cast<std::size_t>(header.width) * static_cast<std::size_t>(header.height);
  const std::size_t expected = header.data_offset + pixel_count * 12;
  if (bytes.size() < expected)
    throw error(name + ": the PFM file ends before its " + std::to_string(header.width) + "x" + std::to_string(header.height) + " pixels (" +
                std::to_string(bytes.size()) + " bytes, " + std::to_string(expected) + " needed)");
  if (bytes.size() > expected)
    throw error(name + ": " + std::to_string(bytes.size() - expected) + " bytes follow the " + std::to_string(header.width) + "x" +
                std::to_string(header.height) + " pixels of the PFM file");
  image decoded(header.width, header.height);
  const char* data = bytes.data() + header.data_offset;
  for (int y = 0; y < header.height; ++y)  // PFM rows are bottom-up, as in vplkit::image
    for (int x = 0; x < header.width; ++x, data += 12) {
      float values[3];
      std::memcpy(values, data, sizeof values);
      for (const float value : values)
        if (!std::isfinite(value))
          throw error(name + ": pixel (" + std::to_string(x) + ", " + std::to_string(header.height - 1 - y) + ") (from the top left) is " +
                      (std::isnan(value) ? "NaN" : "infinite") + "; vplkit compares finite images");
      decoded.at(x, y) = glm::vec4(values[0], values[1], values[2], 1.0f);
    }
  return decoded;
}

image decode_png(const std::string& bytes, const std::string& name, const image_read_limits& limits) {
  const rgba8_image decoded = decode_png_rgba8(bytes, name, limits);
  image linear(decoded.width, decoded.height);
  const auto to_linear = [&](std::uint8_t code) { return decoded.srgb ? srgb_to_linear(code / 255.0f) : code / 255.0f; };
  for (int y = 0; y < decoded.height; ++y)  // PNG rows are top-down
    for (int x = 0; x < decoded.width; ++x) {
      const std::uint8_t* code = &decoded.pixels[4 * linear.index(x, decoded.height - 1 - y)];
      linear.at(x, y) = glm::vec4(to_linear(code[0]), to_linear(code[1]), to_linear(code[2]), 1.0f);
    }
  return linear;
}

}  // namespace

image decode_image(const std::string& bytes, image_file_format format, const std::string& name, const image_read_limits& limits) {
  return format == image_file_format::pfm ? decode_pfm(bytes, name, limits) : decode_png(bytes, name, limits);
}

image read_image_file(const fs::path& path, const image_read_limits& limits) {
  const std::string extension = path.extension().string();
  if (extension != ".pfm" && extension != ".png") throw error(path.string() + ": unsupported image format '" + extension + "' (use .pfm or .png)");
  const image_file_format format = extension == ".pfm" ? image_file_format::pfm : image_file_format::png;
  // The largest file the limits allow: a PFM's exact size; a PNG is compressed, so at most that.
  const std::uintmax_t max_bytes = 64 + static_cast<std::uintmax_t>(limits.max_pixels) * 12;
  return decode_image(read_file(path, max_bytes, extension == ".pfm" ? "PFM image" : "PNG image"), format, path.string(), limits);
}

}  // namespace vplkit
