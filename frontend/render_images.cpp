#include "frontend/render_images.hpp"

#include <algorithm>
#include <cmath>

#include "frontend/error.hpp"

namespace vplkit {

float luminance(float r, float g, float b) { return 0.2126f * r + 0.7152f * g + 0.0722f * b; }

float percentile_exposure(const std::vector<float>& rgba) {
  std::vector<float> values;
  values.reserve(rgba.size() / 4);
  for (std::size_t i = 0; i + 3 < rgba.size(); i += 4) {
    const float value = luminance(rgba[i], rgba[i + 1], rgba[i + 2]);
    if (value > 0.0f && std::isfinite(value)) values.push_back(value);
  }
  if (values.empty()) return 1.0f;
  const std::size_t rank = (values.size() - 1) * 99 / 100;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(rank), values.end());
  return 0.8f / values[rank];
}

std::vector<float> luminance_difference(const std::vector<float>& without_visibility, const std::vector<float>& with_visibility,
                                        float scale) {
  if (without_visibility.size() != with_visibility.size()) throw error("luminance_difference: images of different sizes");
  std::vector<float> out(without_visibility.size(), 1.0f);
  for (std::size_t i = 0; i + 3 < out.size(); i += 4) {
    const float difference = std::fabs(luminance(without_visibility[i], without_visibility[i + 1], without_visibility[i + 2]) -
                                       luminance(with_visibility[i], with_visibility[i + 1], with_visibility[i + 2]));
    out[i] = out[i + 1] = out[i + 2] = difference * scale;
  }
  return out;
}

}  // namespace vplkit
