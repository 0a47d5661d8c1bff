#version 330 core
// Geometry passes (RSM and G-buffer): world-space attributes for the fragment stage.
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 albedo;
uniform mat4 view_projection;
out vec3 world_position;
out vec3 world_normal;
out vec3 surface_albedo;
void main() {
  world_position = position;
  world_normal = normal;
  surface_albedo = albedo;
  gl_Position = view_projection * vec4(position, 1.0);
}
