// A drawn frame's quality against a reference, for `vplkit sweep` and `vplkit render
// --reference`: like with like, on the receivers the reference covers.
// - rsm-brute-force (RSM techniques): the raw gather against the brute-force gather of the same
//   RSM and G-buffer with exact (ray-cast) visibility, on every stride-th receiver of the
//   indirect buffer that the gather covers (rsm_measure.hpp); also against the brute force
//   without visibility, over the leak region (receivers where exact visibility removes >= 20 %),
//   after the post filter, and the error split: the radius (the brute force cut to the radius
//   against all texels), the visibility approximation (the gather against its own samples ray
//   cast, Alg. 2/3/6) and, over seeds, the sampling noise.
// - monte-carlo: the final image against the one-bounce Monte Carlo image of the same scene,
//   camera and size (every pixel; Alg. 1 similarity as Light Wave measures images); for final
//   gathering, the object's indirect irradiance against one bounce from the room (its own
//   cube map leaves the object out) at the object's pixels.
// - base: the final image against the base configuration's at the same seed (Light Wave's %
//   similar to the default, Tables 5.5-5.9), a smaller image stretched to the base's size
//   (Table 5.7).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "frontend/core/setting.hpp"
#include <vplkit/gl/program.hpp>
#include "frontend/image/image.hpp"
#include "frontend/reference/rsm_measure.hpp"
#include "frontend/techniques/pipeline.hpp"

namespace vplkit {

enum class reference_kind { none, rsm_brute_force, monte_carlo, base };

/// "none", "rsm-brute-force", "monte-carlo", "base".
const char* reference_name(reference_kind kind);
/// The kind called `name`; throws vplkit::error for another name.
reference_kind reference_from_name(const std::string& name);

struct reference_options {
  reference_kind kind = reference_kind::none;
  int receiver_stride = 4;    ///< rsm-brute-force: every stride-th receiver per axis
  int samples = 64;           ///< monte-carlo: bounce rays per pixel
  std::uint32_t seed = 1;     ///< monte-carlo: the estimate's seed
  int threads = 1;
};

/// "" when `kind` measures `technique`, else why not (the brute force is the RSM gather's).
std::string reference_refusal(reference_kind kind, const std::string& technique);

/// One named number of a frame's quality. A relative number against a black reference does not
/// exist (relative_error::defined): `defined` is false, `value` is not to be read, and
/// `why_undefined` says why; writers show "undefined" with the reason, and a sweep never ranks it.
struct quality_metric {
  std::string name;
  double value = 0.0;
  bool defined = true;
  std::string why_undefined;
  /// Similarity and SSIM: a larger value is the better one (the worst seed is the smallest).
  bool higher_is_better = false;
  /// Against a stochastic reference (Monte Carlo): the standard error of `value` that the
  /// reference's own noise causes (frontend/image/reference_noise.hpp); negative: not estimated.
  double reference_se = -1.0;
};

/// Named numbers of one drawn frame against the reference, in a fixed order per kind.
struct frame_quality {
  std::vector<quality_metric> metrics;
  std::size_t receivers = 0;  ///< the pixels or receivers the metrics count
  /// Against a stochastic reference: its own noise as a rel_rmse (what a perfect image scores),
  /// estimated from a second reference of another seed; negative: the reference is exact (the
  /// brute force computes every lit texel; its stride subsamples receivers, not the estimate) or
  /// the noise is not defined.
  double reference_noise = -1.0;
  image raw;                  ///< rsm-brute-force: the raw gather (for the noise over seeds)
};

/// The references of one scene, each computed when first needed and kept for every frame that
/// shares it (the brute force per frame size, RSM size, divisor, format and distance clamp; the
/// Monte Carlo image per size).
class scene_references {
 public:
  /// `source`: the scene the frames draw (null for final gathering, which builds its own).
  scene_references(const shader_library& shaders, reference_options options, const scene* source);
  ~scene_references();
  /// The quality of the frame `drawn` has just drawn with `settings` (after draw()).
  frame_quality measure(pipeline& drawn, const technique_settings& settings);
  /// The base configuration's final image at `seed` (kind base): a frame is compared with the
  /// base drawn with its own seed where the base has one, so that the seeds' noise is not counted.
  void set_base(image radiance, const std::string& seed = "") { bases_[seed] = std::move(radiance); }
  /// The noise of several seeds' raw gathers of one configuration (rsm-brute-force), else 0;
  /// undefined (relative to the seeds' mean gather) when that mean is black on the receivers.
  quality_metric seed_noise(const std::vector<image>& raws, const technique_settings& settings);
  /// What the metrics cover and count, one paragraph (markdown), for the references made so far.
  std::string coverage() const;
  const reference_options& options() const { return options_; }

 private:
  const frame_reference& brute_force(const technique_settings& settings);
  const image& monte_carlo(int width, int height);
  /// A second, independent Monte Carlo reference (seed + 1): the first's noise is estimated
  /// from the two (frontend/image/reference_noise.hpp).
  const image& monte_carlo_second(int width, int height);

  const shader_library& shaders_;
  reference_options options_;
  const scene* source_;
  std::map<std::string, std::unique_ptr<frame_reference>> brute_forces_;
  std::map<std::string, image> radius_cuts_;
  std::map<std::string, image> monte_carlo_;
  std::map<std::string, image> monte_carlo_second_;
  std::size_t last_receivers_ = 0;
  std::map<std::string, image> bases_;  ///< by seed ("": a base without one)
};

}  // namespace vplkit
