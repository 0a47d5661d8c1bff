#version 330 core
// Light Wave main pass, vertex stage ([LW], section 4.2). VPLKIT_LIGHTWAVE_ENERGY 0, the
// thesis's: the indirect colour of each vertex from all VPLs (Eq. 4.5), read from a float
// texture, a row per VPL, texel (0, i) [position | attenuation], (1, i) [normal | -] (no [0, 1]
// encoding, Eq. 4.3, 4.4, is needed with float textures), every frame; VPLKIT_LIGHTWAVE_CAPTURE
// makes it the transform-feedback program the parity test reads. 1, flux: the indirect light
// does not depend on the camera, so the pipeline sums it once per light at the receivers
// (lightwave_capture.frag) and this stage passes it on from attribute 3.
#if VPLKIT_LIGHTWAVE_ENERGY != 1
#define VPLKIT_LIGHTWAVE_FETCH 1
#endif
#include "lib/lightwave.glsl"

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 albedo;
layout(location = 5) in vec2 texcoord;
#if VPLKIT_LIGHTWAVE_ENERGY == 1
layout(location = 3) in vec3 captured_indirect;
#endif

uniform mat4 view_projection;
// The same position, bit for bit, in every program that draws the mesh: Light Wave's main pass
// tests its depth EQUAL to a depth pre-pass drawn with scene.vert.
invariant gl_Position;
uniform vec3 eye;
uniform sampler2D vpl_texture;
uniform int vpl_count;
uniform lightwave_shading_settings shading;
uniform irradiance_settings irradiance;

out vec3 world_position;
out vec3 world_normal;
out vec3 surface_albedo;
out vec3 vertex_indirect;
out vec2 surface_texcoord;

#if VPLKIT_LIGHTWAVE_ENERGY != 1
lightwave_vpl lightwave_fetch_vpl(int index) {
  vec4 position_attenuation = texelFetch(vpl_texture, ivec2(0, index), 0);
  return lightwave_vpl(position_attenuation.xyz, texelFetch(vpl_texture, ivec2(1, index), 0).xyz, position_attenuation.w);
}
#endif

void main() {
  vec3 n = normalize(normal);
#if VPLKIT_LIGHTWAVE_INDIRECT && VPLKIT_LIGHTWAVE_ENERGY == 1
  vertex_indirect = captured_indirect;
#elif VPLKIT_LIGHTWAVE_INDIRECT
  vertex_indirect = lightwave_vertex_indirect(position, n, albedo, eye, vpl_count, shading);
#else
  vertex_indirect = vec3(0.0);
#endif
  world_position = position;
  world_normal = n;
  surface_albedo = albedo;
  surface_texcoord = texcoord;
  gl_Position = view_projection * vec4(position, 1.0);
}
