#include "frontend/image/image.hpp"

#include <algorithm>

#include "frontend/core/error.hpp"

namespace vplkit {

float linear_to_srgb(float value) {
  if (!(value > 0.0f)) return 0.0f;  // negative, zero and NaN
  value = std::min(value, 1.0f);
  return value <= 0.0031308f ? 12.92f * value : 1.055f * std::pow(value, 1.0f / 2.4f) - 0.055f;
}

float srgb_to_linear(float value) { return value <= 0.04045f ? value / 12.92f : std::pow((value + 0.055f) / 1.055f, 2.4f); }

std::uint8_t linear_to_srgb8(float value) { return static_cast<std::uint8_t>(std::lround(255.0f * linear_to_srgb(value))); }

std::vector<std::uint8_t> to_srgb8(const image& linear, float exposure) {
  std::vector<std::uint8_t> out(linear.texels.size() * 4);
  for (int y = 0; y < linear.height; ++y)
    for (int x = 0; x < linear.width; ++x) {
      const glm::vec4& texel = linear.at(x, y);
      std::uint8_t* target = &out[linear.index(x, linear.height - 1 - y) * 4];
      for (int c = 0; c < 3; ++c) target[c] = linear_to_srgb8(exposure * texel[c]);
      target[3] = 255;
    }
  return out;
}

float percentile_exposure(const image& linear) {
  std::vector<float> values;
  values.reserve(linear.texels.size());
  for (const glm::vec4& texel : linear.texels) {
    const float value = luminance(glm::vec3(texel));
    if (value > 0.0f && std::isfinite(value)) values.push_back(value);
  }
  if (values.empty()) return 1.0f;
  const std::size_t rank = (values.size() - 1) * 99 / 100;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(rank), values.end());
  return 0.8f / values[rank];
}

image luminance_difference(const image& a, const image& b, float scale) {
  require_same_size(a, b, "luminance difference");
  image out(a.width, a.height, glm::vec4(1.0f));
  for (std::size_t i = 0; i < out.texels.size(); ++i) {
    const float difference = std::fabs(luminance(glm::vec3(a.texels[i])) - luminance(glm::vec3(b.texels[i])));
    out.texels[i] = glm::vec4(glm::vec3(difference * scale), 1.0f);
  }
  return out;
}

image red_as_grey(const image& source) {
  image out(source.width, source.height);
  for (std::size_t i = 0; i < out.texels.size(); ++i) out.texels[i] = glm::vec4(glm::vec3(source.texels[i].r), 1.0f);
  return out;
}

void require_same_size(const image& a, const image& b, const std::string& what) {
  if (!a.same_size(b))
    throw error(what + ": images of different sizes (" + std::to_string(a.width) + "x" + std::to_string(a.height) + " and " + std::to_string(b.width) +
                "x" + std::to_string(b.height) + ")");
}

}  // namespace vplkit
