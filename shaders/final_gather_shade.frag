#version 330 core
// Final gathering, shading ([FG]): the environment with its direct light (every light's,
// shadowed by the room: final_gather_direct.frag's sum); the object with
// direct light plus the indirect irradiance of the variant: VPLKIT_FINAL_GATHER 0 polygon-to-point,
// 1 point-to-point (lib/final_gather.glsl), 2 the classic environment-map lookup.
// Writes [radiance | 1], [indirect irradiance | 1] and [shadowed direct irradiance | 1].
#if VPLKIT_FINAL_GATHER == 1
#define VPLKIT_FORM_FACTOR 1
#else
#define VPLKIT_FORM_FACTOR 0
#endif
#include "lib/final_gather.glsl"
#include "lib/shading.glsl"

uniform sampler2D small_cube;
uniform sampler2D environment_map;
uniform sampler2D gbuffer_position_kind;
uniform sampler2D gbuffer_normal;
uniform sampler2D gbuffer_albedo;
uniform sampler2D direct_irradiance;
uniform int resolution;
uniform int environment_resolution;
uniform vec3 reference_point;
layout(location = 0) out vec4 radiance;
layout(location = 1) out vec4 indirect_out;
layout(location = 2) out vec4 direct_out;

vec4 small_cube_fetch(int face, int i, int j) { return texelFetch(small_cube, ivec2(face * resolution + i, j), 0); }

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 position_kind = texelFetch(gbuffer_position_kind, pixel, 0);
  if (position_kind.w < 0.5) {
    radiance = vec4(0.0, 0.0, 0.0, 1.0);
    indirect_out = vec4(0.0, 0.0, 0.0, 1.0);
    direct_out = vec4(0.0, 0.0, 0.0, 1.0);
    return;
  }
  vec3 x = position_kind.xyz;
  vec3 n = texelFetch(gbuffer_normal, pixel, 0).xyz;
  vec3 albedo = texelFetch(gbuffer_albedo, pixel, 0).xyz;
  vec3 indirect = vec3(0.0);
  if (position_kind.w > 1.5) {
#if VPLKIT_FINAL_GATHER == 2
    ivec3 texel = cube_texel_of(n, environment_resolution);
    indirect = texelFetch(environment_map, ivec2(texel.x * environment_resolution + texel.y, texel.z), 0).xyz;
#else
    indirect = final_gather_irradiance(x, n, reference_point, resolution);
#endif
  }
  vec3 direct = texelFetch(direct_irradiance, pixel, 0).xyz;
  radiance = vec4(diffuse_radiance(albedo, direct, 1.0, indirect), 1.0);
  indirect_out = vec4(indirect, 1.0);
  direct_out = vec4(direct, 1.0);
}
