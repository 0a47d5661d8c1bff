#include "frontend/image_metrics.hpp"

#include <stb/stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include <vplkit/lightwave.hpp>

#include "frontend/error.hpp"
#include "frontend/render_target.hpp"
#include "frontend/image_io.hpp"

namespace vplkit {
namespace fs = std::filesystem;

namespace {

float luminance_of(const glm::vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

float srgb_to_linear(float value) {
  return value <= 0.04045f ? value / 12.92f : std::pow((value + 0.055f) / 1.055f, 2.4f);
}

void require_same_size(const float_image& a, const float_image& b, const char* what) {
  if (a.width != b.width || a.height != b.height)
    throw error(std::string(what) + ": images of different sizes (" + std::to_string(a.width) + "x" + std::to_string(a.height) + " and " +
                std::to_string(b.width) + "x" + std::to_string(b.height) + ")");
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

void write_pfm(const fs::path& path, const float_image& image) {
  std::ostringstream header;
  header << "PF\n" << image.width << " " << image.height << "\n-1.0\n";
  std::vector<std::uint8_t> bytes;
  const std::string text = header.str();
  bytes.insert(bytes.end(), text.begin(), text.end());
  // PFM rows go bottom-up; -1.0 marks little-endian floats.
  for (int y = image.height - 1; y >= 0; --y)
    for (int x = 0; x < image.width; ++x) {
      const glm::vec3 p = image.at(x, y);
      const float values[3] = {p.r, p.g, p.b};
      const auto* raw = reinterpret_cast<const std::uint8_t*>(values);
      bytes.insert(bytes.end(), raw, raw + sizeof values);
    }
  write_bytes_atomically(path, bytes);
}

float_image read_image_file(const fs::path& path) {
  std::error_code ignored;
  if (!fs::exists(path, ignored)) throw error(path.string() + ": no such file");
  const std::string extension = path.extension().string();
  if (extension == ".pfm") {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw error(path.string() + ": cannot read it");
    std::string magic;
    int width = 0, height = 0;
    double scale = 0.0;
    in >> magic >> width >> height >> scale;
    in.get();
    if (!in || magic != "PF") throw error(path.string() + ": not an RGB PFM file (expected the header 'PF width height scale')");
    if (width < 1 || height < 1 || width > 65536 || height > 65536) throw error(path.string() + ": PFM size out of range");
    if (scale >= 0.0) throw error(path.string() + ": big-endian PFM files are not supported");
    float_image image{width, height, std::vector<glm::vec3>(static_cast<std::size_t>(width) * static_cast<std::size_t>(height))};
    for (int y = height - 1; y >= 0; --y)
      for (int x = 0; x < width; ++x) {
        float values[3];
        in.read(reinterpret_cast<char*>(values), sizeof values);
        image.pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)] = glm::vec3(values[0], values[1], values[2]);
      }
    if (!in) throw error(path.string() + ": the PFM file ends before its " + std::to_string(width) + "x" + std::to_string(height) + " pixels");
    return image;
  }
  if (extension == ".png") {
    int width = 0, height = 0, channels = 0;
    unsigned char* data = stbi_load(path.string().c_str(), &width, &height, &channels, 3);
    if (!data) throw error(path.string() + ": not a readable PNG (" + std::string(stbi_failure_reason()) + ")");
    float_image image{width, height, std::vector<glm::vec3>(static_cast<std::size_t>(width) * static_cast<std::size_t>(height))};
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
      image.pixels[i] = glm::vec3(srgb_to_linear(data[3 * i] / 255.0f), srgb_to_linear(data[3 * i + 1] / 255.0f), srgb_to_linear(data[3 * i + 2] / 255.0f));
    stbi_image_free(data);
    return image;
  }
  throw error(path.string() + ": unsupported image format '" + extension + "' (use .pfm or .png)");
}

relative_error relative_error_of(const float_image& image, const float_image& reference, const float_image* mask) {
  require_same_size(image, reference, "relative error");
  if (mask) require_same_size(*mask, reference, "relative error (mask)");
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

image_metrics compare_images(const float_image& image, const float_image& reference, const float_image* mask) {
  require_same_size(image, reference, "compare");
  if (mask) require_same_size(*mask, reference, "compare (mask)");
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
  m.relative = relative_error_of(image, reference);
  if (mask) m.masked = relative_error_of(image, reference, mask);

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
  require_same_size(image, reference, "error image");
  std::vector<float> differences(image.pixels.size());
  float largest = 0.0f;
  for (std::size_t i = 0; i < differences.size(); ++i) {
    differences[i] = std::fabs(luminance_of(image.pixels[i]) - luminance_of(reference.pixels[i]));
    largest = std::max(largest, differences[i]);
  }
  if (!(scale > 0.0f)) scale = largest > 0.0f ? largest : 1.0f;
  // Blue (0) -> cyan -> green -> yellow -> red (scale and above).
  const glm::vec3 ramp[5] = {{0, 0, 1}, {0, 1, 1}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}};
  std::vector<std::uint8_t> out(differences.size() * 4);
  for (std::size_t i = 0; i < differences.size(); ++i) {
    const float t = std::clamp(differences[i] / scale, 0.0f, 1.0f) * 4.0f;
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
