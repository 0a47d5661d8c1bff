#version 330 core
// Pass 1b, the coverage's coarse lights (include/vplkit/rsm_coverage.hpp): one fragment per block
// of the packed RSM, C x C in all, each the flux-weighted reduction of its texels
// (reduce_rsm_block). Writes [position | extent], [normal | 0], [flux | 0], light eye space. The
// gather (gather.frag with VPLKIT_RSM_COVERAGE) reads them for the receivers the pattern cannot
// reach.
#define VPLKIT_RSM_COVERAGE_REDUCE
#include "lib/rsm_coverage.glsl"
#include "lib/rsm_packing.glsl"

uniform rsm_unprojection unprojection;
uniform ivec2 rsm_size;
uniform int coverage_blocks;
uniform usampler2D rsm_packed;

layout(location = 0) out vec4 position_extent;
layout(location = 1) out vec4 normal_out;
layout(location = 2) out vec4 flux_out;

rsm_texel rsm_fetch(ivec2 texel) { return unpack_rsm_texel(texelFetch(rsm_packed, texel, 0), texel, unprojection); }

void main() {
  coarse_light light = reduce_rsm_block(ivec2(gl_FragCoord.xy), coverage_blocks, rsm_size);
  position_extent = vec4(light.position, light.extent);
  normal_out = vec4(light.normal, 0.0);
  flux_out = vec4(light.flux, 0.0);
}
