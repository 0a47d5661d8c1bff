#version 330 core
// Geometry passes (RSM, G-buffers, shadow maps, cube faces): world-space attributes for the
// fragment stage, which takes its material from surface_material.glsl.
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 albedo;
layout(location = 5) in vec2 texcoord;
uniform mat4 view_projection;
// The same position, bit for bit, in every program that draws the mesh: Light Wave's main pass
// tests its depth EQUAL to a depth pre-pass drawn with scene.vert.
invariant gl_Position;
out vec3 world_position;
out vec3 world_normal;
out vec3 surface_albedo;
out vec2 surface_texcoord;
void main() {
  world_position = position;
  world_normal = normal;
  surface_albedo = albedo;
  surface_texcoord = texcoord;
  gl_Position = view_projection * vec4(position, 1.0);
}
