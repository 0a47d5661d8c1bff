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
// voxel_rsm_visibility's samples_per_march: the samples of a path that share one march.
int rsm_voxel_group() { return voxel_march.group; }
#if VPLKIT_RSM_COVERAGE
float rsm_voxel_coarse_visibility(vec3 x, vec3 n, vec3 xc, vec3 nc) {
  return voxel_coarse_light_visible(voxel_shape, voxel_march, voxel_from_light, x, n, xc, nc);
}
#endif
#endif
#if VPLKIT_RSM_COVERAGE && VPLKIT_VISIBILITY != 8
#include "lib/rsm_coarse_visibility.glsl"
// A point light's coarse lights against its six depth maps (lib/rsm_coarse_visibility.glsl;
// rsm_pipeline's coarse_cube_of sets them); a spot's or a sun's stay unoccluded (cube_faces 0).
// The C++ twin: the coarse visibility rsm_cpu_mirror.cpp gives gather_rsm.
uniform int cube_faces;
uniform cube_depth_frames cube_frames;
// The six faces' eye-space depths, one layer each (rsm_pipeline copies each face's RSM's first
// word there): one fetch, where six samplers (GLSL 3.30 indexes sampler arrays with constants
// only) needed an if chain that llvmpipe runs under masks for every lane.
uniform usampler2DArray rsm_face_depths;
float rsm_face_depth(int face, ivec2 texel) { return uintBitsToFloat(texelFetch(rsm_face_depths, ivec3(texel, face), 0).x); }
float rsm_depth_coarse_visibility(vec3 x, vec3 xc) {
  if (cube_faces == 0) return 1.0;
  return coarse_light_cube_visibility(x, xc, cube_frames, unprojection, settings.rsm_size);
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
