// The engine of `vplkit sweep`: a grid of settings (every --vary axis against every other) of one
// technique family on one or more scenes, each configuration timed per pass with the configurations
// interleaved in one process, repeated until the timing's noise is below a threshold, measured
// against a reference over several seeds, and written as one CSV row per configuration and scene
// (sweep_report.hpp writes the markdown and the plots). Everything the plan can check is checked
// before anything runs or is written: a setting no technique of the grid reads, a value out of its
// range, a configuration the family refuses.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "frontend/cli/options.hpp"
#include "frontend/cli/technique_options.hpp"
#include "frontend/reference/quality.hpp"

namespace vplkit::cli {

/// One axis of the grid: a setting and its values, or several settings whose values go together
/// (a zipped axis, `--vary paths:samples-per-path=15:10,20:15`), or `technique`.
struct sweep_axis {
  std::vector<std::string> names;
  std::vector<std::vector<std::string>> values;  ///< per point of the axis, one value per name
};

/// What a sweep is asked to do.
struct sweep_request {
  std::string title;       ///< the specification's section, or "" (sweep.md's heading)
  std::string command;     ///< the arguments, as sweep.md quotes them
  std::string technique;
  given_settings given;    ///< the base configuration: settings given without --vary
  common_options common;   ///< poses, shaders, context (scenes: `scenes`)
  std::vector<std::string> scenes;  ///< empty: the family's default scene
  std::vector<sweep_axis> axes;
  reference_options reference;
  std::string base_technique;  ///< --reference base: the base configuration's technique ("": --technique)
  int seeds = 1;               ///< quality over seeds 1..seeds (the techniques that read a seed)
  int repeat = 20;             ///< the most timing rounds
  int min_rounds = 3;          ///< the fewest
  double max_noise = 0.02;     ///< stop once every configuration's mean frame time has this relative standard error
  int group = 8;               ///< configurations timed interleaved at once (their pipelines live together)
  /// The most points the grid may have (the product of the axes' lengths, before configurations
  /// that a technique reads the same are merged): a larger grid is refused before it is planned.
  std::uint64_t max_configurations = 100000;
  std::filesystem::path out;
  /// --shard K/N: this run measures shard K of N (sweep_steps::owed_units); 1/1: every row.
  int shard = 1, shards = 1;
  /// The sweep's words without --out and --shard (and, for a section of a --spec, the
  /// section's words): what `vplkit sweep merge` plans the whole sweep from again.
  std::vector<std::string> arguments;
};

/// One configuration of the grid.
struct sweep_configuration {
  std::vector<std::string> axis_values;  ///< per axis column ("" where the technique does not read it)
  std::shared_ptr<const technique_settings> settings;
  std::string label;  ///< "radius=0.25 slots=8"
};

/// The checked plan: the configurations and the columns of their rows.
struct sweep_plan {
  const technique_family* family = nullptr;
  std::vector<std::string> axis_columns;  ///< the varied settings, flattened, `technique` excluded
  bool technique_axis = false;
  std::vector<sweep_configuration> configurations;
  std::vector<std::string> scenes;        ///< resolved: the family's default when none was given
  std::shared_ptr<const technique_settings> defaults;  ///< --technique with the given settings, before --vary
  std::shared_ptr<const technique_settings> base;      ///< --reference base's configuration
};

/// Expands and checks the grid. Throws usage_error (exit 2) naming what is wrong, a grid of more
/// than request.max_configurations points among it (counted without overflow, before planning).
sweep_plan plan_sweep(const sweep_request& request);

/// Runs the plan, skipping the configurations whose rows DIR/sweep.csv already holds, and writes
/// DIR/sweep.csv after every group of configurations, then sweep.md and the plots.
void run_sweep(const session& io, const sweep_request& request, const sweep_plan& plan);

/// DIR/sweep-shard.txt, written beside every sweep's sweep.csv: what `vplkit sweep merge`
/// needs to plan the sweep a folder belongs to again and to write its sweep.md.
struct sweep_record {
  std::vector<std::string> arguments;  ///< sweep_request::arguments
  std::string title, command;
  int shard = 1, shards = 1;
  std::string device, method, coverage;
};
void write_sweep_record(const std::filesystem::path& folder, const sweep_record& record);
/// Throws vplkit::error naming the folder when it holds no record, or one this writer did not write.
sweep_record read_sweep_record(const std::filesystem::path& folder);

/// `vplkit sweep merge`: the rows of the shards' folders (their records planned as `request` and
/// `plan`, whose out is the merged folder) in an unsharded run's order, written as one sweep.csv,
/// sweep.md and plots. Throws vplkit::error for a folder of another sweep, a shard given twice or
/// missing, or a row of the same key in two folders; warns (stderr and sweep.md) when the shards
/// ran on different machines.
void merge_sweep(const session& io, const sweep_request& request, const sweep_plan& plan, const std::vector<std::filesystem::path>& folders,
                 const std::vector<sweep_record>& records);

}  // namespace vplkit::cli
