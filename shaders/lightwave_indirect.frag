#version 330 core
// Light Wave's flux energy, first half of the main pass: the receivers (the scene subdivided,
// lightwave_receivers) drawn with their vertices' indirect light (lightwave.vert, attribute 3)
// interpolated into a screen-sized buffer, which the second half (lightwave.frag, drawing the
// scene's own triangles with their materials) reads at its pixel. The heavy fragment stage
// (direct light and the indirect shadows) then runs on the scene's few large triangles: a
// software rasteriser shades each small triangle's partly covered pixel blocks in full.
#include "surface_material.glsl"

in vec3 vertex_indirect;
layout(location = 0) out vec4 indirect_out;

void main() {
  material_albedo(vec3(1.0));  // a cut-out discarded here too, so the buffer holds what lies behind it
  indirect_out = vec4(vertex_indirect, 1.0);
}
