#version 330 core
// Light Wave's flux energy: the indirect light of every receiver vertex, albedo / pi times the
// irradiance of every receiver VPL (lightwave_vertex_bounce, lib/lightwave.glsl), summed once per
// light. One fragment per receiver, receiver i at texel (i % width, i / width) of a full-screen
// triangle: a software rasteriser shades fragments on every core and its vertex stage on one (as
// a transform-feedback vertex stage the sum cost twice as much on two cores). The VPLs come from
// a uniform block, VPLKIT_LIGHTWAVE_PASS_VPLS at a time (by default a 64 KiB block's worth, 1365;
// read from a float texture instead, the boxes' sum took about 1.5x as long on llvmpipe): each
// pass continues the previous pass's sum (lightwave_bounce_sum: the same additions in the same
// order as one loop) and the last turns it into radiance. The pipeline copies the result into the
// buffer the main pass reads as attribute 3.
#ifndef VPLKIT_LIGHTWAVE_PASS_VPLS
#error "lightwave_capture.frag: define VPLKIT_LIGHTWAVE_PASS_VPLS, the VPLs of one pass (lightwave_pipeline sets it)"
#endif
#define VPLKIT_LIGHTWAVE_FETCH_FLUX 1
#include "lib/lightwave.glsl"

// The receivers, a texel each: where the vertex's light is evaluated (lightwave_receiver_samples),
// its normal and its albedo.
uniform sampler2D receiver_points;
uniform sampler2D receiver_normals;
uniform sampler2D receiver_albedos;
uniform int receiver_count;
// The previous passes' irradiance at each receiver (zero before the first).
uniform sampler2D partial_sum;
// This pass's VPLs, three rows each: [position | radius], [normal | -], [flux | -].
layout(std140) uniform lightwave_pass_vpls { vec4 pass_vpl_rows[3 * VPLKIT_LIGHTWAVE_PASS_VPLS]; };
uniform int pass_vpl_count;
uniform int last_pass;  // 1: write the radiance; 0: the irradiance so far
uniform irradiance_settings irradiance;

layout(location = 0) out vec4 indirect_out;

lightwave_flux_vpl lightwave_fetch_flux_vpl(int index) {
  vec4 position_radius = pass_vpl_rows[3 * index];
  return lightwave_flux_vpl(position_radius.xyz, pass_vpl_rows[3 * index + 1].xyz, pass_vpl_rows[3 * index + 2].xyz, position_radius.w);
}

void main() {
  ivec2 texel = ivec2(gl_FragCoord.xy);
  int width = textureSize(receiver_points, 0).x;
  // The texels past the last receiver sum nothing.
  int count = texel.y * width + texel.x < receiver_count ? pass_vpl_count : 0;
  vec3 sample_point = texelFetch(receiver_points, texel, 0).xyz;
  vec3 normal = normalize(texelFetch(receiver_normals, texel, 0).xyz);
  vec3 sum = lightwave_bounce_sum(sample_point, normal, count, texelFetch(partial_sum, texel, 0).xyz, irradiance.min_distance);
  if (last_pass != 0) sum = diffuse_radiance(texelFetch(receiver_albedos, texel, 0).xyz, vec3(0.0), 0.0, sum);
  indirect_out = vec4(sum, 1.0);
}
