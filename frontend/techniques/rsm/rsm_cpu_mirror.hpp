// The CPU mirror of the RSM pipeline's gather and post passes: the same C++ kernels the GLSL
// twins mirror, run on the RSM and G-buffer read back from the GL pipeline, so that tests can
// compare the passes texel by texel and benchmarks can compare the CPU gather with llvmpipe.
// Rows are split across threads; every texel is computed exactly as in its shader.
#pragma once

#include <optional>
#include <vector>

#include "frontend/core/parallel.hpp"
#include "frontend/techniques/rsm/rsm_pipeline.hpp"

namespace vplkit {

/// The G-buffer texel that indirect-buffer texel `texel` gathers for (texel * divisor, clamped),
/// as gather.frag reads it.
glm::ivec2 gbuffer_texel_of(glm::ivec2 texel, const rsm_frame_constants& constants);

/// The receiver of the gather at indirect-buffer texel `texel`, as gather.frag builds it (in the
/// light's eye space); nothing where the G-buffer has no surface.
std::optional<gather_receiver<float>> gather_receiver_at(glm::ivec2 texel, const rsm_pass_buffers& buffers, const rsm_frame_constants& constants);

/// The packed RSM decoded (unpack_rsm_texel, light eye space), one pixel light per element,
/// row-major like the target.
std::vector<rsm_texel<float>> unpack_rsm(const rsm_pass_buffers& buffers, const rsm_frame_constants& constants);

/// Pass 3 on the CPU: [irradiance | camera depth] at the indirect buffer's resolution.
image cpu_gather_pass(const rsm_pass_buffers& buffers, const rsm_frame_constants& constants, int threads);

/// Pass 4a on the CPU (separable filter): the x axis over `indirect`.
image cpu_blur_x_pass(const image& indirect, const rsm_pass_buffers& buffers,
                             const rsm_frame_constants& constants, int threads);

struct post_images {
  image radiance;  ///< [radiance | 1]
  image indirect;  ///< [filtered indirect irradiance | 1]
};

/// Pass 4 on the CPU, reading `filtered_input`: the indirect buffer (full filter) or the x pass's
/// output (separable filter).
post_images cpu_post_pass(const image& filtered_input, const rsm_pass_buffers& buffers,
                          const rsm_frame_constants& constants, int threads);

}  // namespace vplkit
