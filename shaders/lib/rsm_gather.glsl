// GLSL twin of include/vplkit/rsm_gather.hpp: the RSM gather of [RSMV] (Alg. 1/5 with the
// visibility of Alg. 2, 3 or 6, or the original disk pattern), in the light's eye space.
// Before including, define
//   VPLKIT_RSM_PATTERN  0 radial, 1 disk
//   VPLKIT_VISIBILITY   0 none, 2 Alg. 2, 3 Alg. 3, 6 Alg. 6, 7 Alg. 6 about the receiver's light ray
//                       (rsm_visibility::alg6_ray), 8 the voxel grid of lib/voxel_visibility.glsl through
//                       `float rsm_voxel_visibility(vec3 x, vec3 n, vec3 xp, vec3 np)` and, with
//                       coverage, `float rsm_voxel_coarse_visibility(vec3 x, vec3 n, vec3 xc, vec3 nc)`
//                       for the coarse lights (light eye space; the C++ gather given
//                       vplkit/voxel_visibility.hpp's voxel_rsm_visibility); with coverage, every
//                       other value (and the disk pattern) weighs the coarse lights by `float
//                       rsm_depth_coarse_visibility(vec3 x, vec3 xc)` (a point light's
//                       lib/rsm_coarse_visibility.glsl, or 1; the C++ gather_rsm given a coarse
//                       visibility)
//   VPLKIT_SLOT_COUNT   (optional) settings.slots.count, as a constant: see lib/micro_linear_buffer.glsl
//   VPLKIT_RSM_COVERAGE (optional) 1: the coverage of vplkit/rsm_coverage.hpp, reading the coarse
//                       lights through `coarse_light rsm_coarse_fetch(ivec2 block)` (the C++
//                       gather given a coarse fetch); absent or 0: the pattern alone
// and the function `rsm_texel rsm_fetch(ivec2 texel)` (declare it after including this file's
// rsm_texel, e.g. with a prototype: the struct comes first, the fetch after).
#ifndef VPLKIT_RSM_GATHER_GLSL
#define VPLKIT_RSM_GATHER_GLSL

#include "lib/irradiance.glsl"
#include "lib/micro_linear_buffer.glsl"
#include "lib/rsm_coverage.glsl"
#include "lib/rsm_pattern.glsl"
#include "lib/rsm_texel.glsl"
#include "lib/transform.glsl"

#ifndef VPLKIT_RSM_PATTERN
#error "define VPLKIT_RSM_PATTERN (0 radial, 1 disk) before including lib/rsm_gather.glsl"
#endif
#ifndef VPLKIT_VISIBILITY
#error "define VPLKIT_VISIBILITY (0, 2, 3, 6, 7 or 8) before including lib/rsm_gather.glsl"
#endif
#if VPLKIT_RSM_PATTERN == 1 && VPLKIT_VISIBILITY != 0
#error "the disk pattern has no paths: visibility needs VPLKIT_RSM_PATTERN 0"
#endif

#ifndef VPLKIT_RSM_COVERAGE
#define VPLKIT_RSM_COVERAGE 0
#endif

rsm_texel rsm_fetch(ivec2 texel);
#if VPLKIT_VISIBILITY == 8
float rsm_voxel_visibility(vec3 x, vec3 n, vec3 xp, vec3 np);
int rsm_voxel_group();
#endif
#if VPLKIT_RSM_COVERAGE
coarse_light rsm_coarse_fetch(ivec2 block);
#if VPLKIT_VISIBILITY == 8
float rsm_voxel_coarse_visibility(vec3 x, vec3 n, vec3 xc, vec3 nc);
#else
float rsm_depth_coarse_visibility(vec3 x, vec3 xc);
#endif
#endif

struct rsm_gather_settings {
  irradiance_settings irradiance;
  radial_pattern_constants radial;
  disk_pattern_settings disk;
  elevation_slots slots;
  ivec2 rsm_size;
  int coverage_blocks;
  int coverage_interleave;
  int perspective;
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

// The C++ twin's towards_light (alg6_ray's `up`).
vec3 towards_light(gather_receiver receiver, rsm_gather_settings settings) {
  if (settings.perspective == 0) return vec3(0.0, 0.0, 1.0);
  return -receiver.position / sqrt(receiver.position.x * receiver.position.x + receiver.position.y * receiver.position.y +
                                   receiver.position.z * receiver.position.z);
}

// Consecutive samples of a path that share one visibility (rsm-voxel's voxel_march_settings::group):
// the sum of their weighted irradiances and the largest one's pixel light, the one the group is
// marched to. C++ twin: rsm_sample_group.
struct rsm_sample_group {
  vec3 sum;
  float best;
  vec3 position;
  vec3 normal;
};

// The C++ twin is rsm_sample_group's default value, rsm_sample_group<T>{}.
rsm_sample_group rsm_sample_group_empty() { return rsm_sample_group(vec3(0.0), 0.0, vec3(0.0), vec3(0.0)); }

// The C++ twin is rsm_sample_group::add.
void rsm_sample_group_add(inout rsm_sample_group group, vec3 weighted, rsm_texel light) {
  group.sum += weighted;
  float size = weighted.x + weighted.y + weighted.z;
  if (size > group.best) {
    group.best = size;
    group.position = light.position;
    group.normal = light.normal;
  }
}

// The C++ twin is the lambda `accumulate` inside gather_rsm (a function here: GLSL has no lambdas),
// with the visibility object's operator(); rsm-voxel adds the sample to its group instead (the
// march is the group's, in gather_rsm).
void rsm_gather_accumulate(gather_receiver receiver, pattern_sample s, rsm_gather_settings settings, vec3 up,
                           inout micro_linear_buffer linear_buffer, inout rsm_sample_group group, inout vec3 irradiance) {
  ivec2 texel = ivec2(floor(receiver.rsm_coordinate + s.offset));
  if (texel.x < 0 || texel.y < 0 || texel.x >= settings.rsm_size.x || texel.y >= settings.rsm_size.y) return;
  rsm_texel light = rsm_fetch(texel);
  if (!(light.position.z < 0.0)) return;
  float visibility = 1.0;
#if VPLKIT_VISIBILITY == 7
  if (alg6_ray_in_front(receiver.position, receiver.normal, light.position, settings.irradiance.min_distance))
    visibility = clamp(micro_linear_buffer_alg6_ray(linear_buffer, elevation_bucket_about(receiver.position, light.position, up, settings.slots),
                                                    receiver.position, light.position, light.normal),
                       0.0, 1.0);
#elif VPLKIT_VISIBILITY != 0
  int index = elevation_bucket(receiver.position, light.position, settings.slots);
#if VPLKIT_VISIBILITY == 2
  visibility = micro_linear_buffer_alg2(linear_buffer, index);
#elif VPLKIT_VISIBILITY == 3
  visibility = micro_linear_buffer_alg3(linear_buffer, index);
#elif VPLKIT_VISIBILITY == 6
  visibility = clamp(micro_linear_buffer_alg6(linear_buffer, index), 0.0, 1.0);
#endif
#endif
  vec3 e = pixel_light_irradiance(receiver.position, receiver.normal, light.position, light.normal, light.flux,
                                  settings.irradiance);
#if VPLKIT_VISIBILITY == 8
  rsm_sample_group_add(group, s.weight * e, light);
#else
  irradiance += (visibility * s.weight) * e;
#endif
}

vec3 gather_rsm(gather_receiver receiver, rsm_gather_settings settings) {
  vec3 irradiance = vec3(0.0);
  bool in_front = receiver.position.z < 0.0;
  float reach = settings.disk.max_radius;
  if (in_front) {
    micro_linear_buffer linear_buffer;
    rsm_sample_group group = rsm_sample_group_empty();
#if VPLKIT_VISIBILITY == 7
    vec3 up = towards_light(receiver, settings);
#else
    vec3 up = vec3(0.0, 0.0, 1.0);
#endif
    vec2 size = vec2(settings.rsm_size);
    vec2 outside = max(max(-receiver.rsm_coordinate, receiver.rsm_coordinate - size), vec2(0.0));
    float outside_squared = dot(outside, outside);
#if VPLKIT_RSM_PATTERN == 0
    radial_pixel pixel = radial_pattern_pixel(receiver.pixel, settings.radial);
    reach = pixel.scale * settings.radial.max_radius;
    if (outside_squared <= (reach + 1.0) * (reach + 1.0)) {
#if VPLKIT_VISIBILITY == 8
      int group_size = max(rsm_voxel_group(), 1);
#endif
      for (int path = 0; path < settings.radial.paths; ++path) {
        micro_linear_buffer_reset(linear_buffer, settings.slots.count);
        float ring_inner_radius = settings.radial.min_radius;
        for (int sample_index = 0; sample_index < settings.radial.samples_per_path; ++sample_index) {
          rsm_gather_accumulate(receiver, radial_pattern_sample(path, sample_index, ring_inner_radius, pixel, settings.radial),
                                settings, up, linear_buffer, group, irradiance);
          ring_inner_radius *= settings.radial.ring_ratio;
#if VPLKIT_VISIBILITY == 8
          // The group's one march, to its largest member (see the C++ twin).
          if ((sample_index + 1) % group_size == 0 || sample_index + 1 == settings.radial.samples_per_path) {
            if (group.best > 0.0) irradiance += rsm_voxel_visibility(receiver.position, receiver.normal, group.position, group.normal) * group.sum;
            group = rsm_sample_group_empty();
          }
#endif
        }
      }
    }
#else
    if (outside_squared <= (reach + 1.0) * (reach + 1.0)) {
      micro_linear_buffer_reset(linear_buffer, settings.slots.count);  // unused without paths, but defined
      vec2 shift = rsm_disk_pixel_shift(receiver.pixel, settings.disk);
      for (int sample_index = 0; sample_index < settings.disk.samples; ++sample_index)
        rsm_gather_accumulate(receiver, rsm_disk_sample(sample_index, shift, settings.disk), settings, up, linear_buffer, group, irradiance);
    }
#endif
    if (!(outside_squared > 0.0)) return irradiance * 0.318309886183790671538;  // on the map: the pattern alone
  }
#if VPLKIT_RSM_COVERAGE
  // Behind the light every block; off the map the blocks beyond the pattern's reach; of those, the
  // receiver's lattice of the interleave, weighted by its size (see the C++ twin).
  int blocks = settings.coverage_blocks;
  ivec2 side = coverage_block_side(settings.rsm_size, max(blocks, 1));
  int stride = max(settings.coverage_interleave, 1);
  ivec2 phase = coverage_interleave_phase(receiver.pixel, stride);
  vec3 coverage = vec3(0.0);
  for (int y = phase.y; y < blocks; y += stride)
    for (int x = phase.x; x < blocks; x += stride) {
      if (in_front) {  // behind the light every block counts (see the C++ twin)
        vec2 offset = coverage_block_centre(ivec2(x, y), side) - receiver.rsm_coordinate;
        if (!(dot(offset, offset) > reach * reach)) continue;
      }
      coarse_light light = rsm_coarse_fetch(ivec2(x, y));
#if VPLKIT_VISIBILITY == 8
      // A coarse light that lights nothing here is not judged (see the C++ twin).
      vec3 e = coarse_light_irradiance(receiver.position, receiver.normal, light, settings.irradiance);
      if (e.x + e.y + e.z > 0.0) coverage += rsm_voxel_coarse_visibility(receiver.position, receiver.normal, light.position, light.normal) * e;
#else
      vec3 e = coarse_light_irradiance(receiver.position, receiver.normal, light, settings.irradiance);
      if (e.x + e.y + e.z > 0.0) coverage += rsm_depth_coarse_visibility(receiver.position, light.position) * e;
#endif
    }
  irradiance += coverage * float(stride * stride);
#endif
  return irradiance * 0.318309886183790671538;
}

#endif
