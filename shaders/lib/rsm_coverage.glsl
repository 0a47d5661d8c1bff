// GLSL twin of include/vplkit/rsm_coverage.hpp: the coarse pixel lights that light the receivers
// the RSM gather's pattern cannot reach (behind the light, off the map), and their irradiance.
// reduce_rsm_block is compiled when the including shader defines VPLKIT_RSM_COVERAGE_REDUCE: it
// reads the RSM through `rsm_texel rsm_fetch(ivec2 texel)`, which that shader then defines (the
// prototype is declared here, after lib/rsm_texel.glsl's struct; Mesa's linker wants every
// declared function that a compiled function calls defined, reached or not).
#ifndef VPLKIT_RSM_COVERAGE_GLSL
#define VPLKIT_RSM_COVERAGE_GLSL

#include "lib/irradiance.glsl"
#include "lib/rsm_texel.glsl"

#define VPLKIT_MAX_COVERAGE_BLOCKS 64

ivec2 coverage_interleave_phase(uvec2 pixel, int side) {
  uint s = uint(max(side, 1));
  return ivec2(int(pixel.x % s), int(pixel.y % s));
}

struct coarse_light {
  vec3 position;
  vec3 normal;
  vec3 flux;
  float extent;
};

struct coarse_light_sum {
  vec3 origin;
  vec3 position;
  vec3 normal;
  vec3 flux;
  float square;
  float weight;
  int count;
};

void coarse_light_add(inout coarse_light_sum sum, vec3 position, vec3 normal, vec3 flux) {
  if (sum.count == 0) sum.origin = position;
  float weight = flux.x + flux.y + flux.z;
  vec3 offset = position - sum.origin;
  sum.position += weight * offset;
  sum.normal += weight * normal;
  sum.flux += flux;
  sum.square += weight * dot(offset, offset);
  sum.weight += weight;
  sum.count += 1;
}

coarse_light coarse_light_from(coarse_light_sum sum) {
  coarse_light light = coarse_light(vec3(0.0), vec3(0.0), vec3(0.0), 0.0);
  if (!(sum.weight > 0.0)) return light;
  float inverse = 1.0 / sum.weight;
  vec3 mean_offset = sum.position * inverse;
  light.position = sum.origin + mean_offset;
  light.normal = sum.normal * inverse;
  light.flux = sum.flux;
  light.extent = max(0.0, sum.square * inverse - dot(mean_offset, mean_offset));
  return light;
}

ivec2 coverage_block_side(ivec2 rsm_size, int blocks) { return (rsm_size + blocks - 1) / blocks; }

#ifdef VPLKIT_RSM_COVERAGE_REDUCE
rsm_texel rsm_fetch(ivec2 texel);

coarse_light reduce_rsm_block(ivec2 block, int blocks, ivec2 rsm_size) {
  ivec2 side = coverage_block_side(rsm_size, blocks);
  ivec2 first = block * side, last = min(first + side, rsm_size);
  coarse_light_sum sum = coarse_light_sum(vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), 0.0, 0.0, 0);
  for (int y = first.y; y < last.y; ++y)
    for (int x = first.x; x < last.x; ++x) {
      rsm_texel texel = rsm_fetch(ivec2(x, y));
      if (texel.position.z < 0.0) coarse_light_add(sum, texel.position, texel.normal, texel.flux);
    }
  return coarse_light_from(sum);
}
#endif

vec3 coarse_light_irradiance(vec3 x, vec3 n, coarse_light light, irradiance_settings settings) {
  vec3 light_to_receiver = x - light.position;
  float min_distance = settings.min_distance;
  float distance_squared = max(dot(light_to_receiver, light_to_receiver), min_distance * min_distance);
  float spread_squared = distance_squared + 2.0 * light.extent;
  float emit = max(0.0, dot(light.normal, light_to_receiver));
  float receive = max(0.0, -dot(n, light_to_receiver));
  return light.flux * ((emit * receive) / (distance_squared * spread_squared));  // one division: see the C++ twin
}

vec2 coverage_block_centre(ivec2 block, ivec2 side) { return (vec2(block) + 0.5) * vec2(side); }

#endif
