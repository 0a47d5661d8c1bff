#include "frontend/image_metrics.hpp"

#include <stb/stb_image.h>

#include <algorithm>
#include <cmath>
#include <charconv>
#include <cstring>
#include <memory>
#include <fstream>
#include <limits>
#include <sstream>

#include <vplkit/lightwave.hpp>

#include "frontend/error.hpp"
#include "frontend/render_target.hpp"
#include "frontend/files.hpp"
#include "frontend/image_io.hpp"

namespace vplkit {
namespace fs = std::filesystem;

namespace {

// In double: the luminance of finite float pixels can exceed FLT_MAX.
double luminance_of(const glm::vec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

float srgb_to_linear(float value) {
  return value <= 0.04045f ? value / 12.92f : std::pow((value + 0.055f) / 1.055f, 2.4f);
}

void require_same_size(const float_image& a, const float_image& b, const char* what) {
  if (a.width != b.width || a.height != b.height)
    throw error(std::string(what) + ": images of different sizes (" + std::to_string(a.width) + "x" + std::to_string(a.height) + " and " +
                std::to_string(b.width) + "x" + std::to_string(b.height) + ")");
}

// The metrics promise finite numbers; an image made in memory could hold NaN (files cannot).
void require_finite(const float_image& image, const std::string& what) {
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    if (!std::isfinite(image.pixels[i].r) || !std::isfinite(image.pixels[i].g) || !std::isfinite(image.pixels[i].b))
      throw error(what + ": pixel (" + std::to_string(i % static_cast<std::size_t>(image.width)) + ", " +
                  std::to_string(i / static_cast<std::size_t>(image.width)) + ") is not finite");
}

// Two images of the same size with finite pixels (and the mask, if any).
void require_comparable(const float_image& image, const float_image& reference, const float_image* mask, const char* what) {
  require_same_size(image, reference, what);
  if (mask) require_same_size(*mask, reference, what);
  require_finite(image, std::string(what) + ": the image");
  require_finite(reference, std::string(what) + ": the reference");
  if (mask) require_finite(*mask, std::string(what) + ": the mask");
}

}  // namespace

float_image float_image_from_rgba(const std::vector<float>& rgba, int width, int height) {
  float_image image{width, height, std::vector<glm::vec3>(static_cast<std::size_t>(width) * static_cast<std::size_t>(height))};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t source = (static_cast<std::size_t>(height - 1 - y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 4;
      image.pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)] =
          glm::vec3(rgba[source], rgba[source + 1], rgba[source + 2]);
    }
  return image;
}

float_image float_image_from_buffer(const image_buffer& buffer) {
  float_image image{buffer.width, buffer.height, std::vector<glm::vec3>(buffer.texels.size())};
  for (int y = 0; y < buffer.height; ++y)
    for (int x = 0; x < buffer.width; ++x)
      image.pixels[static_cast<std::size_t>(buffer.height - 1 - y) * static_cast<std::size_t>(buffer.width) + static_cast<std::size_t>(x)] =
          glm::vec3(buffer.at(glm::ivec2(x, y)));
  return image;
}

std::vector<float> rgba_from_float_image(const float_image& image) {
  std::vector<float> rgba;
  rgba.reserve(image.pixels.size() * 4);
  for (int y = image.height - 1; y >= 0; --y)
    for (int x = 0; x < image.width; ++x) {
      const glm::vec3 p = image.at(x, y);
      rgba.insert(rgba.end(), {p.r, p.g, p.b, 1.0f});
    }
  return rgba;
}

std::vector<std::uint8_t> encode_pfm(const float_image& image) {
  std::ostringstream header;
  header << "PF\n" << image.width << " " << image.height << "\n-1.0\n";
  std::vector<std::uint8_t> bytes;
  const std::string text = header.str();
  bytes.reserve(text.size() + image.pixels.size() * 12);
  bytes.insert(bytes.end(), text.begin(), text.end());
  // PFM rows go bottom-up; -1.0 marks little-endian floats.
  for (int y = image.height - 1; y >= 0; --y)
    for (int x = 0; x < image.width; ++x) {
      const glm::vec3 p = image.at(x, y);
      const float values[3] = {p.r, p.g, p.b};
      const auto* raw = reinterpret_cast<const std::uint8_t*>(values);
      bytes.insert(bytes.end(), raw, raw + sizeof values);
    }
  return bytes;
}

void write_pfm(const fs::path& path, const float_image& image) { write_bytes_atomically(path, encode_pfm(image)); }

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

float_image decode_pfm(const std::string& bytes, const std::string& name, const image_read_limits& limits) {
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
  float_image image{header.width, header.height, std::vector<glm::vec3>(pixel_count)};
  const char* data = bytes.data() + header.data_offset;
  for (int y = header.height - 1; y >= 0; --y)
    for (int x = 0; x < header.width; ++x, data += 12) {
      float values[3];
      std::memcpy(values, data, sizeof values);
      for (const float value : values)
        if (!std::isfinite(value))
          throw error(name + ": pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") (from the top left) is " +
                      (std::isnan(value) ? "NaN" : "infinite") + "; vplkit compares finite images");
      image.pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(header.width) + static_cast<std::size_t>(x)] =
          glm::vec3(values[0], values[1], values[2]);
    }
  return image;
}

float_image decode_png(const std::string& bytes, const std::string& name, const image_read_limits& limits) {
  // stb_image picks its decoder from the content; only the PNG decoder may run.
  static constexpr unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (bytes.size() < sizeof signature || std::memcmp(bytes.data(), signature, sizeof signature) != 0)
    throw error(name + ": not a PNG file (no PNG signature)");
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) throw error(name + ": the PNG file is larger than 2 GiB");
  // The size from the IHDR chunk, which must come first, checked before stb allocates anything.
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  if (bytes.size() < 33 || std::memcmp(data + 12, "IHDR", 4) != 0) throw error(name + ": not a readable PNG (no IHDR chunk after the signature)");
  const auto big_endian = [&](std::size_t at) {
    return (std::uint32_t{data[at]} << 24) | (std::uint32_t{data[at + 1]} << 16) | (std::uint32_t{data[at + 2]} << 8) | std::uint32_t{data[at + 3]};
  };
  const std::uint32_t claimed_width = big_endian(16), claimed_height = big_endian(20);
  if (claimed_width == 0 || claimed_height == 0 || claimed_width > 0x7fffffffu || claimed_height > 0x7fffffffu)
    throw error(name + ": not a readable PNG (its header claims " + std::to_string(claimed_width) + "x" + std::to_string(claimed_height) + " pixels)");
  check_size(static_cast<int>(claimed_width), static_cast<int>(claimed_height), name, limits);
  const int length = static_cast<int>(bytes.size());
  int width = 0, height = 0, channels = 0;
  stbi_uc* decoded = stbi_load_from_memory(data, length, &width, &height, &channels, 3);
  if (!decoded) throw error(name + ": not a readable PNG (" + std::string(stbi_failure_reason()) + ")");
  if (static_cast<std::uint32_t>(width) != claimed_width || static_cast<std::uint32_t>(height) != claimed_height) {
    stbi_image_free(decoded);
    throw error(name + ": not a readable PNG (decoded " + std::to_string(width) + "x" + std::to_string(height) + ", the header says " +
                std::to_string(claimed_width) + "x" + std::to_string(claimed_height) + ")");
  }
  const std::unique_ptr<stbi_uc, void (*)(void*)> owned(decoded, stbi_image_free);
  float_image image{width, height, std::vector<glm::vec3>(static_cast<std::size_t>(width) * static_cast<std::size_t>(height))};
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    image.pixels[i] = glm::vec3(srgb_to_linear(decoded[3 * i] / 255.0f), srgb_to_linear(decoded[3 * i + 1] / 255.0f),
                                srgb_to_linear(decoded[3 * i + 2] / 255.0f));
  return image;
}

}  // namespace

float_image decode_image(const std::string& bytes, image_file_format format, const std::string& name, const image_read_limits& limits) {
  return format == image_file_format::pfm ? decode_pfm(bytes, name, limits) : decode_png(bytes, name, limits);
}

float_image read_image_file(const fs::path& path, const image_read_limits& limits) {
  const std::string extension = path.extension().string();
  if (extension != ".pfm" && extension != ".png") throw error(path.string() + ": unsupported image format '" + extension + "' (use .pfm or .png)");
  const image_file_format format = extension == ".pfm" ? image_file_format::pfm : image_file_format::png;
  // The largest file the limits allow: a PFM's exact size; a PNG is compressed, so at most that.
  const std::uintmax_t max_bytes = 64 + static_cast<std::uintmax_t>(limits.max_pixels) * 12;
  return decode_image(read_file(path, max_bytes, extension == ".pfm" ? "PFM image" : "PNG image"), format, path.string(), limits);
}

namespace {

// relative_error_of without the checks, for callers that made them.
relative_error relative_error_over(const float_image& image, const float_image& reference, const float_image* mask) {
  double squared = 0.0, sum_image = 0.0, sum_reference = 0.0;
  relative_error result;
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    if (mask && !(luminance_of(mask->pixels[i]) > 0.5f)) continue;
    for (int c = 0; c < 3; ++c) {
      const double a = image.pixels[i][c], b = reference.pixels[i][c];
      squared += (a - b) * (a - b);
      sum_image += a;
      sum_reference += b;
    }
    ++result.pixels;
  }
  if (result.pixels == 0 || !(sum_reference > 0.0)) return result;
  const double n = 3.0 * static_cast<double>(result.pixels), mean = sum_reference / n;
  result.rmse = std::sqrt(squared / n) / mean;
  result.bias = (sum_image - sum_reference) / sum_reference;
  return result;
}

}  // namespace

relative_error relative_error_of(const float_image& image, const float_image& reference, const float_image* mask) {
  require_comparable(image, reference, mask, "relative error");
  return relative_error_over(image, reference, mask);
}

image_metrics compare_images(const float_image& image, const float_image& reference, const float_image* mask) {
  require_comparable(image, reference, mask, "compare");
  image_metrics m;
  const std::size_t count = image.pixels.size();
  double squared = 0.0, relative = 0.0, peak = 0.0, leak_squared = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    const bool in_mask = mask && luminance_of(mask->pixels[i]) > 0.5f;
    for (int c = 0; c < 3; ++c) {
      const double a = image.pixels[i][c], b = reference.pixels[i][c], d = a - b;
      squared += d * d;
      relative += d * d / (b * b + 0.01);
      peak = std::max(peak, std::fabs(b));
      if (in_mask) leak_squared += d * d;
    }
    m.leak_pixels += in_mask;
  }
  const double mse = squared / (3.0 * static_cast<double>(count));
  m.rmse = std::sqrt(mse);
  m.relative_mse = relative / (3.0 * static_cast<double>(count));
  m.psnr = mse > 0.0 ? 10.0 * std::log10(std::max(peak, 1e-12) * std::max(peak, 1e-12) / mse) : std::numeric_limits<double>::infinity();
  if (mask) m.leak_rmse = m.leak_pixels > 0 ? std::sqrt(leak_squared / (3.0 * static_cast<double>(m.leak_pixels))) : 0.0;
  m.relative = relative_error_over(image, reference, nullptr);
  if (mask) m.masked = relative_error_over(image, reference, mask);

  // SSIM on luminance, Gaussian window 11 x 11, sigma 1.5 (Wang et al. 2004), clipped at borders.
  const int w = image.width, h = image.height, radius = 5;
  std::vector<double> la(count), lb(count);
  double l_max = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    la[i] = luminance_of(image.pixels[i]);
    lb[i] = luminance_of(reference.pixels[i]);
    l_max = std::max(l_max, lb[i]);
  }
  const double range = std::max(l_max, 1e-6), c1 = (0.01 * range) * (0.01 * range), c2 = (0.03 * range) * (0.03 * range);
  double ssim_sum = 0.0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double weight = 0.0, mean_a = 0.0, mean_b = 0.0;
      for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) {
          const int sx = x + dx, sy = y + dy;
          if (sx < 0 || sy < 0 || sx >= w || sy >= h) continue;
          const double g = std::exp(-(dx * dx + dy * dy) / (2.0 * 1.5 * 1.5));
          const std::size_t j = static_cast<std::size_t>(sy) * static_cast<std::size_t>(w) + static_cast<std::size_t>(sx);
          weight += g;
          mean_a += g * la[j];
          mean_b += g * lb[j];
        }
      mean_a /= weight;
      mean_b /= weight;
      double var_a = 0.0, var_b = 0.0, covariance = 0.0;
      for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) {
          const int sx = x + dx, sy = y + dy;
          if (sx < 0 || sy < 0 || sx >= w || sy >= h) continue;
          const double g = std::exp(-(dx * dx + dy * dy) / (2.0 * 1.5 * 1.5)) / weight;
          const std::size_t j = static_cast<std::size_t>(sy) * static_cast<std::size_t>(w) + static_cast<std::size_t>(sx);
          var_a += g * (la[j] - mean_a) * (la[j] - mean_a);
          var_b += g * (lb[j] - mean_b) * (lb[j] - mean_b);
          covariance += g * (la[j] - mean_a) * (lb[j] - mean_b);
        }
      ssim_sum += ((2 * mean_a * mean_b + c1) * (2 * covariance + c2)) / ((mean_a * mean_a + mean_b * mean_b + c1) * (var_a + var_b + c2));
    }
  m.ssim = ssim_sum / static_cast<double>(count);

  // Alg. 1 on the 8-bit sRGB encodings, RGB channels.
  std::vector<std::uint8_t> a8, b8;
  a8.reserve(count * 3);
  b8.reserve(count * 3);
  const auto encode = [](float value) {
    value = std::clamp(value, 0.0f, 1.0f);
    const float srgb = value <= 0.0031308f ? 12.92f * value : 1.055f * std::pow(value, 1.0f / 2.4f) - 0.055f;
    return static_cast<std::uint8_t>(std::lround(255.0f * srgb));
  };
  for (std::size_t i = 0; i < count; ++i)
    for (int c = 0; c < 3; ++c) {
      a8.push_back(encode(image.pixels[i][c]));
      b8.push_back(encode(reference.pixels[i][c]));
    }
  m.similarity = lightwave_similarity(a8.data(), b8.data(), a8.size());
  return m;
}

std::vector<std::uint8_t> false_colour_error(const float_image& image, const float_image& reference, float scale) {
  require_comparable(image, reference, nullptr, "error image");
  if (!std::isfinite(scale)) throw error("error image: the scale must be finite");
  std::vector<double> differences(image.pixels.size());
  double largest = 0.0;
  for (std::size_t i = 0; i < differences.size(); ++i) {
    differences[i] = std::fabs(luminance_of(image.pixels[i]) - luminance_of(reference.pixels[i]));
    largest = std::max(largest, differences[i]);
  }
  const double full_red = scale > 0.0f ? double{scale} : largest > 0.0 ? largest : 1.0;
  // Blue (0) -> cyan -> green -> yellow -> red (scale and above).
  const glm::vec3 ramp[5] = {{0, 0, 1}, {0, 1, 1}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}};
  std::vector<std::uint8_t> out(differences.size() * 4);
  for (std::size_t i = 0; i < differences.size(); ++i) {
    const float t = static_cast<float>(std::clamp(differences[i] / full_red, 0.0, 1.0)) * 4.0f;
    const int k = std::min(3, static_cast<int>(t));
    const glm::vec3 c = glm::mix(ramp[k], ramp[k + 1], t - static_cast<float>(k));
    out[4 * i] = static_cast<std::uint8_t>(std::lround(255.0f * c.r));
    out[4 * i + 1] = static_cast<std::uint8_t>(std::lround(255.0f * c.g));
    out[4 * i + 2] = static_cast<std::uint8_t>(std::lround(255.0f * c.b));
    out[4 * i + 3] = 255;
  }
  return out;
}

}  // namespace vplkit
