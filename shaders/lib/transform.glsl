// GLSL twin of include/vplkit/transform.hpp: point and direction transforms with a fixed order of sums.
#ifndef VPLKIT_TRANSFORM_GLSL
#define VPLKIT_TRANSFORM_GLSL

vec3 transform_point(mat4 m, vec3 p) {
  return m[0].xyz * p.x + m[1].xyz * p.y + m[2].xyz * p.z + m[3].xyz;
}

vec3 transform_direction(mat4 m, vec3 v) {
  return m[0].xyz * v.x + m[1].xyz * v.y + m[2].xyz * v.z;
}

vec2 map_coordinate(mat4 view_projection, vec3 p, ivec2 size) {
  vec4 clip = view_projection[0] * p.x + view_projection[1] * p.y + view_projection[2] * p.z + view_projection[3];
  vec2 ndc = clip.xy / clip.w;
  return (ndc * 0.5 + 0.5) * vec2(size);
}

#endif
