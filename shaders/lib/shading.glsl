// GLSL twin of include/vplkit/shading.hpp: the final composition of every technique,
// L = albedo / pi * (E_direct * v + E_indirect). Same arithmetic in the same order.
#ifndef VPLKIT_SHADING_GLSL
#define VPLKIT_SHADING_GLSL

vec3 diffuse_radiance(vec3 albedo, vec3 direct_irradiance, float direct_visibility, vec3 indirect_irradiance) {
  return albedo * 0.318309886183790671538 * (direct_irradiance * direct_visibility + indirect_irradiance);
}

#endif
