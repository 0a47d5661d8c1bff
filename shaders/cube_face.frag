#version 330 core
// Final gathering, pass 1 ([FG], section 4): one face of the cube map around the reference
// point o: [radiance | distance from o] of the environment (the object is left out). The
// environment's radiance is its direct light with the room's shadows (final_gather_shadow.glsl):
// albedo / pi * E * V of one light; the pipeline draws the faces once per light and adds the
// lights' radiances (blending, the distance written again), so that each light has its own shadows.
#include "final_gather_shadow.glsl"
#include "surface_material.glsl"

uniform irradiance_settings irradiance;
uniform vec3 reference_point;

in vec3 world_position;
in vec3 world_normal;
in vec3 surface_albedo;
layout(location = 0) out vec4 radiance_distance;

void main() {
  vec3 n = normalize(world_normal);
  vec3 radiance = material_albedo(surface_albedo) * 0.318309886183790671538 * final_gather_light_irradiance(world_position, n, irradiance) *
                  final_gather_light_visibility(world_position, n);
  radiance_distance = vec4(radiance, length(world_position - reference_point));
}
