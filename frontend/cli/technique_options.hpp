// What `render` and `view` share: --technique over the three families, --scene, the common
// options, --camera/--light, --seed, and each family's options, each scoped to the techniques
// that read it (registered once here so that both commands accept and refuse the same options).
#pragma once

#include <string>

#include "frontend/cli/final_gather_options.hpp"
#include "frontend/cli/lightwave_options.hpp"
#include "frontend/cli/options.hpp"
#include "frontend/cli/rsm_options.hpp"

namespace vplkit::cli {

struct technique_options {
  std::string technique = rsm_pipeline_settings().technique;
  common_options common;
  rsm_options rsm;
  lightwave_options lightwave;
  final_gather_options final_gather;
  option_scope scope;
};

/// Registers the options above on `command`. `with_raw_indirect`: --raw-indirect (render only).
void add_technique_options(CLI::App& command, technique_options& options, bool with_raw_indirect);

}  // namespace vplkit::cli
