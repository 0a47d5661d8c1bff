#version 330 core
// Light Wave main pass, vertex stage ([LW], section 4.2): the indirect colour of each vertex
// from all VPLs (Eq. 4.5, lib/lightwave.glsl), read from a float texture: texel (0, i) holds
// [position | attenuation] of VPL i, texel (1, i) its [normal | -]. No [0, 1] encoding (Eq. 4.3,
// 4.4) is needed with float textures.
#define VPLKIT_LIGHTWAVE_FETCH 1
#include "lib/lightwave.glsl"

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 albedo;
layout(location = 5) in vec2 texcoord;

uniform mat4 view_projection;
uniform vec3 eye;
uniform sampler2D vpl_texture;
uniform int vpl_count;
uniform lightwave_shading_settings shading;

out vec3 world_position;
out vec3 world_normal;
out vec3 surface_albedo;
out vec3 vertex_indirect;
out vec2 surface_texcoord;

lightwave_vpl lightwave_fetch_vpl(int index) {
  vec4 position_attenuation = texelFetch(vpl_texture, ivec2(0, index), 0);
  return lightwave_vpl(position_attenuation.xyz, texelFetch(vpl_texture, ivec2(1, index), 0).xyz, position_attenuation.w);
}

void main() {
  vec3 n = normalize(normal);
#if VPLKIT_LIGHTWAVE_INDIRECT
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
