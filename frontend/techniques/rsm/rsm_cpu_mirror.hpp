// The CPU mirror of the RSM pipeline's gather and post passes: the same C++ kernels the GLSL
// twins mirror, run on the RSM and G-buffer read back from the GL pipeline, so that tests can
// compare the passes texel by texel and benchmarks can compare the CPU gather with llvmpipe.
// Rows are split across threads; every texel is computed exactly as in its shader.
#pragma once

#include <array>
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

/// Pass 1b on the CPU (coverage): the coarse lights of the RSM, reduce_rsm_block per block, as
/// rsm_coarse.frag writes them: [position | extent], [normal | 0], [flux | 0], C x C each.
std::array<image, 3> cpu_coarse_pass(const rsm_pass_buffers& buffers, const rsm_frame_constants& constants, int threads);

/// The coarse lights read back from the GL pipeline (buffers.coarse), block (x, y) at y * C + x;
/// empty without coverage.
std::vector<coarse_light<float>> coarse_lights_of(const rsm_pass_buffers& buffers);

/// Pass 3 on the CPU: [irradiance | camera depth] at the indirect buffer's resolution, with the
/// coverage's coarse lights read back in `buffers`.
image cpu_gather_pass(const rsm_pass_buffers& buffers, const rsm_frame_constants& constants, int threads);

/// Pass 3b on the CPU (temporal accumulation, rsm_pipeline::render_next): `indirect` (this frame's
/// gather) blended with `history` (the previous accumulated buffer) as temporal.frag does, with
/// the inputs the pipeline reports for the frame (last_temporal_inputs).
image cpu_temporal_pass(const image& indirect, const image& history, const rsm_pipeline::temporal_inputs& inputs, const rsm_pass_buffers& buffers,
                        const rsm_frame_constants& constants, int threads);

/// Pass 4a on the CPU (separable filter): the x axis over `indirect`.
image cpu_blur_x_pass(const image& indirect, const rsm_pass_buffers& buffers,
                             const rsm_frame_constants& constants, int threads);

struct post_images {
  image radiance;  ///< [radiance | 1]
  image indirect;  ///< [filtered indirect irradiance | 1]
};

/// Pass 4 on the CPU, reading `filtered_input`: the indirect buffer (full filter) or the x pass's
/// output (separable filter). With the separable filter at indirect divisor 2 the y axis runs as
/// pass 4b does (blur_y.frag): the 2 x 2 pixels of each indirect texel at once
/// (bilateral_filter_axis_quad), the same values as per pixel.
post_images cpu_post_pass(const image& filtered_input, const rsm_pass_buffers& buffers,
                          const rsm_frame_constants& constants, int threads);

}  // namespace vplkit
