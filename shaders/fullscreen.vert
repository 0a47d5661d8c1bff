#version 330 core
// Full-screen triangle without vertex data (gl_VertexID 0, 1, 2).
out vec2 texture_coordinate;
void main() {
  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  texture_coordinate = corner;
  gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
