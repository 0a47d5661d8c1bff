// The small distance cube map of final gathering ([FG], section 4) from the full-size one: texel
// (i, j) of face `face` at resolution M is the mean of the block of (S / M)^2 texels of the S x S
// face under it, radiance and distance alike, each texel weighted by its solid angle.
//
// Why weighted: the small texel is one area light standing for the block's texels, which the
// paper calls "larger lights having the average radiance of the small lights" without saying how
// the average is taken. A face's texels are not equal lights: a texel's solid angle is
// (2 / S)^2 (1 + u^2 + v^2)^(-3/2), so one at a face's corner covers 0.19 of one at its centre,
// and within the corner block of M = 4 they differ by a factor of 2.8. The plain mean counts the
// texels towards the cube's corners too much, so that the small map's radiance integral
// sum L_i Omega_i is not the full map's: measured on the fg rooms' cube maps (face 256), the
// plain mean moved the polygon gather's irradiance near the reference point by -5 % to +5 % of
// the full map's (the residual bias docs/scenes.md had put down to M = 4), the weighted one by
// -0.8 % to +0.8 % (docs/errata.md, FG-3). With the weights, sum_i L_i Omega_i equals the full map's
// sum_p L_p Omega_p (Omega_i the sum of its texels' Omega_p), whatever the radiance.
//
// The weight is direct_light.hpp's perspective_texel_solid_angle of the face's 90-degree view,
// at the texel's centre (the midpoint rule: the weights of the six faces sum to 4 pi within 4e-6
// relative at S = 256, 1.5e-2 at S = 4).
// The distance is averaged with the same weights: the quad's distance is the mean over the solid
// angle it stands for.
//
// Faces lie side by side as in final_gather.hpp: the callable fetch(face, i, j) returns the full
// map's [radiance | distance] of its texel (i, j). GLSL twin: shaders/lib/final_gather_downsample.glsl
// (the including shader provides `vec4 full_cube_fetch(int face, int i, int j)`).
#pragma once

#include <glm/glm.hpp>

#include <vplkit/direct_light.hpp>

namespace vplkit {

/// The solid-angle weight of texel (i, j) of an S x S cube face (S = face_size).
template <typename T>
T cube_face_texel_solid_angle(int i, int j, int face_size) {
  const glm::vec<2, T> ndc(T(2 * i + 1) / T(face_size) - T(1), T(2 * j + 1) / T(face_size) - T(1));
  return perspective_texel_solid_angle(ndc, T(1), glm::ivec2(face_size));
}

/// Texel (i, j) of face `face` of the M x M map (M = resolution, dividing face_size): the
/// solid-angle-weighted mean of [radiance | distance] over its block. See the top comment.
template <typename T, typename Fetch>
glm::vec<4, T> cube_downsample_texel(int face, int i, int j, int face_size, int resolution, Fetch&& fetch) {
  const int block = face_size / resolution;
  glm::vec<4, T> sum(T(0));
  T weight_sum = T(0);
  for (int y = j * block; y < (j + 1) * block; ++y) {
    for (int x = i * block; x < (i + 1) * block; ++x) {
      const T weight = cube_face_texel_solid_angle<T>(x, y, face_size);
      sum += glm::vec<4, T>(fetch(face, x, y)) * weight;
      weight_sum += weight;
    }
  }
  return sum / weight_sum;
}

}  // namespace vplkit
