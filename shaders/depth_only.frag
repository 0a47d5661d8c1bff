#version 330 core
// Shadow-map passes: depth only (the rasteriser writes gl_FragCoord.z); cut-outs are discarded.
#include "surface_material.glsl"

void main() { material_albedo(vec3(1.0)); }
