#version 330 core
// Several lights: a further light's Light Wave images (drawn by a pipeline of its own, with its
// own VPLs and shadow maps) added onto the first light's with additive blending
// (lightwave_pipeline::add_light_pipelines). Every image of the main pass is linear in the light
// (direct * shadow + indirect, no emission, no ambient term), so the sum is the image of all
// lights. Output 1, the indirect shadow factor, is a ratio, not a light: it is masked and stays the
// first light's. Alpha 0: the sum keeps the first image's alpha of 1.
uniform sampler2D radiance_image;
uniform sampler2D indirect_image;
uniform sampler2D irradiance_image;
uniform sampler2D direct_image;
layout(location = 0) out vec4 colour;
layout(location = 1) out vec4 indirect_shadow;
layout(location = 2) out vec4 indirect_out;
layout(location = 3) out vec4 indirect_irradiance_out;
layout(location = 4) out vec4 direct_irradiance_out;

void main() {
  // The same size as the target: texel for texel, no filtering.
  ivec2 texel = ivec2(gl_FragCoord.xy);
  colour = vec4(texelFetch(radiance_image, texel, 0).rgb, 0.0);
  indirect_shadow = vec4(0.0);
  indirect_out = vec4(texelFetch(indirect_image, texel, 0).rgb, 0.0);
  indirect_irradiance_out = vec4(texelFetch(irradiance_image, texel, 0).rgb, 0.0);
  direct_irradiance_out = vec4(texelFetch(direct_image, texel, 0).rgb, 0.0);
}
