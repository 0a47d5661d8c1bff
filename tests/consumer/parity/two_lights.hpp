// The C++ twin of shaders/my/two_lights.glsl: the irradiance at a receiver (x, n) from two pixel
// lights (xa, na) and (xb, nb) of the same flux, with vplkit's Eq. 3.2.
#pragma once

#include <vplkit/irradiance.hpp>

template <typename T>
glm::vec<3, T> two_lights_irradiance(const glm::vec<3, T>& x, const glm::vec<3, T>& n, const glm::vec<3, T>& xa, const glm::vec<3, T>& na,
                                     const glm::vec<3, T>& xb, const glm::vec<3, T>& nb, const glm::vec<3, T>& flux,
                                     const vplkit::irradiance_settings<T>& settings) {
  const glm::vec<3, T> sum = vplkit::pixel_light_irradiance(x, n, xa, na, flux, settings) + vplkit::pixel_light_irradiance(x, n, xb, nb, flux, settings);
  return sum;
}
