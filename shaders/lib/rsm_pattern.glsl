// GLSL twin of include/vplkit/rsm_pattern.hpp: the radial pattern of [RSMV] and the original
// RSM disk pattern, bit-identical offsets (hash.glsl, polynomial_math.glsl).
#ifndef VPLKIT_RSM_PATTERN_GLSL
#define VPLKIT_RSM_PATTERN_GLSL

#include "lib/hash.glsl"
#include "lib/polynomial_math.glsl"

struct pattern_sample {
  vec2 offset;
  float weight;
};

struct radial_pattern_constants {
  int paths;
  int samples_per_path;
  float min_radius;
  float ring_ratio;
  float path_turns;
  float path_angle;
  float rotation_jitter;
  float angle_jitter;
  float scale_jitter;
  uint seed;
  float max_radius;
};

struct radial_pixel {
  uint hash;
  float rotation;
  float scale;
};

uint pattern_pixel_hash(uint seed, uvec2 pixel) { return hash_combine(hash_combine(seed, pixel.x), pixel.y); }

radial_pixel radial_pattern_pixel(uvec2 pixel, radial_pattern_constants constants) {
  uint pixel_hash = pattern_pixel_hash(constants.seed, pixel);
  float rotation = constants.rotation_jitter * uniform_float_from_bits(hash_combine(pixel_hash, 0u));
  float scale = 1.0 + constants.scale_jitter * (uniform_float_from_bits(hash_combine(pixel_hash, 1u)) - 0.5);
  return radial_pixel(pixel_hash, rotation, scale);
}

pattern_sample radial_pattern_sample(int path, int sample_index, float ring_inner_radius, radial_pixel pixel,
                                     radial_pattern_constants constants) {
  uint sample_hash = hash_combine(pixel.hash, uint(2 + path * constants.samples_per_path + sample_index));
  float angle_offset = constants.angle_jitter * (uniform_float_from_bits(sample_hash) - 0.5);
  float radial_position = uniform_float_from_bits(hash_uint32(sample_hash));
  float ring_width = pixel.scale * (ring_inner_radius * constants.ring_ratio - ring_inner_radius);
  float radius = pixel.scale * ring_inner_radius + radial_position * ring_width;
  vec2 direction = direction_from_turns(constants.path_turns * (float(path) + pixel.rotation + angle_offset));
  return pattern_sample(direction * radius, constants.path_angle * radius * ring_width);
}

pattern_sample radial_pattern_sample(int path, int sample_index, uvec2 pixel, radial_pattern_constants constants) {
  float inner = constants.min_radius;
  for (int ring = 0; ring < sample_index; ++ring) inner *= constants.ring_ratio;
  return radial_pattern_sample(path, sample_index, inner, radial_pattern_pixel(pixel, constants), constants);
}

struct disk_pattern_settings {
  int samples;
  float max_radius;
  uint seed;
  bool printed_weights;
  bool per_pixel_shift;
};

vec2 rsm_disk_pixel_shift(uvec2 pixel, disk_pattern_settings settings) {
  if (!settings.per_pixel_shift) return vec2(0.0);
  uint pixel_hash = pattern_pixel_hash(settings.seed ^ 0x27d4eb2fu, pixel);  // salted: see the C++ twin
  return vec2(uniform_float_from_bits(hash_combine(pixel_hash, 0u)), uniform_float_from_bits(hash_combine(pixel_hash, 1u)));
}

pattern_sample rsm_disk_sample(int sample_index, vec2 shift, disk_pattern_settings settings) {
  uint sample_hash = hash_combine(settings.seed ^ 0x5bd1e995u, uint(sample_index));
  float xi1 = fract(uniform_float_from_bits(sample_hash) + shift.x);
  float xi2 = fract(uniform_float_from_bits(hash_uint32(sample_hash)) + shift.y);
  vec2 direction = direction_from_turns(xi2);
  float radius = settings.max_radius * xi1;
  vec2 offset = vec2(direction.y, direction.x) * radius;
  if (settings.printed_weights) {
    float normalisation = 3.0 * 3.14159265358979323846 * settings.max_radius * settings.max_radius / float(settings.samples);
    return pattern_sample(offset, xi1 * xi1 * normalisation);
  }
  float normalisation = 2.0 * 3.14159265358979323846 * settings.max_radius * settings.max_radius / float(settings.samples);
  return pattern_sample(offset, xi1 * normalisation);
}

#endif
