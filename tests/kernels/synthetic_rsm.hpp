// A synthetic reflective shadow map for the kernel tests of the RSM gather and the shadow
// density: an orthographic light looking straight down at a lit floor, optionally with a block
// standing on it.
#pragma once

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/rsm_gather.hpp>

namespace vplkit::testing {

constexpr int rsm_size = 256;
constexpr double texel = 0.02;   // world units per RSM texel: the RSM covers 5.12 x 5.12
constexpr double light_height = 10.0;

// An orthographic light looking straight down (-y) at the origin; eye space x = world x,
// eye y = -world z, eye z = world y - light_height.
inline glm::dmat4 light_view() { return glm::lookAt(glm::dvec3(0, light_height, 0), glm::dvec3(0), glm::dvec3(0, 0, -1)); }
inline glm::dmat4 light_view_projection() {
  const double half = 0.5 * rsm_size * texel;
  return glm::ortho(-half, half, -half, half, 0.1, 20.0) * light_view();
}

// A pixel light given in the world, in the light's eye space where the gather works.
inline rsm_texel<double> light_space_texel(const glm::dvec3& world_position, const glm::dvec3& world_normal, const glm::dvec3& flux) {
  return {transform_point(light_view(), world_position), transform_direction(light_view(), world_normal), flux};
}

// A synthetic RSM: a floor at y = 0 (normal up) with flux 1 per texel, and optionally a block
// [x0, x1] x [0, height] x all z standing on it, seen from above as its top face. Eye x is
// world x, so tests may read a texel's x as the world's.
struct synthetic_rsm {
  double block_x0 = 1e9, block_x1 = 1e9, block_height = 0.0;
  bool in_block(double x) const { return x >= block_x0 && x <= block_x1; }
  glm::dvec3 world_of(glm::ivec2 t) const {
    return {(t.x + 0.5 - rsm_size / 2) * texel, 0.0, -(t.y + 0.5 - rsm_size / 2) * texel};
  }
  rsm_texel<double> operator()(glm::ivec2 t) const {
    glm::dvec3 p = world_of(t);
    if (in_block(p.x)) p.y = block_height;
    return light_space_texel(p, glm::dvec3(0, 1, 0), glm::dvec3(1.0));
  }
};

inline rsm_gather_settings<double> gather_settings() {
  rsm_gather_settings<double> settings;
  radial_pattern_settings<double> radial;
  radial.paths = 32;
  radial.samples_per_path = 16;
  radial.max_radius = 120.0;
  settings.radial = make_radial_pattern_constants(radial);
  settings.rsm_size = glm::ivec2(rsm_size);
  return settings;
}

// A receiver at a world position, by default facing down (the underside of a table).
inline gather_receiver<double> receiver_at(glm::dvec3 position, glm::uvec2 pixel, glm::dvec3 normal = glm::dvec3(0, -1, 0)) {
  return make_gather_receiver(position, normal, light_view(), light_view_projection(), glm::ivec2(rsm_size), pixel);
}

template <rsm_visibility V>
inline glm::dvec3 gather(const synthetic_rsm& rsm, const gather_receiver<double>& receiver) {
  return gather_rsm<rsm_pattern::radial, V>(receiver, rsm, gather_settings());
}


}  // namespace vplkit::testing
