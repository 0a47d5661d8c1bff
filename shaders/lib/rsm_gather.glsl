// GLSL twin of include/vplkit/rsm_gather.hpp: the RSM gather of [RSMV] (Alg. 1/5 with the
// visibility of Alg. 2, 3 or 6, or the original disk pattern), in the light's eye space.
// Before including, define
//   VPLKIT_RSM_PATTERN  0 radial, 1 disk
//   VPLKIT_VISIBILITY   0 none, 2 Alg. 2, 3 Alg. 3, 6 Alg. 6
//   VPLKIT_SLOT_COUNT   (optional) settings.slots.count, as a constant: see lib/micro_linear_buffer.glsl
// and the function `rsm_texel rsm_fetch(ivec2 texel)` (declare it after including this file's
// rsm_texel, e.g. with a prototype: the struct comes first, the fetch after).
#ifndef VPLKIT_RSM_GATHER_GLSL
#define VPLKIT_RSM_GATHER_GLSL

#include "lib/irradiance.glsl"
#include "lib/micro_linear_buffer.glsl"
#include "lib/rsm_pattern.glsl"
#include "lib/rsm_texel.glsl"
#include "lib/transform.glsl"

#ifndef VPLKIT_RSM_PATTERN
#error "define VPLKIT_RSM_PATTERN (0 radial, 1 disk) before including lib/rsm_gather.glsl"
#endif
#ifndef VPLKIT_VISIBILITY
#error "define VPLKIT_VISIBILITY (0, 2, 3 or 6) before including lib/rsm_gather.glsl"
#endif
#if VPLKIT_RSM_PATTERN == 1 && VPLKIT_VISIBILITY != 0
#error "the disk pattern has no paths: visibility needs VPLKIT_RSM_PATTERN 0"
#endif

rsm_texel rsm_fetch(ivec2 texel);

struct rsm_gather_settings {
  irradiance_settings irradiance;
  radial_pattern_constants radial;
  disk_pattern_settings disk;
  elevation_slots slots;
  ivec2 rsm_size;
};

struct gather_receiver {
  vec3 position;
  vec3 normal;
  vec2 rsm_coordinate;
  uvec2 pixel;
};

gather_receiver make_gather_receiver(vec3 world_position, vec3 world_normal, mat4 light_view, mat4 light_view_projection,
                                     ivec2 rsm_size, uvec2 pixel) {
  return gather_receiver(transform_point(light_view, world_position), transform_direction(light_view, world_normal),
                         map_coordinate(light_view_projection, world_position, rsm_size), pixel);
}

// The C++ twin is the lambda `accumulate` inside gather_rsm (a function here: GLSL has no lambdas).
void rsm_gather_accumulate(gather_receiver receiver, pattern_sample s, rsm_gather_settings settings,
                           inout micro_linear_buffer buffer, inout vec3 irradiance) {
  ivec2 texel = ivec2(floor(receiver.rsm_coordinate + s.offset));
  if (texel.x < 0 || texel.y < 0 || texel.x >= settings.rsm_size.x || texel.y >= settings.rsm_size.y) return;
  rsm_texel light = rsm_fetch(texel);
  if (!(light.position.z < 0.0)) return;
  float visibility = 1.0;
#if VPLKIT_VISIBILITY != 0
  int index = elevation_bucket(receiver.position, light.position, settings.slots);
#if VPLKIT_VISIBILITY == 2
  visibility = micro_linear_buffer_alg2(buffer, index);
#elif VPLKIT_VISIBILITY == 3
  visibility = micro_linear_buffer_alg3(buffer, index);
#elif VPLKIT_VISIBILITY == 6
  visibility = clamp(micro_linear_buffer_alg6(buffer, index), 0.0, 1.0);
#endif
#endif
  vec3 e = pixel_light_irradiance(receiver.position, receiver.normal, light.position, light.normal, light.flux,
                                  settings.irradiance);
  irradiance += (visibility * s.weight) * e;
}

vec3 gather_rsm(gather_receiver receiver, rsm_gather_settings settings) {
  vec3 irradiance = vec3(0.0);
  if (!(receiver.position.z < 0.0)) return irradiance;  // behind the light: see the C++ twin
  micro_linear_buffer buffer;
#if VPLKIT_RSM_PATTERN == 0
  radial_pixel pixel = radial_pattern_pixel(receiver.pixel, settings.radial);
  for (int path = 0; path < settings.radial.paths; ++path) {
    micro_linear_buffer_reset(buffer, settings.slots.count);
    float ring_inner_radius = settings.radial.min_radius;
    for (int sample = 0; sample < settings.radial.samples_per_path; ++sample) {
      rsm_gather_accumulate(receiver, radial_pattern_sample(path, sample, ring_inner_radius, pixel, settings.radial),
                            settings, buffer, irradiance);
      ring_inner_radius *= settings.radial.ring_ratio;
    }
  }
#else
  micro_linear_buffer_reset(buffer, settings.slots.count);  // unused without paths, but defined
  for (int sample = 0; sample < settings.disk.samples; ++sample)
    rsm_gather_accumulate(receiver, rsm_disk_sample(sample, settings.disk), settings, buffer, irradiance);
#endif
  return irradiance * 0.318309886183790671538;
}

#endif
