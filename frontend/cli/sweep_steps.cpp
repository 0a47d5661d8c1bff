// The plan, time and measure steps of `vplkit sweep` (sweep_steps.hpp).
#include "frontend/cli/sweep_steps.hpp"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "frontend/core/setting.hpp"

namespace vplkit::cli::sweep_steps {

namespace fs = std::filesystem;

std::string joined(const std::vector<std::string>& items, const std::string& separator) {
  std::string all;
  for (const std::string& item : items) all += (all.empty() ? "" : separator) + item;
  return all;
}

std::string identity(const technique_settings& settings) {
  std::string text = "technique=" + settings.technique();
  for (const auto& [name, value] : settings_in_effect(settings)) text += ";" + name + "=" + value;
  return text;
}

std::string hashed(const std::string& text) {
  std::uint64_t hash = 1469598103934665603ull;
  for (char c : text) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 1099511628211ull;
  }
  std::ostringstream out;
  out << std::hex << std::setw(16) << std::setfill('0') << hash;
  return out.str();
}

std::string slug(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (std::isalnum(static_cast<unsigned char>(c))) out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    else if (!out.empty() && out.back() != '_') out += '_';
  }
  while (!out.empty() && out.back() == '_') out.pop_back();
  return out;
}

std::string number_text(double value) { return std::isfinite(value) ? format_real(value) : std::string(); }

statistics of(const std::vector<double>& values) {
  statistics s;
  if (values.empty()) return s;
  for (double v : values) s.mean += v / static_cast<double>(values.size());
  if (values.size() > 1) {
    double squares = 0.0;
    for (double v : values) squares += (v - s.mean) * (v - s.mean);
    s.sd = std::sqrt(squares / static_cast<double>(values.size() - 1));
  }
  return s;
}

int sweep_keys::seeds_of(const technique_settings& settings) const { return settings.reads("seed") ? request.seeds : 1; }

std::string sweep_keys::scene_of(const sweep_configuration& configuration, std::size_t scene_index) const {
  return !plan.scenes[scene_index].empty() ? plan.scenes[scene_index] : drawn_scene_name(request.common, *configuration.settings);
}

std::string sweep_keys::shown_scene(const std::string& scene) { return fs::path(scene).stem().string(); }

std::string sweep_keys::key_of(const sweep_configuration& configuration, std::size_t scene_index) const {
  const reference_options& reference = request.reference;
  return hashed(identity(*configuration.settings) + "|scene=" + scene_of(configuration, scene_index) + "|reference=" + reference_name(reference.kind) +
                "|stride=" + std::to_string(reference.receiver_stride) + "|samples=" + std::to_string(reference.samples) +
                "|seeds=" + std::to_string(seeds_of(*configuration.settings)) + (plan.base ? "|base=" + identity(*plan.base) : std::string()));
}

std::vector<sweep_unit> owed_units(const sweep_keys& keys, const std::set<std::string>& done) {
  std::vector<sweep_unit> units;
  const std::size_t count = keys.plan.configurations.size(), shards = static_cast<std::size_t>(keys.request.shards);
  for (std::size_t s = 0; s < keys.plan.scenes.size(); ++s)
    for (std::size_t c = 0; c < count; ++c) {
      // Round robin over the unsharded order: every shard gets scenes and configurations alike.
      if ((s * count + c) % shards != static_cast<std::size_t>(keys.request.shard - 1)) continue;
      if (done.count(keys.key_of(keys.plan.configurations[c], s))) continue;
      units.push_back({&keys.plan.configurations[c], s, c});
    }
  return units;
}

double timing::noise() const {
  const statistics s = of(frames);
  return frames.size() > 1 && s.mean > 0.0 ? s.sd / std::sqrt(static_cast<double>(frames.size())) / s.mean : 1.0;
}

std::vector<timing> time_group(const sweep_request& request, const std::vector<pipeline*>& pipelines) {
  std::vector<timing> timings(pipelines.size());
  int rounds = 0;
  while (rounds < request.repeat) {
    for (std::size_t i = 0; i < pipelines.size(); ++i) {
      pipelines[i]->draw();
      double total = 0.0;
      for (const pass_time& pass : pipelines[i]->collect_pass_times()) {
        if (!timings[i].passes.count(pass.pass)) timings[i].pass_order.push_back(pass.pass);
        timings[i].passes[pass.pass].push_back(pass.milliseconds);
        total += pass.milliseconds;
      }
      timings[i].frames.push_back(total);
    }
    ++rounds;
    bool quiet = rounds >= request.min_rounds;
    for (const timing& t : timings) quiet = quiet && t.noise() <= request.max_noise;
    if (quiet) break;
  }
  for (timing& t : timings) t.rounds = rounds;
  return timings;
}

void timing_columns(sweep_table& table, std::map<std::string, std::string>& row, const timing& measured, const sweep_request& request, bool wall_clock,
                    const std::string& machine) {
  const statistics frames = of(measured.frames);
  for (const char* column : {"frame_ms", "frame_ms_spread", "frame_ms_noise", "timing_rounds", "noise_met", "timing", "machine"}) table.add_column(column);
  row["frame_ms"] = number_text(frames.mean);
  row["frame_ms_spread"] = number_text(frames.mean > 0.0 ? frames.sd / frames.mean : 0.0);
  row["frame_ms_noise"] = number_text(measured.noise());
  row["timing_rounds"] = std::to_string(measured.rounds);
  row["noise_met"] = measured.noise() <= request.max_noise ? "yes" : "no";
  row["timing"] = wall_clock ? "wall clock" : "timer queries";
  row["machine"] = machine;
  for (const std::string& pass : measured.pass_order) {
    table.add_column(slug(pass) + "_ms");
    row[slug(pass) + "_ms"] = number_text(of(measured.passes.at(pass)).mean);
  }
}

double quality_columns(sweep_table& table, std::map<std::string, std::string>& row, const seed_qualities& measured, scene_references& references,
                       const technique_settings& first_seed) {
  // Per metric in the order the reference names them: the seeds' values (of the defined ones),
  // the reference's standard errors, the direction, and why a seed's is undefined.
  struct collected {
    std::vector<double> values, reference_se;
    bool higher_is_better = false;
  };
  std::vector<std::string> order;
  std::map<std::string, collected> metrics;
  std::map<std::string, std::string> undefined;  // metric -> why, where a seed's is undefined
  std::vector<double> noises;
  for (const frame_quality& quality : measured.seeds) {
    for (const quality_metric& metric : quality.metrics) {
      if (std::find(order.begin(), order.end(), metric.name) == order.end()) order.push_back(metric.name);
      collected& c = metrics[metric.name];
      c.higher_is_better = metric.higher_is_better;
      if (!metric.defined) {
        undefined.emplace(metric.name, metric.why_undefined);
        continue;
      }
      c.values.push_back(metric.value);
      if (metric.reference_se >= 0.0) c.reference_se.push_back(metric.reference_se);
    }
    if (quality.reference_noise >= 0.0) noises.push_back(quality.reference_noise);
  }
  const std::size_t seeds = measured.seeds.size();
  for (const std::string& name : order) {
    table.add_column(name);
    // Undefined at one seed is undefined for the mean: never a number a ranking could read.
    if (undefined.count(name)) {
      row[name] = "undefined";
      continue;
    }
    const collected& c = metrics[name];
    row[name] = number_text(of(c.values).mean);
    if (c.reference_se.size() == c.values.size() && !c.values.empty()) {
      table.add_column(name + "_ref_se");
      row[name + "_ref_se"] = number_text(of(c.reference_se).mean);
    }
    if (c.values.size() < 2) continue;
    // Seeds in columns: each seed's value, the spread, and the worst seed (the furthest from the
    // reference; the smallest for a measure where larger is better).
    table.add_column(name + "_sd");
    row[name + "_sd"] = number_text(of(c.values).sd);
    std::size_t worst = 0;
    for (std::size_t s = 0; s < c.values.size(); ++s) {
      table.add_column(name + "_seed" + std::to_string(s + 1));
      row[name + "_seed" + std::to_string(s + 1)] = number_text(c.values[s]);
      const bool worse = c.higher_is_better ? c.values[s] < c.values[worst] : std::fabs(c.values[s]) > std::fabs(c.values[worst]);
      if (worse) worst = s;
    }
    table.add_column(name + "_worst");
    table.add_column(name + "_worst_seed");
    row[name + "_worst"] = number_text(c.values[worst]);
    row[name + "_worst_seed"] = std::to_string(worst + 1);
  }
  double share = -1.0;
  if (!noises.empty()) {
    table.add_column("ref_noise");
    table.add_column("ref_noise_share");
    const double noise = of(noises).mean;
    row["ref_noise"] = number_text(noise);
    const std::optional<double> rmse = sweep_table::number(row, "rel_rmse");
    if (rmse && *rmse > 0.0) share = noise / *rmse;
    row["ref_noise_share"] = share >= 0.0 ? number_text(share) : std::string();
  }
  if (measured.raws.size() > 1 && seeds > 1) {
    table.add_column("seed_noise");
    const quality_metric noise = references.seed_noise(measured.raws, first_seed);
    row["seed_noise"] = noise.defined ? number_text(noise.value) : "undefined";
    if (!noise.defined) undefined.emplace("seed_noise", noise.why_undefined);
  }
  if (!undefined.empty()) {
    // "rel_bias rel_rmse: why | leak_rmse: why", the metrics of one reason together (no comma or
    // semicolon: the cell needs no CSV quoting in either dialect).
    std::map<std::string, std::string> by_reason;
    for (const auto& [name, reason] : undefined) by_reason[reason] += (by_reason[reason].empty() ? "" : " ") + name;
    std::string why;
    for (const auto& [reason, names] : by_reason) why += (why.empty() ? "" : " | ") + names + ": " + reason;
    table.add_column("undefined");
    row["undefined"] = why;
  }
  return share;
}

std::string noise_warning(const sweep_table& table) {
  std::size_t noisy = 0, measured = 0;
  double worst = 0.0;
  for (const auto& row : table.rows) {
    const std::optional<double> share = sweep_table::number(row, "ref_noise_share");
    if (!share) continue;
    ++measured;
    if (*share > noise_share_warning) ++noisy;
    worst = std::max(worst, *share);
  }
  if (noisy == 0) return {};
  std::ostringstream text;
  text << "the reference's own noise is more than " << std::lround(100.0 * noise_share_warning) << " % of the error (rel_rmse) of " << noisy << " of "
       << measured << " row(s), up to " << std::fixed << std::setprecision(0) << 100.0 * worst
       << " % (ref_noise_share): those errors are partly the reference's, and rows that differ by less than ref_noise are not ranked by it; "
          "raise --reference-samples (4x the samples halves the noise), and read rel_rmse_corrected";
  return text.str();
}

std::string machine_name(const std::string& device) {
  char host[HOST_NAME_MAX + 1] = {};
  const std::string name = ::gethostname(host, sizeof host - 1) == 0 && host[0] ? std::string(host) : std::string("unknown host");
  // The renderer line of describe_current_context ("GL_RENDERER llvmpipe (...)").
  std::string renderer;
  std::istringstream lines(device);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("GL_RENDERER", 0) == 0 && line.find_first_not_of(' ', 11) != std::string::npos) renderer = line.substr(line.find_first_not_of(' ', 11));
  // No comma or semicolon: the cell needs no CSV quoting in either dialect (scripts split these
  // rows at their separators).
  std::string machine;
  for (char c : renderer.empty() ? name : name + ": " + renderer)
    if (c != ',' && c != ';') machine += c;
  return machine;
}

}  // namespace vplkit::cli::sweep_steps
