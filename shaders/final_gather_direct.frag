#version 330 core
// Final gathering: one light's direct irradiance at the G-buffer's surfaces, E * V with the
// room's shadows (final_gather_shadow.glsl); the pipeline adds the lights' passes (blending onto
// 0), so that the shading and its CPU mirror read the sum. Here rather than in the G-buffer pass
// so that each light is one full-screen pass with its own shadow map.
#include "final_gather_shadow.glsl"

uniform irradiance_settings irradiance;
uniform sampler2D gbuffer_position_kind;
uniform sampler2D gbuffer_normal;
layout(location = 0) out vec4 direct;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 position_kind = texelFetch(gbuffer_position_kind, pixel, 0);
  if (position_kind.w < 0.5) {
    direct = vec4(0.0);
    return;
  }
  vec3 x = position_kind.xyz, n = texelFetch(gbuffer_normal, pixel, 0).xyz;
  direct = vec4(final_gather_light_irradiance(x, n, irradiance) * final_gather_light_visibility(x, n), 0.0);
}
