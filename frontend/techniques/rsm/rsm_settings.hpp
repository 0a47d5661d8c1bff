// The RSM family's settings: its techniques, the settings struct with the thesis's configuration
// as the defaults, the table every option, control and sweep axis comes from
// (frontend/core/setting.hpp), validate() and the one derive() both validation and the frame use.
// No GL: the pipeline (rsm_pipeline.hpp) draws what these describe.
#pragma once

#include <string>
#include <vector>

#include <vplkit/bilateral.hpp>
#include <vplkit/irradiance.hpp>
#include <vplkit/rsm_gather.hpp>
#include <vplkit/shadow.hpp>
#include <vplkit/temporal_accumulation.hpp>
#include <vplkit/voxel_visibility.hpp>

#include "frontend/core/setting.hpp"
#include "frontend/gl/render_target.hpp"

namespace vplkit {

/// A technique the pipeline renders.
struct rsm_technique {
  const char* name = "";     ///< CLI name, e.g. "rsm-alg6"
  bool indirect = false;     ///< false: direct light only
  rsm_pattern pattern = rsm_pattern::radial;
  rsm_visibility visibility = rsm_visibility::none;
  const char* description = "";
};

/// direct, rsm-original, rsm-radial, rsm-alg2, rsm-alg3, rsm-alg6.
const std::vector<rsm_technique>& rsm_techniques();
/// Throws vplkit::error listing the names when `name` is unknown.
const rsm_technique& find_rsm_technique(const std::string& name);

enum class post_filter { full, separable };

/// Every setting of the pipeline, with the thesis's configuration as the defaults.
struct rsm_pipeline_settings {
  int width = 512;              ///< final image (the thesis: 512 x 512)
  int height = 512;
  int rsm_size = 512;           ///< square RSM (the thesis: 512 x 512)
  int indirect_divisor = 2;     ///< indirect buffer = image / divisor per axis (2: 256^2, 1: Table 5.2's 512^2)
  texel_format format = texel_format::rgba16f;  ///< G-buffer, indirect and output targets: rgba16f (the thesis) or rgba32f; the RSM is packed (RGBA32UI)
  std::string technique = "rsm-alg6";
  /// r_max of the radial and disk patterns as a fraction of the RSM side, so the radius scales
  /// with the RSM; make_rsm_gather_settings derives it in texels.
  float radius = default_rsm_gather_preset<float>().radius_fraction;
  /// Paths x samples of the default preset; max_radius is not read (see radius).
  radial_pattern_settings<float> radial = default_radial_settings();
  disk_pattern_settings<float> disk;            ///< 400 samples; max_radius is not read (see radius)
  int slots = default_rsm_gather_preset<float>().slots;  ///< micro linear buffer slots
  /// Coarse lights per side of the RSM for the receivers the pattern cannot reach (behind the
  /// light, off the map; vplkit/rsm_coverage.hpp); 0: none, as in the thesis.
  int coverage_blocks = default_coverage_blocks;
  /// Side of the pixel tile the coverage's blocks are interleaved over (each receiver gathers
  /// 1 / side^2 of them, the post filter averages the tile); 1: every receiver every block.
  int coverage_interleave = default_coverage_interleave;
  irradiance_settings<float> irradiance;
  shadow_density_settings<float> shadow;
  bilateral_settings<float> bilateral;          ///< kernel 17
  /// Separable by default: 2 x 17 taps instead of 17^2, 7x cheaper on llvmpipe for a few percent
  /// of difference in the filtered indirect light (bench/rsm-tables.sweep measures both).
  post_filter filter = post_filter::separable;
  /// Temporal accumulation of the frames of a sequence (render_next; vplkit/temporal_accumulation.hpp);
  /// blend 1 keeps no history (and the pattern does not turn between frames).
  temporal_settings<float> temporal;
  /// rsm-voxel: the scene's occupancy grid (built on the CPU when the pipeline is made: the scene's
  /// triangles are fixed for its life) and the march's offsets (vplkit/voxel_visibility.hpp).
  voxel_grid_settings<float> voxel_grid;
  voxel_march_settings<float> voxel_march;

  static radial_pattern_settings<float> default_radial_settings() {
    radial_pattern_settings<float> radial;
    radial.paths = default_rsm_gather_preset<float>().paths;
    radial.samples_per_path = default_rsm_gather_preset<float>().samples_per_path;
    return radial;
  }
  // A preset (default_rsm_gather_preset, thesis_rsm_gather_preset) sets radius, paths, samples
  // and slots through the table's entries (rsm_settings_table's "preset").
};

/// The description of every setting a user sets (frontend/core/setting.hpp): the options of
/// `vplkit render`, the viewer's controls, the sweep's axes.
const std::vector<setting<rsm_pipeline_settings, rsm_technique>>& rsm_settings_table();

/// What the frame's kernels read that is derived from the settings, derived here once: the
/// gather's uniforms (make_rsm_gather_settings: the radius in texels, the pattern constants, the
/// slots) and the radial pattern with that radius. validate() checks it, make_frame_constants
/// uploads it; perspective stays to be set per light.
struct rsm_derived_settings {
  rsm_gather_settings<float> gather;
  radial_pattern_settings<float> radial;  ///< settings.radial with max_radius = the radius in texels
};
/// Settings whose ranges check_settings accepted (no division by a zero count).
rsm_derived_settings derive(const rsm_pipeline_settings& settings);

/// Empty when usable, else a message naming the bad setting: the table's ranges, then the
/// kernels' settings as derive() makes them (the patterns with their radius in texels, slots,
/// shadow, filter).
std::string validate(const rsm_pipeline_settings& settings);

}  // namespace vplkit
