#include "frontend/cli/sweep_engine.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <iostream>
#include <iomanip>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "frontend/cli/sweep_steps.hpp"
#include "frontend/core/error.hpp"
#include "frontend/core/files.hpp"
#include "frontend/core/parallel.hpp"
#include "frontend/core/text.hpp"
#include "frontend/gl/context.hpp"

namespace vplkit::cli {

namespace fs = std::filesystem;
using namespace sweep_steps;

namespace {

// Sets `values` (name, text) on `settings`: presets first, then the table's order; a setting the
// technique does not read is skipped. "" on success, else "<name> <why>".
std::string apply_values(technique_settings& settings, const std::vector<std::pair<std::string, std::string>>& values) {
  for (const bool first : {true, false})
    for (const setting_info* info : settings.settings())
      if (info->applies_first == first)
        for (const auto& [name, value] : values)
          if (name == info->name && settings.reads(name))
            if (const std::string why = settings.set(name, value); !why.empty()) return name + " " + why;
  return {};
}

std::string duration(double seconds) {
  const long whole = std::lround(std::max(0.0, seconds));
  std::ostringstream out;
  if (whole >= 3600) out << whole / 3600 << " h " << (whole % 3600) / 60 << " min";
  else if (whole >= 60) out << whole / 60 << " min " << whole % 60 << " s";
  else out << whole << " s";
  return out.str();
}

// Who reads `name`, when no technique of the grid does: the message of a usage error.
std::string unread_message(const std::string& option, const std::string& name, const std::vector<std::string>& techniques) {
  return option + ": " + name + " is read by " + setting_readers(name) + ", not by technique" + (techniques.size() > 1 ? "s " : " ") + joined(techniques, ", ");
}

// The number of points of the grid, refused past request.max_configurations before anything is
// planned (planning costs about 1.4 KB and 26 us a point). The product is checked step by step:
// 8 axes of 256 values wrapped to 0 in 64 bits and ran "0 configurations".
std::uint64_t grid_size(const sweep_request& request) {
  std::uint64_t points = 1;
  long double whole = 1.0L;  // the count when it does not fit in 64 bits, for the message
  bool fits = true;
  std::string factors;
  for (const sweep_axis& axis : request.axes) {
    const std::uint64_t length = axis.values.size();
    whole *= static_cast<long double>(length);
    if (fits && length != 0 && points > std::numeric_limits<std::uint64_t>::max() / length) fits = false;
    if (fits) points *= length;
    factors += (factors.empty() ? "" : " x ") + joined(axis.names, ":") + " (" + std::to_string(length) + ")";
  }
  if (fits && points <= request.max_configurations) return points;
  std::ostringstream count;
  if (fits) count << points;
  else count << "about " << std::setprecision(3) << static_cast<double>(whole);
  throw usage_error("--vary: the grid has " + count.str() + " configurations (" + factors + "), more than --max-configurations " +
                    std::to_string(request.max_configurations) + "; vary fewer values, split it into sections of a --spec, or raise --max-configurations");
}

}  // namespace

sweep_plan plan_sweep(const sweep_request& request) {
  sweep_plan plan;
  plan.family = &family_of(request.technique);
  const technique_family& family = *plan.family;
  std::vector<std::string> techniques = {request.technique};
  std::set<std::string> varied;
  for (const sweep_axis& axis : request.axes) {
    for (const std::string& name : axis.names)
      if (!varied.insert(name).second) throw usage_error("--vary " + name + " is given twice: one axis per setting");
    if (std::find(axis.names.begin(), axis.names.end(), "technique") == axis.names.end()) continue;
    if (axis.names.size() != 1) throw usage_error("--vary technique cannot be zipped with settings");
    techniques.clear();
    for (const std::vector<std::string>& point : axis.values) {
      if (!family.has(point[0]))
        throw usage_error("--vary technique=" + point[0] + ": not a technique of the " + family.name + " family of --technique " + request.technique + " (" +
                          joined(family.technique_names(), ", ") + ")");
      techniques.push_back(point[0]);
    }
    plan.technique_axis = true;
  }
  const std::uint64_t points = grid_size(request);
  // Every setting given or varied exists and some technique of the grid reads it.
  const auto check_name = [&](const std::string& option, const std::string& name) {
    const std::unique_ptr<technique_settings> probe = family.make_settings(techniques.front());
    if (!probe->find(name)) {
      if (setting_readers(name) != "no technique") throw usage_error(unread_message(option, name, techniques));
      std::vector<std::string> read;
      for (const std::string& technique : techniques) {
        const std::unique_ptr<technique_settings> settings = family.make_settings(technique);
        for (const setting_info* info : settings->settings())
          if (settings->reads(info->name) && std::find(read.begin(), read.end(), info->name) == read.end()) read.push_back(info->name);
      }
      throw usage_error(option + ": no setting '" + name + "'; technique" + (techniques.size() > 1 ? "s " : " ") + joined(techniques, ", ") +
                        " read" + (techniques.size() > 1 ? "" : "s") + ": " + joined(read, ", ") + " (and technique, to vary the technique)");
    }
    for (const std::string& technique : techniques)
      if (family.make_settings(technique)->reads(name)) return;
    throw usage_error(unread_message(option, name, techniques));
  };
  for (const sweep_axis& axis : request.axes)
    for (std::size_t n = 0; n < axis.names.size(); ++n) {
      const std::string& name = axis.names[n];
      if (name == "technique") continue;
      check_name("--vary " + name, name);
      plan.axis_columns.push_back(name);
      const std::unique_ptr<technique_settings> probe = family.make_settings(techniques.front());
      for (const std::vector<std::string>& point : axis.values)
        if (const std::string why = probe->find(name)->check(point[n]); !why.empty()) throw usage_error("--vary " + name + "=" + point[n] + ": " + name + " " + why);
    }
  for (const auto& [name, value] : request.given.values) check_name("--" + name, name);
  // Seeds, and the reference each technique can be measured against.
  bool seeded = false;
  for (const std::string& technique : techniques) seeded = seeded || family.make_settings(technique)->reads("seed");
  if (request.seeds > 1 && !seeded) throw usage_error("--seeds " + std::to_string(request.seeds) + ": technique " + joined(techniques, ", ") + " reads no seed");
  if (request.seeds > 1 && (request.given.find("seed") || varied.count("seed")))
    throw usage_error("--seeds sets the seed of each measurement (1 to N): give --seed or --seeds, not both");
  for (const std::string& technique : techniques)
    if (const std::string refusal = reference_refusal(request.reference.kind, technique); !refusal.empty())
      throw usage_error("--reference " + std::string(reference_name(request.reference.kind)) + ": " + refusal);
  // Scenes.
  // An empty name: the family's own room (final gathering without --scene).
  if (!family.takes_scene() && !request.scenes.empty())
    throw usage_error("--scene is read by the techniques that draw a scene, not by technique " + request.technique);
  plan.scenes = !request.scenes.empty() ? request.scenes : std::vector<std::string>{family.reads_scene() ? family.default_scene : std::string()};
  {
    std::shared_ptr<technique_settings> defaults = family.make_settings(request.technique);
    if (const std::string why = apply_values(*defaults, request.given.values); !why.empty()) throw usage_error(why);
    plan.defaults = defaults;
  }
  // The base configuration of --reference base.
  if (request.reference.kind == reference_kind::base) {
    const std::string base = request.base_technique.empty() ? request.technique : request.base_technique;
    if (!family.has(base)) throw usage_error("--base-technique " + base + ": not a technique of the " + family.name + " family");
    std::shared_ptr<technique_settings> settings = family.make_settings(base);
    if (const std::string why = apply_values(*settings, request.given.values); !why.empty()) throw usage_error("the base configuration: " + why);
    if (const std::string why = settings->validate(); !why.empty()) throw usage_error("the base configuration: " + why);
    plan.base = settings;
  }
  // The grid: every point of every axis against every other, deduplicated where a technique does
  // not read a varied setting.
  std::set<std::string> seen;
  for (std::uint64_t point = 0; point < points; ++point) {
    // The point's index on each axis, the last axis fastest.
    std::vector<std::size_t> index(request.axes.size(), 0);
    for (std::size_t a = request.axes.size(), rest = static_cast<std::size_t>(point); a-- > 0;) {
      index[a] = rest % request.axes[a].values.size();
      rest /= request.axes[a].values.size();
    }
    std::string technique = request.technique;
    std::vector<std::pair<std::string, std::string>> values = request.given.values;
    std::vector<std::string> labels;
    for (std::size_t a = 0; a < request.axes.size(); ++a) {
      const sweep_axis& axis = request.axes[a];
      for (std::size_t n = 0; n < axis.names.size(); ++n) {
        const std::string& value = axis.values[index[a]][n];
        if (axis.names[n] == "technique") {
          technique = value;
        } else {
          values.erase(std::remove_if(values.begin(), values.end(), [&](const auto& v) { return v.first == axis.names[n]; }), values.end());
          values.emplace_back(axis.names[n], value);
        }
      }
    }
    std::shared_ptr<technique_settings> settings = family.make_settings(technique);
    sweep_configuration configuration;
    for (const sweep_axis& axis : request.axes)
      for (std::size_t n = 0; n < axis.names.size(); ++n) {
        if (axis.names[n] == "technique") continue;
        const auto found = std::find_if(values.begin(), values.end(), [&](const auto& v) { return v.first == axis.names[n]; });
        const bool read = settings->reads(axis.names[n]);
        configuration.axis_values.push_back(read ? found->second : "");
        if (read) labels.push_back(axis.names[n] + "=" + found->second);
      }
    if (plan.technique_axis) labels.insert(labels.begin(), technique);
    configuration.label = labels.empty() ? technique : joined(labels, " ");
    if (const std::string why = apply_values(*settings, values); !why.empty()) throw usage_error("configuration " + configuration.label + ": " + why);
    if (const std::string why = settings->validate(); !why.empty()) throw usage_error("configuration " + configuration.label + ": " + why);
    if (seen.insert(identity(*settings)).second) {
      configuration.settings = settings;
      plan.configurations.push_back(std::move(configuration));
    }
  }
  return plan;
}

namespace {

// The progress line: how much of the work is done, and an estimate of what is left.
struct progress_report {
  const session& io;
  double total = 0.0, done = 0.0;
  std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();

  void operator()(const std::string& what) const {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    io.out << "sweep: " << fixed(total > 0.0 ? 100.0 * done / total : 100.0, 0) << " % " << what << "; " << duration(elapsed) << " so far";
    if (done > 0.0 && done < total) io.out << ", about " << duration(elapsed / done * (total - done)) << " left";
    io.out << std::endl;
  }
};

using pipeline_builder = std::function<std::unique_ptr<pipeline>(const technique_settings&)>;

// measure: the quality of one configuration at each seed, the timed pipeline drawing seed 1 (it
// was built with it) and a pipeline of its own each other seed.
seed_qualities measure_seeds(scene_references& references, pipeline& timed, const technique_settings& first_seed, int seeds, const pipeline_builder& build,
                             progress_report& progress) {
  seed_qualities measured;
  for (int seed = 1; seed <= seeds; ++seed) {
    std::unique_ptr<pipeline> other;
    pipeline* drawn = &timed;
    std::unique_ptr<technique_settings> settings = first_seed.clone();
    if (seed > 1) {
      settings->set("seed", std::to_string(seed));
      other = build(*settings);
      drawn = other.get();
    }
    drawn->draw();
    drawn->collect_pass_times();
    frame_quality quality = references.measure(*drawn, *settings);
    if (!quality.raw.texels.empty()) measured.raws.push_back(std::move(quality.raw));
    measured.seeds.push_back(std::move(quality));
    progress.done += 1.0;
  }
  return measured;
}

// The base configuration of --reference base at every seed the rows are measured with (once
// where it reads none), for the scene's references.
void draw_base(const sweep_keys& keys, scene_references& references, const pipeline_builder& build) {
  const int base_seeds = keys.seeds_of(*keys.plan.base);
  for (int seed = 1; seed <= base_seeds; ++seed) {
    std::unique_ptr<technique_settings> seeded_base = keys.plan.base->clone();
    if (base_seeds > 1) seeded_base->set("seed", std::to_string(seed));
    const std::unique_ptr<pipeline> base = build(*seeded_base);
    base->draw();
    references.set_base(base->output().read_image(), seeded_base->reads("seed") ? seeded_base->get("seed") : std::string());
    base->collect_pass_times();
  }
}

sweep_record record_of(const sweep_request& request, const sweep_context& context) {
  return {request.arguments, request.title, request.command, request.shard, request.shards, context.device, context.method, context.coverage};
}

// The warnings of the rows: the reference's noise (on stderr too), machines that differ.
std::vector<std::string> row_warnings(const sweep_table& table) {
  std::vector<std::string> warnings;
  if (const std::string noise = noise_warning(table); !noise.empty()) warnings.push_back(noise);
  std::set<std::string> machines;
  for (const auto& row : table.rows)
    if (row.count("machine") && !row.at("machine").empty()) machines.insert(row.at("machine"));
  if (machines.size() > 1)
    warnings.push_back("the rows were timed on " + std::to_string(machines.size()) + " machines (" + joined({machines.begin(), machines.end()}, "; ") +
                       "): frame_ms compares only within one machine (the column machine), and the Pareto front and ranks mix them");
  return warnings;
}

void finish(const session& io, const sweep_request& request, const sweep_plan& plan, sweep_table& table, sweep_context& context) {
  write_table(request.out / "sweep.csv", table, plan);
  context.warnings = row_warnings(table);
  for (const std::string& warning : context.warnings) std::cerr << "sweep: warning: " << warning << "\n";
  write_sweep_record(request.out, record_of(request, context));
  write_report(io, request, plan, table, context);
}

}  // namespace

namespace {

// What a run carries from step to step: the table (the rows there and the new ones), the context
// sweep.md reports, how a row is timed and keyed, and the progress.
struct sweep_run {
  const session& io;
  const sweep_request& request;
  const sweep_plan& plan;
  const headless_session& gl;
  sweep_keys keys;
  reference_options reference;  ///< request.reference with this machine's threads
  sweep_table table;
  sweep_context context;
  bool wall_clock = false;
  std::string machine;
  progress_report progress;
};

// plan: the rows this run (this shard) still owes, and the work for the estimate (per row one
// unit for its timing and one per seed).
std::vector<sweep_unit> plan_rows(sweep_run& run) {
  std::set<std::string> done;
  for (const auto& row : run.table.rows) done.insert(row.count("key") ? row.at("key") : std::string());
  std::vector<sweep_unit> owed = owed_units(run.keys, done);
  for (const sweep_unit& unit : owed) run.progress.total += 1.0 + run.keys.seeds_of(*unit.configuration->settings);
  if (run.context.resumed > 0)
    run.io.out << "sweep: resuming " << (run.request.out / "sweep.csv").string() << ": " << run.context.resumed << " row(s) already there are kept\n";
  if (run.request.shards > 1) run.io.out << "sweep: shard " << run.request.shard << "/" << run.request.shards << ": " << owed.size() << " row(s) to measure\n";
  return owed;
}

// One group of configurations of a scene, built at their first seed, a warm-up frame each (the
// shader compilers' lazy work).
struct timed_group {
  std::vector<const sweep_unit*> units;
  std::vector<std::unique_ptr<technique_settings>> seeded;
  std::vector<std::unique_ptr<pipeline>> pipelines;
  std::vector<timing> timings;
};

// time: the group's pipelines timed interleaved.
timed_group time_rows(sweep_run& run, const std::vector<const sweep_unit*>& units, const pipeline_builder& build) {
  timed_group group;
  group.units = units;
  std::vector<pipeline*> drawn;
  for (const sweep_unit* unit : units) {
    group.seeded.push_back(unit->configuration->settings->clone());
    if (run.keys.seeds_of(*group.seeded.back()) > 1) group.seeded.back()->set("seed", "1");
    group.pipelines.push_back(build(*group.seeded.back()));
    group.pipelines.back()->draw();
    group.pipelines.back()->collect_pass_times();
    drawn.push_back(group.pipelines.back().get());
  }
  group.timings = time_group(run.request, drawn);
  run.progress.done += static_cast<double>(units.size());
  const std::string& scene = run.plan.scenes[units.front()->scene_index];
  run.progress("timed " + std::to_string(units.size()) + " configuration(s) of " + (scene.empty() ? run.plan.family->name : sweep_keys::shown_scene(scene)) +
               " in " + std::to_string(group.timings.front().rounds) + " round(s)");
  return group;
}

// measure: the group's i-th configuration against the reference, seed by seed, into its row.
std::map<std::string, std::string> measure_row(sweep_run& run, timed_group& group, std::size_t i, scene_references& references, const pipeline_builder& build) {
  const sweep_unit& unit = *group.units[i];
  const sweep_configuration& configuration = *unit.configuration;
  const std::string scene = run.keys.scene_of(configuration, unit.scene_index);
  const bool measured = run.request.reference.kind != reference_kind::none;
  sweep_table& table = run.table;
  std::map<std::string, std::string> row;
  row["scene"] = sweep_keys::shown_scene(scene);
  row["technique"] = configuration.settings->technique();
  for (std::size_t a = 0; a < run.plan.axis_columns.size(); ++a) row[run.plan.axis_columns[a]] = configuration.axis_values[a];
  timing_columns(table, row, group.timings[i], run.request, run.wall_clock, run.machine);
  for (const char* column : {"receivers", "seeds", "key"}) table.add_column(column);
  const int seeds = run.keys.seeds_of(*configuration.settings);
  double share = -1.0;
  if (measured) {
    const seed_qualities qualities = measure_seeds(references, *group.pipelines[i], *group.seeded[i], seeds, build, run.progress);
    share = quality_columns(table, row, qualities, references, *group.seeded[i]);
    row["receivers"] = std::to_string(qualities.seeds.back().receivers);
    run.context.coverage = references.coverage();
  } else {
    run.progress.done += static_cast<double>(seeds);
  }
  row["seeds"] = std::to_string(measured ? seeds : 0);
  row["key"] = run.keys.key_of(configuration, unit.scene_index);
  if (run.plan.base) {
    table.add_column("is_base");
    row["is_base"] = identity(*configuration.settings) == identity(*run.plan.base) ? "1" : "0";
  }
  std::string summary = row["scene"] + ": " + configuration.label + ": " + fixed(of(group.timings[i].frames).mean, 2) + " ms";
  for (const char* name : {"rel_rmse", "rel_bias"})
    if (row.count(name)) summary += std::string(", ") + name + " " + (row[name] == "undefined" ? std::string("undefined") : fixed(*parse_real(row[name]), 4));
  if (share >= 0.0) summary += ", reference noise " + fixed(100.0 * share, 0) + " % of rel_rmse";
  run.progress(summary);
  return row;
}

}  // namespace

void run_sweep(const session& io, const sweep_request& request, const sweep_plan& plan) {
  fs::create_directories(request.out);
  const headless_session gl(request.common);
  sweep_run run{io, request, plan, gl, sweep_keys{request, plan}, request.reference, {}, {}, false, {}, progress_report{io}};
  run.reference.threads = hardware_threads();
  if (fs::exists(request.out / "sweep.csv")) run.table = read_sweep_csv(request.out / "sweep.csv");
  for (const char* column : {"scene", "technique"}) run.table.add_column(column);
  for (const std::string& column : plan.axis_columns) run.table.add_column(column);
  run.context.method = describe(timing_method_for_current_context());
  run.context.device = describe_current_context();
  run.context.coverage = scene_references(gl.shaders, run.reference, nullptr).coverage();
  run.context.resumed = run.table.rows.size();
  run.wall_clock = timing_method_for_current_context() == timing_method::wall_clock;
  run.machine = machine_name(run.context.device);
  write_sweep_record(request.out, record_of(request, run.context));

  const std::vector<sweep_unit> owed = plan_rows(run);
  const technique_family& family = *plan.family;
  for (std::size_t scene_index = 0; scene_index < plan.scenes.size(); ++scene_index) {
    std::vector<const sweep_unit*> pending;
    for (const sweep_unit& unit : owed)
      if (unit.scene_index == scene_index) pending.push_back(&unit);
    if (pending.empty()) continue;
    std::unique_ptr<scene> source;
    if (!plan.scenes[scene_index].empty()) source = std::make_unique<scene>(load_scene(request.common, plan.scenes[scene_index]));
    scene_references references(gl.shaders, run.reference, source.get());
    const pipeline_builder build = [&](const technique_settings& settings) {
      std::unique_ptr<scene> none;
      return source ? family.make_pipeline(gl.shaders, source.get(), settings) : make_posed_pipeline(gl.shaders, request.common, settings, none);
    };
    if (plan.base) draw_base(run.keys, references, build);
    for (std::size_t first = 0; first < pending.size(); first += static_cast<std::size_t>(request.group)) {
      const std::size_t last = std::min(pending.size(), first + static_cast<std::size_t>(request.group));
      timed_group group = time_rows(run, {pending.begin() + static_cast<std::ptrdiff_t>(first), pending.begin() + static_cast<std::ptrdiff_t>(last)}, build);
      for (std::size_t i = 0; i < group.units.size(); ++i) run.table.rows.push_back(measure_row(run, group, i, references, build));
      // write: the CSV after every group, so that a stopped sweep resumes from here.
      write_table(request.out / "sweep.csv", run.table, plan);
    }
  }
  finish(io, request, plan, run.table, run.context);
}

void merge_sweep(const session& io, const sweep_request& request, const sweep_plan& plan, const std::vector<fs::path>& folders,
                 const std::vector<sweep_record>& records) {
  // Every shard of the sweep once.
  const int shards = records.front().shards;
  std::map<int, fs::path> shard_folders;
  for (std::size_t i = 0; i < records.size(); ++i) {
    if (records[i].shards != shards)
      throw error(folders[i].string() + " is shard " + std::to_string(records[i].shard) + "/" + std::to_string(records[i].shards) + ", " + folders[0].string() +
                  " one of " + std::to_string(shards) + ": shards of one sweep split it the same number of ways");
    const auto [where, fresh] = shard_folders.emplace(records[i].shard, folders[i]);
    if (!fresh) throw error("shard " + std::to_string(records[i].shard) + "/" + std::to_string(shards) + " is given twice: " + where->second.string() + " and " + folders[i].string());
  }
  std::vector<std::string> missing;
  for (int k = 1; k <= shards; ++k)
    if (!shard_folders.count(k)) missing.push_back(std::to_string(k) + "/" + std::to_string(shards));
  if (!missing.empty()) throw error("shard " + joined(missing, ", ") + " is missing: give the folder of every shard of the sweep");
  // The rows in the order of an unsharded run: by the plan's units (scene by scene).
  sweep_request whole = request;
  whole.shard = whole.shards = 1;
  const sweep_keys keys{whole, plan};
  std::map<std::string, std::size_t> order;
  for (const sweep_unit& unit : owed_units(keys, {})) order.emplace(keys.key_of(*unit.configuration, unit.scene_index), order.size());
  sweep_table table;
  for (const char* column : {"scene", "technique"}) table.add_column(column);
  for (const std::string& column : plan.axis_columns) table.add_column(column);
  std::map<std::size_t, std::map<std::string, std::string>> rows;
  for (const fs::path& folder : folders) {
    const sweep_table shard = read_sweep_csv(folder / "sweep.csv");
    for (const std::string& column : shard.columns) table.add_column(column);
    for (const auto& row : shard.rows) {
      const auto place = order.find(row.count("key") ? row.at("key") : std::string());
      if (place == order.end())
        throw error(folder.string() + "/sweep.csv holds a row (" + row.at("scene") + " " + row.at("technique") + ") that its sweep's plan does not: the shard's CSV is not this sweep's");
      if (!rows.emplace(place->second, row).second) throw error(folder.string() + "/sweep.csv holds the row " + row.at("key") + " a shard before it holds too");
    }
  }
  for (auto& [place, row] : rows) table.rows.push_back(std::move(row));
  if (table.rows.size() < order.size())
    std::cerr << "sweep merge: warning: " << order.size() - table.rows.size() << " of " << order.size()
              << " row(s) are not in any shard's CSV (a shard that stopped early): run that shard again to resume it, then merge again\n";
  // The context of the shard holding the unsharded run's last row (its coverage names the
  // references the last scene made), the device of every shard in the warning when they differ.
  sweep_context context;
  const std::size_t last_shard = order.empty() ? 1 : (order.size() - 1) % static_cast<std::size_t>(shards) + 1;
  for (const sweep_record& record : records)
    if (record.shard == static_cast<int>(last_shard)) {
      context.device = record.device;
      context.method = record.method;
      context.coverage = record.coverage;
    }
  fs::create_directories(request.out);
  io.out << "sweep merge: " << table.rows.size() << " row(s) of " << shards << " shard(s) into " << request.out.string() << "\n";
  finish(io, whole, plan, table, context);
}

}  // namespace vplkit::cli
