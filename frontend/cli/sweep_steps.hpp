// The steps of `vplkit sweep` (sweep_engine.hpp), for the engine's files only: run_sweep is
// plan (which configurations of which scene this run, or this shard, still owes), time (a group
// of them interleaved), measure (each against the reference, seed by seed, into its row) and
// write (sweep.csv after every group; sweep.md and the plots at the end). `vplkit sweep merge`
// reuses the plan (the row order of an unsharded run) and the write step.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "frontend/cli/sweep_engine.hpp"
#include "frontend/cli/sweep_report.hpp"

namespace vplkit::cli::sweep_steps {

std::string joined(const std::vector<std::string>& items, const std::string& separator);
/// The settings in effect as one line: the configuration's identity.
std::string identity(const technique_settings& settings);
/// FNV-1a, 64 bits, as hex.
std::string hashed(const std::string& text);
/// Lower-case letters and digits, other runs as one '_' (a pass's or a column's file name).
std::string slug(const std::string& text);
std::string number_text(double value);

struct statistics {
  double mean = 0.0, sd = 0.0;
};
statistics of(const std::vector<double>& values);

/// One row a sweep owes: a configuration on a scene, at its place in an unsharded run's order.
struct sweep_unit {
  const sweep_configuration* configuration = nullptr;
  std::size_t scene_index = 0;
  std::size_t configuration_index = 0;
};

/// The rows' keys and scenes, as every step names them.
struct sweep_keys {
  const sweep_request& request;
  const sweep_plan& plan;
  /// Seeds a configuration is measured with (1 for a technique without a seed).
  int seeds_of(const technique_settings& settings) const;
  /// The scene as the command line named it (a file's path: the key's), for plan.scenes[index].
  std::string scene_of(const sweep_configuration& configuration, std::size_t scene_index) const;
  /// The scene as the rows show it (a file's stem).
  static std::string shown_scene(const std::string& scene);
  /// The key of a row: configuration, scene, reference and seeds.
  std::string key_of(const sweep_configuration& configuration, std::size_t scene_index) const;
};

/// plan: the units of shard K of N (every unit u of the unsharded order, scene by scene, with
/// u mod N = K - 1: the same split on every machine), without the ones whose key is in `done`.
std::vector<sweep_unit> owed_units(const sweep_keys& keys, const std::set<std::string>& done);

/// What one configuration's timing collected.
struct timing {
  std::vector<double> frames;                         // total of the passes, per round
  std::map<std::string, std::vector<double>> passes;  // per pass, per round
  std::vector<std::string> pass_order;
  int rounds = 0;
  /// The mean frame time's relative standard error (1 with fewer than two rounds).
  double noise() const;
};

/// time: draws every pipeline round after round (A B C A B C ...) until each mean's noise is
/// below request.max_noise (at least min_rounds, at most repeat rounds).
std::vector<timing> time_group(const sweep_request& request, const std::vector<pipeline*>& pipelines);

/// The timing columns of a row (frame_ms, its spread and noise, rounds, the passes, machine).
void timing_columns(sweep_table& table, std::map<std::string, std::string>& row, const timing& measured, const sweep_request& request, bool wall_clock,
                    const std::string& machine);

/// The quality of one configuration at each seed (what measure collects before the row).
struct seed_qualities {
  std::vector<frame_quality> seeds;
  std::vector<image> raws;  ///< rsm-brute-force: the raw gathers, for the noise over seeds
};

/// measure: the quality columns of a row from its seeds: per metric the mean, and over several
/// seeds each seed's value, the spread, the worst seed and its value; the reference's standard
/// error, its noise and the corrected rel_rmse where the reference is stochastic; "undefined"
/// with the reason where a seed's is. Returns the row's ref_noise_share (or a negative number).
double quality_columns(sweep_table& table, std::map<std::string, std::string>& row, const seed_qualities& measured, scene_references& references,
                       const technique_settings& first_seed);

/// The warning threshold: the reference's noise above this fraction of a row's rel_rmse.
inline constexpr double noise_share_warning = 0.10;

/// write: sweep.csv with the Pareto front (within the noise), the ties and the family's rank
/// against the base configuration, its columns in order (scene, technique, the varied
/// settings, the timing, the passes, the quality, the bookkeeping), atomically.
void write_table(const std::filesystem::path& path, sweep_table& table, const sweep_plan& plan);

/// What sweep.md says about where and how it was timed and measured.
struct sweep_context {
  std::string device, method, coverage;
  std::size_t resumed = 0;
  std::vector<std::string> warnings;  ///< each a paragraph (the reference's noise, mixed machines)
};

/// write: the plots (a gnuplot plot per varied setting and the Pareto front) and sweep.md, and
/// the lines naming them on io.out.
void write_report(const session& io, const sweep_request& request, const sweep_plan& plan, const sweep_table& table, const sweep_context& context);

/// The warning (one line, "" for none) when rows' ref_noise_share exceeds noise_share_warning.
std::string noise_warning(const sweep_table& table);

/// The machine a row ran on: the host's name and the GL renderer.
std::string machine_name(const std::string& device);

}  // namespace vplkit::cli::sweep_steps
