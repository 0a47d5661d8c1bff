// Measuring the RSM gather against its ground truth (the brute-force gather of the same frame,
// [RSMV] Fig. 5.1d), for `vplkit sweep` and `vplkit render --reference rsm-brute-force`: the
// references of one frame, with and without exact visibility, the masks the metrics count, and a
// drawn frame's errors against them, raw and filtered. Every image here is at the indirect
// buffer's resolution, a vplkit::image (rows bottom-up, like the buffer).
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
/// stride-th receiver, every receiver with a surface (the light's first bounce reaches it whether
/// the pattern covers it or not), and the masks the metrics use.
struct frame_reference {
  std::unique_ptr<scene> source;       ///< kept alive for `rays`
  std::unique_ptr<ray_scene> rays;
  rsm_pass_buffers buffers;            ///< RSM and G-buffer of the frame (the same for every gather setting)
  rsm_frame_constants constants;        ///< light view 0's (buffers: its RSM)
  std::size_t views = 1;               ///< the frame's light views; unoccluded and exact sum them all
  int stride = 1;
  image unoccluded;              ///< brute force, every lit texel, no visibility
  image exact;                   ///< brute force with ray-cast visibility
  image receivers;               ///< mask: every receiver with a surface on the stride grid (what the metrics count)
  image covered;                 ///< mask: the receivers the pattern covers (in front of the light, projection inside the RSM)
  image uncovered;               ///< mask: the others, behind the light or projecting off the map (the coverage lights them)
  image leak;                    ///< mask: receivers where exact visibility removes >= 20 %
  std::size_t receiver_count = 0, leak_count = 0, uncovered_count = 0;  ///< uncovered_count of receiver_count
  double uncovered_share = 0.0;        ///< of the unoccluded light, on the receivers not covered
  double occluded_share = 0.0;         ///< of the unoccluded light that exact visibility removes (receivers)
  double leak_occluded_share = 0.0;    ///< the same over the leak region
};

/// Renders `source` once with `settings` (only the frame's size, RSM size, indirect divisor and
/// format matter) and computes the references. Exact visibility costs receivers x lit texels rays.
/// With a non-empty `cache` (a path prefix), the two brute-force images are read from
/// <cache>-unoccluded.pfm and <cache>-exact.pfm when both exist, and written there after they are
/// computed (cache_key names a frame).
frame_reference make_frame_reference(const shader_library& shaders, const scene& source, const rsm_pipeline_settings& settings, int stride,
                                     int threads, const std::string& cache = {});

/// A file-name-safe 64-bit FNV-1a hash of `text` in hex, for make_frame_reference's cache.
std::string cache_key(const std::string& text);

/// One sentence on a reference: the receivers counted and not covered, the leak region, and how
/// much light exact visibility removes.
std::string describe(const frame_reference& reference);

/// The brute force cut to the pixel lights within `radius` RSM texels of each receiver's
/// projection (no visibility), on the reference's receivers.
image brute_force_within(const frame_reference& reference, float radius, int threads);

/// A drawn frame's errors against the references.
struct frame_errors {
  relative_error raw_vs_unoccluded, raw_vs_exact, raw_leak, filtered_vs_exact, filtered_leak;
  relative_error raw_covered_vs_exact;      ///< over the receivers the pattern covers
  relative_error raw_uncovered_vs_unoccluded;  ///< over the others: what the coverage brings against what reaches them
  image raw;       ///< the gather's output at the receivers (0 for direct light only)
  image filtered;  ///< the filtered indirect light at the receivers' G-buffer texels
};

/// The errors of the frame `drawn` just drew (its size and RSM size must be the reference's).
frame_errors measure_frame(const rsm_pipeline& drawn, const frame_reference& reference);

/// The relative RMSE of one seed's raw gather against the mean of several seeds' (made unbiased
/// for the seed count): the sampling noise. 0 for fewer than two seeds; undefined (rmse not to be
/// read, see relative_error) when the seeds' mean is black on the receivers.
relative_error seed_noise(const std::vector<image>& raws, const frame_reference& reference);

/// The radial pattern of `settings` (its seed) with ray-cast visibility (CPU): the same samples
/// as the gather with exact visibility instead of the micro linear buffer.
image ray_cast_gather(const frame_reference& reference, const rsm_pipeline_settings& settings, int threads);

}  // namespace vplkit
