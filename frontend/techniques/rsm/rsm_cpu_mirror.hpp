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

/// A point light's six RSMs read back for one view's coarse-light visibility (rsm_pipeline::coarse_cube).
struct cube_face_rsms {
  cube_depth_frames<float> frames;
  std::array<packed_rsm, 6> faces;
};

/// The cube view `view`'s gather reads (rsm_pipeline::coarse_cube), read back; nothing when it reads none.
std::optional<cube_face_rsms> read_cube_faces(const rsm_pipeline& pipeline, std::size_t view);

/// Pass 3 on the CPU: [irradiance | camera depth] at the indirect buffer's resolution, with the
/// coverage's coarse lights read back in `buffers`; with `cube` (read_cube_faces), every technique
/// but rsm-voxel weighs the coarse lights by coarse_light_cube_visibility over its faces, as
/// gather.frag does; without it they stay unoccluded.
image cpu_gather_pass(const rsm_pass_buffers& buffers, const rsm_frame_constants& constants, int threads, const cube_face_rsms* cube = nullptr);

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
