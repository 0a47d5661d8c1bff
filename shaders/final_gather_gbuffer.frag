#version 330 core
// Final gathering, G-buffer: [world position | 1 environment, 2 object], [normal | -],
// [albedo | -]; 0 in .w of the first target means no surface. The direct light is summed per
// light from these by final_gather_direct.frag.
#include "surface_material.glsl"

uniform float surface_kind;
in vec3 world_position;
in vec3 world_normal;
in vec3 surface_albedo;
layout(location = 0) out vec4 position_kind;
layout(location = 1) out vec4 normal_out;
layout(location = 2) out vec4 albedo_out;
void main() {
  position_kind = vec4(world_position, surface_kind);
  normal_out = vec4(normalize(world_normal), 0.0);
  albedo_out = vec4(material_albedo(surface_albedo), 0.0);
}
