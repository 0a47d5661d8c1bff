#version 330 core
// Light Wave's flux energy: the indirect light of every receiver vertex, albedo / pi times the
// irradiance of every receiver VPL (lightwave_bounce_sums, lib/lightwave.glsl), summed once per
// light. Four receivers per fragment (VPLKIT_LIGHTWAVE_SUM_RECEIVERS): a software rasteriser reads
// the uniform block per fragment lane, and four receivers sharing each VPL's read cost the boxes'
// sum about half as much as one each (llvmpipe, 2 cores). Receiver r is number t = r % cells of band k = r / cells
// (cells = the grid's width x rows): it is read at texel (t % width, k x rows + t / width) of the
// receiver textures, its sum written to attachment k at texel (t % width, t / width). A software
// rasteriser shades fragments on every core and its vertex stage on one (as a transform-feedback
// vertex stage the sum cost twice as much on two cores). The VPLs come from a uniform block,
// VPLKIT_LIGHTWAVE_PASS_VPLS at a time (by default a 64 KiB block's worth, 1365; read from a
// float texture instead, the boxes' sum took about 1.5x as long on llvmpipe): each pass continues
// the previous pass's sums (the same additions in the same order as one loop) and the last turns
// them into radiance. The pipeline copies attachment k into the buffer the main pass reads as
// attribute 3, from receiver k x cells on.
#ifndef VPLKIT_LIGHTWAVE_PASS_VPLS
#error "lightwave_capture.frag: define VPLKIT_LIGHTWAVE_PASS_VPLS, the VPLs of one pass (lightwave_pipeline sets it)"
#endif
#define VPLKIT_LIGHTWAVE_FETCH_FLUX 1
#include "lib/lightwave.glsl"
#if VPLKIT_LIGHTWAVE_SUM_RECEIVERS != 4
#error "lightwave_capture.frag reads the previous pass's sums from four samplers (GLSL 3.30 indexes sampler arrays by constants only)"
#endif

// The receivers, a texel each in four bands of `rows` rows: where the vertex's light is evaluated
// (lightwave_receiver_samples), its normal and its albedo.
uniform sampler2D receiver_points;
uniform sampler2D receiver_normals;
uniform sampler2D receiver_albedos;
uniform int receiver_count;
// The previous passes' irradiance at each band's receivers (zero before the first).
uniform sampler2D partial_sum0;
uniform sampler2D partial_sum1;
uniform sampler2D partial_sum2;
uniform sampler2D partial_sum3;
// This pass's VPLs, three rows each: [position | radius], [normal | -], [flux | -].
layout(std140) uniform lightwave_pass_vpls { vec4 pass_vpl_rows[3 * VPLKIT_LIGHTWAVE_PASS_VPLS]; };
uniform int pass_vpl_count;
uniform int last_pass;  // 1: write the radiance; 0: the irradiance so far
uniform irradiance_settings irradiance;

layout(location = 0) out vec4 sums_out[VPLKIT_LIGHTWAVE_SUM_RECEIVERS];

lightwave_flux_vpl lightwave_fetch_flux_vpl(int index) {
  vec4 position_radius = pass_vpl_rows[3 * index];
  return lightwave_flux_vpl(position_radius.xyz, pass_vpl_rows[3 * index + 1].xyz, pass_vpl_rows[3 * index + 2].xyz, position_radius.w);
}

void main() {
  ivec2 texel = ivec2(gl_FragCoord.xy);
  ivec2 grid = textureSize(partial_sum0, 0);
  int cell = texel.y * grid.x + texel.x, cells = grid.x * grid.y;
  ivec2 band_texels[VPLKIT_LIGHTWAVE_SUM_RECEIVERS];
  vec3 sample_points[VPLKIT_LIGHTWAVE_SUM_RECEIVERS], normals[VPLKIT_LIGHTWAVE_SUM_RECEIVERS];
  vec3 sums[VPLKIT_LIGHTWAVE_SUM_RECEIVERS];
  sums[0] = texelFetch(partial_sum0, texel, 0).xyz;
  sums[1] = texelFetch(partial_sum1, texel, 0).xyz;
  sums[2] = texelFetch(partial_sum2, texel, 0).xyz;
  sums[3] = texelFetch(partial_sum3, texel, 0).xyz;
  for (int k = 0; k < VPLKIT_LIGHTWAVE_SUM_RECEIVERS; ++k) {
    band_texels[k] = texel + ivec2(0, k * grid.y);
    sample_points[k] = texelFetch(receiver_points, band_texels[k], 0).xyz;
    normals[k] = normalize(texelFetch(receiver_normals, band_texels[k], 0).xyz);  // the pipeline gives empty texels a unit normal
  }
  // A fragment past the last receiver sums nothing (the first band's receivers come first).
  lightwave_bounce_sums(sample_points, normals, cell < receiver_count ? pass_vpl_count : 0, sums, irradiance.min_distance);
  for (int k = 0; k < VPLKIT_LIGHTWAVE_SUM_RECEIVERS; ++k) {
    vec3 sum = sums[k];
    if (last_pass != 0) sum = diffuse_radiance(texelFetch(receiver_albedos, band_texels[k], 0).xyz, vec3(0.0), 0.0, sum);
    sums_out[k] = vec4(k * cells + cell < receiver_count ? sum : vec3(0.0), 1.0);
  }
}
