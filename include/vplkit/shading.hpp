// The final composition of every technique: the radiance a Lambertian surface sends towards the
// camera from its direct and its one-bounce indirect irradiance,
//
//   L = albedo / pi * (E_direct * v + E_indirect),
//
// with v the direct light's visibility (the RSM pipeline's shadow density of Alg. 4, 1 where the
// direct irradiance is already shadowed or unshadowed by construction). The RSM post pass, the
// final-gathering shading pass, the Light Wave and cube-map direct terms, their CPU mirrors and
// the Monte Carlo reference all call it, so a technique and its reference compose alike.
// docs/architecture.md explains the mirror rule this header follows.
//
// GLSL twin: shaders/lib/shading.glsl.
#pragma once

#include <glm/glm.hpp>

namespace vplkit {

/// 1 / pi, written once for the C++ kernels (the GLSL twins spell the same literal).
template <typename T>
constexpr T inv_pi = T(0.318309886183790671538);

/// albedo / pi * (direct_irradiance * direct_visibility + indirect_irradiance).
template <typename T>
glm::vec<3, T> diffuse_radiance(const glm::vec<3, T>& albedo, const glm::vec<3, T>& direct_irradiance, T direct_visibility,
                                const glm::vec<3, T>& indirect_irradiance) {
  return albedo * inv_pi<T> * (direct_irradiance * direct_visibility + indirect_irradiance);
}

}  // namespace vplkit
