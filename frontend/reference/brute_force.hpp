// The brute-force RSM gather of [RSMV]'s Fig. 5.1d on the CPU: every pixel light of the RSM at
// every G-buffer point, with exact visibility (a ray cast per pair) or without; the radial
// pattern's own samples with ray-cast visibility; and the receivers the RSM gather covers.
// Deterministic, multi-threaded, long work (estimate_rsm_gather says what a run costs).
#pragma once

#include <cstdint>
#include <vector>

#include "frontend/core/progress.hpp"
#include "frontend/image/image.hpp"
#include "frontend/reference/ray_scene.hpp"
#include "frontend/reference/work.hpp"
#include "frontend/techniques/rsm/rsm_pipeline.hpp"

namespace vplkit {

/// Options of the brute-force RSM gather (the thesis's Fig. 5.1d).
struct rsm_brute_force_options {
  bool exact_visibility = false;  ///< ray-cast every pixel light against the scene (else none)
  /// Only the pixel lights within this many RSM texels of the receiver's projection (for the
  /// radius part of the error split); 0: every lit texel of the RSM.
  float max_radius = 0.0f;
  /// Compute every stride-th receiver of the indirect buffer per axis (the others stay 0), to
  /// bound the cost of exact visibility at full resolution.
  int receiver_stride = 1;
  int threads = 1;
};

/// The brute-force RSM gather at the receivers of the indirect buffer of `buffers` (the G-buffer
/// points the GL gather uses): every lit RSM texel (flux > 0) is a pixel light, Eq. 3.2 with the
/// same distance clamp and the same 1/pi as gather_rsm. Receivers behind the light (light eye
/// z >= 0) are computed too: the RSM does light them, although the gather cannot (see
/// rsm_covered_receivers). Returns [irradiance | the fraction of the unoccluded irradiance that is
/// visible (1 without visibility)].
image reference_rsm_gather(const ray_scene& rays, const rsm_pass_buffers& buffers, const rsm_frame_constants& constants,
                                  const rsm_brute_force_options& options, const progress_settings& progress = {});

/// The cost of reference_rsm_gather with these options: receivers x lit RSM texels pairs (a ray
/// each with exact visibility), timed on up to 64 receivers spread over the buffer.
reference_cost estimate_rsm_gather(const ray_scene& rays, const rsm_pass_buffers& buffers, const rsm_frame_constants& constants,
                                   const rsm_brute_force_options& options);

/// The radial pattern's own samples (the same pattern, seed and weights as the frame's gather)
/// with exact visibility: each sample's pixel light is ray cast instead of tested against the
/// micro linear buffer. The difference to the brute force with exact visibility is the
/// sampling error alone; to the gather with Alg. 6, the visibility approximation's error alone.
image gather_with_ray_cast_visibility(const ray_scene& rays, const rsm_pass_buffers& buffers, const rsm_frame_constants& constants,
                                             int receiver_stride, int threads);

/// The receivers of the indirect buffer the RSM gather covers (1) or not (0): a surface in front
/// of the light (light eye z < 0) whose projection falls inside the RSM. gather_rsm returns 0
/// behind the light (no projection), and outside the light's frustum its pattern reaches only
/// the part of the RSM within its radius of a projection that lies off the map. Every RSM metric
/// counts covered receivers only, and says how much light the others hold. With a stride, only
/// every stride-th receiver per axis can count (the ones a strided reference computes).
std::vector<std::uint8_t> rsm_covered_receivers(const rsm_pass_buffers& buffers, const rsm_frame_constants& constants, int receiver_stride = 1);

/// Every light of the frame `drawn` last drew (rsm_pipeline::read_buffers and constants per light),
/// each light's brute force summed: [the summed irradiance | the fraction of the summed unoccluded
/// irradiance that is visible]. One light: exactly reference_rsm_gather of its buffers.
image reference_rsm_gather(const ray_scene& rays, const rsm_pipeline& drawn, const rsm_brute_force_options& options, const progress_settings& progress = {});

/// The cost of the call above: each light's estimate_rsm_gather added up.
reference_cost estimate_rsm_gather(const ray_scene& rays, const rsm_pipeline& drawn, const rsm_brute_force_options& options);

/// The receivers some light's pattern covers (rsm_covered_receivers of each light, or-ed).
std::vector<std::uint8_t> rsm_covered_receivers(const rsm_pipeline& drawn, int receiver_stride = 1);

}  // namespace vplkit
