#version 330 core
// The emission pass (frontend/scene_gl/emission_pass.hpp): the emitted radiance of an emissive
// material's fragment, added to a technique's final image where the fragment is the surface the
// camera sees (depth EQUAL to the family's own depth of the view: scene.vert's invariant
// position). Radiance leaves the side the surface's normal faces, the side every technique and
// reference lights; the back of an emitter adds nothing.
#include "surface_material.glsl"

uniform vec3 eye;
uniform vec3 material_emission;  // linear RGB, frontend/scene/material.hpp
uniform int material_emission_textured;
uniform sampler2D material_emission_texture;
uniform vec4 material_emission_texture_matrix;  // its KHR_texture_transform's 2x2, column by column
uniform vec2 material_emission_texture_offset;

in vec3 world_position;
in vec3 world_normal;
in vec3 surface_albedo;
out vec4 radiance;

void main() {
  // Sampled before any discard: the texture's level of detail needs the whole pixel quad.
  vec3 texel = vec3(1.0);
  if (material_emission_textured != 0)
    texel = texture(material_emission_texture,
                    mat2(material_emission_texture_matrix.xy, material_emission_texture_matrix.zw) * surface_texcoord + material_emission_texture_offset).rgb;
  material_albedo(surface_albedo);  // a cut-out emits nothing
  if (dot(world_normal, eye - world_position) <= 0.0) discard;
  radiance = vec4(material_emission * texel, 0.0);
}
