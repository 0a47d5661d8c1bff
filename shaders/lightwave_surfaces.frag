#version 330 core
// Light Wave's flux energy: what the spot light sees, one texel per direction of its frustum:
// [world position | 1], [unit normal | 0], [albedo | 0] (cleared to 0 where no surface is). The
// pipeline looks every ray of the flux layout up here and makes its VPL where the ray meets the
// scene (lightwave_pipeline::build_flux_vpls). The albedo is the material's (texture included).
#include "surface_material.glsl"

in vec3 world_position;
in vec3 world_normal;
in vec3 surface_albedo;
layout(location = 0) out vec4 position_out;
layout(location = 1) out vec4 normal_out;
layout(location = 2) out vec4 albedo_out;

void main() {
  position_out = vec4(world_position, 1.0);
  normal_out = vec4(normalize(world_normal), 0.0);
  albedo_out = vec4(material_albedo(surface_albedo), 0.0);
}
