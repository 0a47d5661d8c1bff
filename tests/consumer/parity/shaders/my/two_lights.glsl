// A user's GLSL function built on a vplkit twin: the irradiance at a receiver from two pixel lights
// of the same flux, the sum of two terms of Eq. 3.2 (lib/irradiance.glsl, found among vplkit's
// installed shaders). C++ twin: two_lights.hpp, the same operations in the same order.
// Needs #version 330 core (lib/irradiance.glsl does) and no defines.
#include "lib/irradiance.glsl"

vec3 two_lights_irradiance(vec3 x, vec3 n, vec3 xa, vec3 na, vec3 xb, vec3 nb, vec3 flux, irradiance_settings settings) {
  vec3 sum = pixel_light_irradiance(x, n, xa, na, flux, settings) + pixel_light_irradiance(x, n, xb, nb, flux, settings);
  return sum;
}
