// The CPU mirror of the final-gathering shading pass (shaders/final_gather_shade.frag): the same
// kernels (vplkit/final_gather.hpp, vplkit/direct_light.hpp, vplkit/shading.hpp) applied to the
// small cube map and the G-buffer the GL pipeline read back, so that a test can compare the GL
// image with it texel by texel.
#pragma once

#include "frontend/techniques/final_gather/final_gather_pipeline.hpp"

namespace vplkit {

/// The shading pass on the CPU: [radiance | 1] and [indirect irradiance | 1] per pixel.
struct final_gather_images {
  image radiance;
  image indirect;
};
final_gather_images cpu_final_gather_shade(const final_gather_buffers& buffers, const final_gather_scene& source,
                                           const final_gather_settings& settings, int threads);

}  // namespace vplkit
