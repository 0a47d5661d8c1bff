#version 330 core
// Final gathering, G-buffer: [world position | 1 environment, 2 object], [normal | the spot's
// visibility past the room (final_gather_shadow.glsl)], [albedo | -]; 0 in .w of the first target
// means no surface. The visibility is here, not in the shading pass, so that the CPU mirror reads
// it as the shading does.
#include "final_gather_shadow.glsl"
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
  vec3 n = normalize(world_normal);
  normal_out = vec4(n, final_gather_light_visibility(world_position, n));
  albedo_out = vec4(material_albedo(surface_albedo), 0.0);
}
