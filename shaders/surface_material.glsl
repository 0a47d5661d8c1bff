// The material of the triangles a mesh draws (frontend/scene/material.hpp defines it;
// mesh_buffers::draw sets these uniforms per material range): albedo = the vertex's colour factor
// x the base-colour texture (sRGB decoded by its SRGB8_ALPHA8 format, filtered and mipmapped by
// the material's sampler), alpha = the factor's alpha x the texture's. An alpha-tested (MASK)
// fragment below the cutoff is discarded in every pass that draws the scene, the shadow and depth
// passes included, so that a cut-out is not seen, lit, reflected or cast as a shadow.
// Included by every fragment shader that draws a mesh after shaders/scene.vert (or lightwave.vert).
// VPLKIT_MATERIAL_NO_ALPHA_TEST: a pass without the alpha test, for a scene without cut-outs or a
// pass drawn after a depth pre-pass that did it (depth test EQUAL: the pre-pass wrote no depth
// where a cut-out is). A shader without discard has its depth tested before it runs, and a
// depth-only one need not run at all: Light Wave's shadow maps and main pass.
#ifndef VPLKIT_SURFACE_MATERIAL_GLSL
#define VPLKIT_SURFACE_MATERIAL_GLSL

uniform sampler2D material_texture;
uniform int material_textured;          // 0: the vertex albedo alone
uniform vec4 material_texture_matrix;   // KHR_texture_transform's 2x2, column by column
uniform vec2 material_texture_offset;
uniform float material_alpha_factor;
uniform float material_alpha_cutoff;    // < 0: opaque, no alpha test

in vec2 surface_texcoord;

// The surface's albedo (linear RGB) for the vertex colour factor `factor`; discards a cut-out.
vec3 material_albedo(vec3 factor) {
  vec4 texel = vec4(1.0);
  if (material_textured != 0)
    texel = texture(material_texture, mat2(material_texture_matrix.xy, material_texture_matrix.zw) * surface_texcoord + material_texture_offset);
#ifndef VPLKIT_MATERIAL_NO_ALPHA_TEST
  if (material_alpha_factor * texel.a < material_alpha_cutoff) discard;
#endif
  return factor * texel.rgb;
}

#endif
