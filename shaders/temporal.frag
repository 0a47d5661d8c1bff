#version 330 core
// Pass 3b, temporal accumulation (sequences: rsm_pipeline::render_next): each receiver's raw
// gather blended with its accumulated value of the frame before, reprojected through the previous
// camera and clamped to the current 3 x 3 neighbourhood (lib/temporal_accumulation.glsl). Writes
// [irradiance | camera eye depth] like the indirect buffer; the post filter reads it instead.
#include "lib/temporal_accumulation.glsl"
#include "lib/transform.glsl"

uniform temporal_settings temporal;
uniform mat4 previous_view;
uniform mat4 previous_view_projection;
uniform int history_valid;
uniform int indirect_divisor;
uniform ivec2 indirect_size;
uniform ivec2 gbuffer_size;
uniform sampler2D indirect_buffer;
uniform sampler2D history_buffer;
uniform sampler2D gbuffer_position_depth;

layout(location = 0) out vec4 accumulated;

void main() {
  ivec2 texel = ivec2(gl_FragCoord.xy);
  vec4 current = texelFetch(indirect_buffer, texel, 0);
  if (!(current.w < 0.0)) {  // no surface here
    accumulated = vec4(0.0);
    return;
  }
  neighbourhood_moments moments = neighbourhood_moments(vec3(0.0), vec3(0.0), 0.0);
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      ivec2 neighbour = texel + ivec2(dx, dy);
      if (neighbour.x < 0 || neighbour.y < 0 || neighbour.x >= indirect_size.x || neighbour.y >= indirect_size.y) continue;
      vec4 value = texelFetch(indirect_buffer, neighbour, 0);
      if (value.w < 0.0) neighbourhood_add(moments, value.xyz);
    }
  vec3 world = texelFetch(gbuffer_position_depth, min(texel * indirect_divisor, gbuffer_size - 1), 0).xyz;
  float expected = transform_point(previous_view, world).z;
  bool valid = false;
  vec3 history = vec3(0.0);
  if (history_valid != 0 && expected < 0.0) {
    vec2 previous = map_coordinate(previous_view_projection, world, indirect_size);
    if (previous.x >= 0.0 && previous.y >= 0.0 && previous.x < float(indirect_size.x) && previous.y < float(indirect_size.y)) {
      vec4 stored = texelFetch(history_buffer, ivec2(floor(previous)), 0);
      valid = temporal_history_matches(expected, stored.w, temporal);
      history = stored.xyz;
    }
  }
  accumulated = vec4(temporal_resolve(current.xyz, history, valid, moments, temporal), current.w);
}
