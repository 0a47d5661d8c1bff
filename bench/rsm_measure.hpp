// Measuring the RSM gather against its ground truth, for the study (rsm_study.cpp) and the
// quality report (quality_report.cpp): the brute-force references of one frame, and a
// technique's errors against them, raw and filtered, averaged over pattern seeds.
// Every image here is at the indirect buffer's resolution, a vplkit::image (rows bottom-up, like the buffer).
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include <vplkit/gl/program.hpp>

#include "frontend/image/metrics.hpp"
#include "frontend/reference/reference.hpp"
#include "frontend/techniques/rsm/rsm_pipeline.hpp"

namespace vplkit {

/// The ground truth of one frame: the brute force with and without exact visibility at every
/// stride-th receiver, and the masks the metrics use.
struct frame_reference {
  std::unique_ptr<scene> source;       ///< kept alive for `rays`
  std::unique_ptr<ray_scene> rays;
  rsm_pass_buffers buffers;            ///< RSM and G-buffer of the frame (the same for every gather setting)
  rsm_frame_constants constants;
  int stride = 1;
  image unoccluded;              ///< brute force, every lit texel, no visibility
  image exact;                   ///< brute force with ray-cast visibility
  image receivers;               ///< mask: covered (in front of the light, inside its frustum) and on the stride grid
  image leak;                    ///< mask: receivers where exact visibility removes >= 20 %
  std::size_t receiver_count = 0, leak_count = 0, uncovered_count = 0;
  double uncovered_share = 0.0;        ///< of the unoccluded light, on receivers not covered
  double occluded_share = 0.0;         ///< of the unoccluded light that exact visibility removes (receivers)
  double leak_occluded_share = 0.0;    ///< the same over the leak region
};

/// Renders `source` once with `settings` (only the frame's size, RSM size and format matter) and
/// computes the references. Exact visibility costs receivers x lit texels rays.
frame_reference make_frame_reference(const shader_library& shaders, const scene& source, const rsm_pipeline_settings& settings, int stride,
                                     int threads);

/// One markdown sentence on a reference: the receivers counted and not covered, the leak region,
/// and how much light exact visibility removes.
std::string describe(const frame_reference& reference);

/// `value` with `digits` decimals, and a fraction as a percentage with one decimal.
std::string fixed(double value, int digits);
std::string percent(double fraction);

/// The brute force cut to the pixel lights within `radius` RSM texels of each receiver's
/// projection (no visibility), on the reference's receivers.
image brute_force_within(const frame_reference& reference, float radius, int threads);

/// A technique's errors against the references, each the mean over the seeds.
struct technique_errors {
  relative_error raw_vs_unoccluded, raw_vs_exact, raw_leak, filtered_vs_exact, filtered_leak;
  double raw_noise = 0.0;  ///< relative RMSE of one seed against the mean of the seeds (unbiased for the seed count)
  image mean_raw;    ///< the raw gather averaged over the seeds
  image filtered_mean;  ///< the filtered indirect light at the receivers, averaged over the seeds
};

/// Renders `settings` (whose size and RSM size must be the reference's) with seeds 1..seeds.
technique_errors measure_technique(const shader_library& shaders, const scene& source, const rsm_pipeline_settings& settings,
                                   const frame_reference& reference, int seeds);

/// The radial pattern of `settings` with ray-cast visibility (CPU), mean over seeds 1..seeds.
image ray_cast_gather(const frame_reference& reference, const rsm_pipeline_settings& settings, int seeds, int threads);

/// Wall-clock ms of one frame of each configuration (median of `repeat`, interleaved: A B C A B C).
std::vector<double> interleaved_frame_ms(const shader_library& shaders, const scene& source, const std::vector<rsm_pipeline_settings>& configurations,
                                         int repeat);

}  // namespace vplkit
