#version 330 core
// Final gathering: the room seen from one light (a spot, a sun, or one face of a point light),
// its light eye depth (negative in front of the light, lib/shadow.glsl's convention) for final_gather_shadow.glsl; cut-outs are discarded.
#include "lib/transform.glsl"
#include "surface_material.glsl"

uniform mat4 light_view;
in vec3 world_position;
layout(location = 0) out vec4 light_depth;

void main() {
  material_albedo(vec3(1.0));
  light_depth = vec4(transform_point(light_view, world_position).z, 0.0, 0.0, 1.0);
}
