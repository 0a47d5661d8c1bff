// GLSL twin of vplkit::rsm_texel (include/vplkit/rsm_gather.hpp): one pixel light of the RSM, in
// the light's eye space. Shared by the gather (lib/rsm_gather.glsl) and the packing
// (lib/rsm_packing.glsl), which the RSM pass uses without the gather.
#ifndef VPLKIT_RSM_TEXEL_GLSL
#define VPLKIT_RSM_TEXEL_GLSL

struct rsm_texel {
  vec3 position;  // light eye space; z >= 0: empty texel
  vec3 normal;    // light eye space
  vec3 flux;
};

#endif
