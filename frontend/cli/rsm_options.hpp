// The RSM techniques of `vplkit render` and `vplkit view` ([RSMV]: direct, rsm-original,
// rsm-radial, rsm-alg2, rsm-alg3, rsm-alg6): their options, each scoped to the techniques that
// read it, the pipeline settings made from them, and the images `render` writes.
#pragma once

#include <optional>
#include <string>

#include "frontend/cli/options.hpp"
#include "frontend/techniques/rsm/rsm_pipeline.hpp"

namespace vplkit::cli {

struct rsm_options {
  int rsm_size = rsm_pipeline_settings().rsm_size;
  int indirect_divisor = rsm_pipeline_settings().indirect_divisor;
  std::string preset = "default";  ///< rsm_gather_preset: "default" or "thesis"
  std::optional<int> paths, samples_per_path, slots;  ///< explicit values override the preset
  std::optional<float> radius, max_radius_texels;
  int disk_samples = rsm_pipeline_settings().disk.samples;
  std::string disk_weights = "unbiased";  ///< rsm-original: "unbiased" or "printed" (the original's xi1^2)
  int coverage_blocks = default_coverage_blocks;  ///< coarse lights per RSM side for what the pattern cannot reach (0: none)
  std::string filter = "separable";
  bool raw_indirect = false;
  std::string poses;  ///< render --poses: a pose file, one frame per line
  std::optional<float> temporal_blend;  ///< --poses: weight of each new frame (1: no accumulation) [rsm_pipeline_settings]
};

/// Whether `technique` is one of the RSM family.
bool is_rsm_technique(const std::string& technique);

/// --rsm-size and --indirect-divisor: the frame's RSM and indirect buffer (what the brute-force
/// reference needs as well). `only_indirect`: scope --indirect-divisor to the techniques that
/// gather indirect light (render and view); null for a command that always reads it.
void add_rsm_frame_options(CLI::App& command, rsm_options& options, option_scope* only_indirect);

/// The gather's options (--preset, --paths, --samples-per-path, --radius, --max-radius, --slots,
/// --disk-samples, --disk-weights, --coverage-blocks, --post-filter, and --raw-indirect when
/// `with_raw_indirect`),
/// each scoped to the RSM techniques that read it.
void add_rsm_gather_options(CLI::App& command, rsm_options& options, option_scope& scope, bool with_raw_indirect);

/// --poses FILE and --temporal-blend (render only), scoped to the RSM techniques.
void add_rsm_sequence_options(CLI::App& command, rsm_options& options, option_scope& scope);

/// The pipeline settings for `technique`: the preset, then the explicit values. Throws
/// usage_error for contradictory options and for settings rsm_pipeline rejects.
rsm_pipeline_settings make_rsm_settings(const std::string& technique, const common_options& common, const rsm_options& options);

/// `vplkit render` for an RSM technique: the final image, the filtered indirect irradiance
/// (PNG and linear PFM), the visibility difference (Fig. 5.1c) for Alg. 2/3/6, and
/// <out>-raw-indirect.pfm with --raw-indirect. With --poses, a sequence in one pipeline instead:
/// frame i (from 1) of the pose file as <out>-NNNN.png and <out>-NNNN-indirect.pfm (and
/// -NNNN-raw-indirect.pfm), every frame rendered before any file is written.
int render_rsm(const session& io, const std::string& technique, const common_options& common, const rsm_options& options, const std::string& out);

}  // namespace vplkit::cli
