#version 330 core
// Pass 3, RSM sampling ([RSMV], section 4.4): the gather at the indirect buffer's resolution,
// one G-buffer sample per texel (G-buffer texel = indirect texel * divisor). Writes
// [irradiance | camera eye depth] (Fig. 4.4). VPLKIT_RSM_PATTERN and VPLKIT_VISIBILITY select
// the variant, VPLKIT_SLOT_COUNT fixes the slot count, VPLKIT_RSM_COVERAGE adds the coarse
// lights of rsm_coarse.frag for the receivers the pattern cannot reach (lib/rsm_gather.glsl). One
// fetch per sample: the RSM is one packed texture (lib/rsm_packing.glsl), and the gather runs in
// the light's eye space.
#include "lib/rsm_gather.glsl"
#include "lib/rsm_packing.glsl"
#if VPLKIT_VISIBILITY == 8
#include "lib/voxel_visibility.glsl"
#endif

uniform rsm_gather_settings settings;
uniform rsm_unprojection unprojection;
uniform mat4 light_view;
uniform mat4 light_view_projection;
uniform int indirect_divisor;
uniform ivec2 gbuffer_size;
uniform usampler2D rsm_packed;
uniform sampler2D gbuffer_position_depth;
uniform sampler2D gbuffer_normal;
#if VPLKIT_RSM_COVERAGE
uniform sampler2D coarse_position_extent;
uniform sampler2D coarse_normal;
uniform sampler2D coarse_flux;
#endif

#if VPLKIT_VISIBILITY == 8
// rsm-voxel: the scene's occupancy grid (vplkit/voxel_visibility.hpp), built on the CPU.
uniform usampler2D voxel_packed;
uniform voxel_grid_shape voxel_shape;
uniform voxel_march_settings voxel_march;
uniform mat4 voxel_from_light;  // the light's eye space to the grid's cells (voxel_cells_from)
#endif

layout(location = 0) out vec4 indirect;

rsm_texel rsm_fetch(ivec2 texel) { return unpack_rsm_texel(texelFetch(rsm_packed, texel, 0), texel, unprojection); }
#if VPLKIT_RSM_COVERAGE
coarse_light rsm_coarse_fetch(ivec2 block) {
  vec4 position_extent = texelFetch(coarse_position_extent, block, 0);
  return coarse_light(position_extent.xyz, texelFetch(coarse_normal, block, 0).xyz, texelFetch(coarse_flux, block, 0).xyz, position_extent.w);
}
#endif
#if VPLKIT_VISIBILITY == 8
uvec4 voxel_fetch(ivec2 texel) { return texelFetch(voxel_packed, texel, 0); }
// The C++ twins are voxel_rsm_visibility's operator() and coarse(): from the light's eye space to the grid's cells.
float rsm_voxel_visibility(vec3 x, vec3 n, vec3 xp, vec3 np) { return voxel_light_visible(voxel_shape, voxel_march, voxel_from_light, x, n, xp, np); }
#if VPLKIT_RSM_COVERAGE
float rsm_voxel_coarse_visibility(vec3 x, vec3 n, vec3 xc, vec3 nc) {
  return voxel_coarse_light_visible(voxel_shape, voxel_march, voxel_from_light, x, n, xc, nc);
}
#endif
#endif
#if VPLKIT_RSM_COVERAGE && VPLKIT_VISIBILITY != 0 && VPLKIT_VISIBILITY != 8 && VPLKIT_VISIBILITY != 2
#define PROTO_SLAB 0.25
#ifndef PROTO_K
#define PROTO_K 4
#endif
#ifndef PROTO_THICK
#define PROTO_THICK 0.2
#endif
uniform int cube_faces;
uniform mat4 cube_from_light;
uniform mat4 face_from_light[6];
uniform usampler2D rsm_face0;
uniform usampler2D rsm_face1;
uniform usampler2D rsm_face2;
uniform usampler2D rsm_face3;
uniform usampler2D rsm_face4;
uniform usampler2D rsm_face5;
float face_depth(int g, ivec2 t) {
  if (g == 0) return uintBitsToFloat(texelFetch(rsm_face0, t, 0).x);
  if (g == 1) return uintBitsToFloat(texelFetch(rsm_face1, t, 0).x);
  if (g == 2) return uintBitsToFloat(texelFetch(rsm_face2, t, 0).x);
  if (g == 3) return uintBitsToFloat(texelFetch(rsm_face3, t, 0).x);
  if (g == 4) return uintBitsToFloat(texelFetch(rsm_face4, t, 0).x);
  return uintBitsToFloat(texelFetch(rsm_face5, t, 0).x);
}
bool point_hidden(vec3 p, int g) {
  if (unprojection.perspective != 0 && !(p.z < 0.0)) return false;
  vec2 ray = unprojection.perspective != 0 ? p.xy / -p.z : p.xy;
  ivec2 texel = ivec2(floor((ray - unprojection.ray_origin) / unprojection.ray_step + 0.5));
  if (texel.x < 0 || texel.y < 0 || texel.x >= settings.rsm_size.x || texel.y >= settings.rsm_size.y) return false;
  float z = g < 0 ? uintBitsToFloat(texelFetch(rsm_packed, texel, 0).x) : face_depth(g, texel);
  if (!(z < 0.0)) return false;
#ifdef PROTO_SLAB
  return -p.z > -z * (1.0 + 0.01) && -p.z < -z * (1.0 + PROTO_SLAB);
#else
  return -p.z > -z * (1.0 + PROTO_THICK);
#endif
}
float rsm_depth_coarse_visibility(vec3 x, vec3 xc) {
  if (cube_faces == 0) return 1.0;  // a spot's or a sun's map: measured no better (Cornell box, living-room 5, thin-walls 5 worse for Alg. 3/6)
  for (int i = 0; i < PROTO_K; ++i) {
    float t = (float(i) + 0.5) / float(PROTO_K);
    t = 0.1 + 0.8 * t;
    vec3 p = mix(xc, x, t);
    vec3 d = transform_direction(cube_from_light, p);  // the world's axes: the cube's
    vec3 a = abs(d);
    int g = a.x >= a.y && a.x >= a.z ? (d.x > 0.0 ? 0 : 1) : a.y >= a.z ? (d.y > 0.0 ? 2 : 3) : (d.z > 0.0 ? 4 : 5);
    if (point_hidden(transform_point(face_from_light[g], p), g)) return 0.0;
  }
  return 1.0;
}
#endif

void main() {
  ivec2 texel = ivec2(gl_FragCoord.xy);
  ivec2 sample_texel = min(texel * indirect_divisor, gbuffer_size - 1);
  vec4 position_depth = texelFetch(gbuffer_position_depth, sample_texel, 0);
  if (!(position_depth.w < 0.0)) {  // no surface here
    indirect = vec4(0.0);
    return;
  }
  gather_receiver receiver = make_gather_receiver(position_depth.xyz, texelFetch(gbuffer_normal, sample_texel, 0).xyz, light_view,
                                                  light_view_projection, settings.rsm_size, uvec2(texel));
  indirect = vec4(gather_rsm(receiver, settings), position_depth.w);
}
