#include "frontend/cli/sweep_engine.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "frontend/cli/sweep_report.hpp"
#include "frontend/core/error.hpp"
#include "frontend/core/text.hpp"
#include "frontend/core/files.hpp"
#include "frontend/core/parallel.hpp"
#include "frontend/gl/context.hpp"

#include <vplkit/lightwave.hpp>

namespace vplkit::cli {

namespace fs = std::filesystem;

namespace {

std::string joined(const std::vector<std::string>& items, const std::string& separator) {
  std::string all;
  for (const std::string& item : items) all += (all.empty() ? "" : separator) + item;
  return all;
}

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

// The settings in effect as one line: the configuration's identity.
std::string identity(const technique_settings& settings) {
  std::string text = "technique=" + settings.technique();
  for (const auto& [name, value] : settings_in_effect(settings)) text += ";" + name + "=" + value;
  return text;
}

// FNV-1a, 64 bits, as hex: the key of a row (configuration, scene, reference, seeds).
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

std::string duration(double seconds) {
  const long whole = std::lround(std::max(0.0, seconds));
  std::ostringstream out;
  if (whole >= 3600) out << whole / 3600 << " h " << (whole % 3600) / 60 << " min";
  else if (whole >= 60) out << whole / 60 << " min " << whole % 60 << " s";
  else out << whole << " s";
  return out.str();
}

std::string number_text(double value) { return std::isfinite(value) ? format_real(value) : std::string(); }

struct statistics {
  double mean = 0.0, sd = 0.0;
};

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
  if (!family.reads_scene() && !request.scenes.empty())
    throw usage_error("--scene is read by the techniques that draw a scene, not by technique " + request.technique + " (it draws its --object in a room)");
  plan.scenes = family.reads_scene() ? (request.scenes.empty() ? std::vector<std::string>{family.default_scene} : request.scenes) : std::vector<std::string>{""};
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

// What one configuration's timing collected.
struct timing {
  std::vector<double> frames;                         // total of the passes, per round
  std::map<std::string, std::vector<double>> passes;  // per pass, per round
  std::vector<std::string> pass_order;
  double noise() const {
    const statistics s = of(frames);
    return frames.size() > 1 && s.mean > 0.0 ? s.sd / std::sqrt(static_cast<double>(frames.size())) / s.mean : 1.0;
  }
};

const std::vector<std::string> head_columns = {"scene", "technique"};
// "undefined": why a row's relative numbers are "undefined" (a black reference), when one is.
const std::vector<std::string> tail_columns = {"undefined", "receivers", "seeds", "is_base", "rank", "pareto", "key"};

// The columns in their order: scene, technique, the varied settings, the timing, the passes, the
// quality numbers, then the bookkeeping.
void order_columns(sweep_table& table, const std::vector<std::string>& axis_columns) {
  std::vector<std::string> ordered = head_columns;
  for (const std::string& name : axis_columns) ordered.push_back(name);
  for (const char* name : {"frame_ms", "frame_ms_spread", "frame_ms_noise", "timing_rounds", "noise_met", "timing"})
    if (std::find(table.columns.begin(), table.columns.end(), name) != table.columns.end()) ordered.push_back(name);
  for (const std::string& name : table.columns)
    if (std::find(ordered.begin(), ordered.end(), name) == ordered.end() && std::find(tail_columns.begin(), tail_columns.end(), name) == tail_columns.end() &&
        name.size() > 3 && name.compare(name.size() - 3, 3, "_ms") == 0)
      ordered.push_back(name);
  for (const std::string& name : table.columns)
    if (std::find(ordered.begin(), ordered.end(), name) == ordered.end() && std::find(tail_columns.begin(), tail_columns.end(), name) == tail_columns.end())
      ordered.push_back(name);
  for (const std::string& name : tail_columns)
    if (std::find(table.columns.begin(), table.columns.end(), name) != table.columns.end()) ordered.push_back(name);
  table.columns = ordered;
}

// [LW] Table 5.10's rank (Eq. 5.3): the frames per second a configuration gains over the base
// configuration's, divided by the % of similarity it loses, where the base is one of the rows.
void rank_against_base(sweep_table& table) {
  if (std::find(table.columns.begin(), table.columns.end(), "is_base") == table.columns.end()) return;
  table.add_column("rank");
  // Each scene's base row first (the last one where a resumed CSV holds several), then the ranks:
  // one pass each, not a search of every row per row.
  std::map<std::string, double> base_ms;
  for (auto& row : table.rows)
    if (row["is_base"] == "1")
      if (const std::optional<double> ms = sweep_table::number(row, "frame_ms")) base_ms[row["scene"]] = *ms;
  for (auto& row : table.rows) {
    row["rank"] = "";
    const std::optional<double> ms = sweep_table::number(row, "frame_ms"), similarity = sweep_table::number(row, "similarity");
    const auto base = base_ms.find(row["scene"]);
    if (!ms || !similarity || *similarity >= 100.0 || row["is_base"] == "1" || base == base_ms.end()) continue;
    row["rank"] = format_real(lightwave_rank(1000.0 / *ms - 1000.0 / base->second, *similarity));
  }
}

void write_table(const fs::path& path, sweep_table& table, const std::vector<std::string>& axis_columns) {
  mark_pareto(table, "frame_ms", "rel_rmse");
  rank_against_base(table);
  order_columns(table, axis_columns);
  const std::string text = sweep_csv(table);
  write_bytes_atomically(path, std::vector<std::uint8_t>(text.begin(), text.end()));
}

std::string cell(const std::map<std::string, std::string>& row, const std::string& column) {
  const auto found = row.find(column);
  return found == row.end() ? std::string() : found->second;
}

// A plot of the sweep: DIR/<name>.png, or why gnuplot did not draw it.
struct drawn_plot {
  std::string name, caption, failure;
};

// Draws `plot` as DIR/<name>.png: its script and data are written beside it (NAME.gnuplot and
// NAME.dat, to be run again by hand), gnuplot draws into a temporary, and the PNG is installed
// as every output is (write_all_or_nothing). "" on success, else why not.
std::string draw(const fs::path& folder, const std::string& name, const gnuplot_plot& plot) {
  const fs::path script = fs::absolute(folder / (name + ".gnuplot")), data = fs::absolute(folder / (name + ".dat")), png = fs::absolute(folder / (name + ".png"));
  write_all_or_nothing({{script, [&] { return std::vector<std::uint8_t>(plot.script.begin(), plot.script.end()); }},
                        {data, [&] { return std::vector<std::uint8_t>(plot.data.begin(), plot.data.end()); }}});
  const fs::path drawn = sibling_temporary_name(png, "partial");
  std::string failure = run_gnuplot(script, data, drawn);
  std::error_code code;
  if (failure.empty() && !fs::is_regular_file(drawn, code)) failure = "gnuplot exited 0 but wrote no PNG";
  if (failure.empty()) {
    try {
      const std::string bytes = read_file(drawn, std::uintmax_t{1} << 28, "PNG gnuplot drew");
      write_bytes_atomically(png, std::vector<std::uint8_t>(bytes.begin(), bytes.end()));
    } catch (const error& problem) {
      failure = problem.what();
    }
  }
  fs::remove(drawn, code);
  return failure;
}

// The markdown report. Every name a user gave (a scene, a value, the command, a section) is
// escaped: shown as it is, never a link, HTML or a table's cell boundary.
std::string report(const sweep_request& request, const sweep_plan& plan, const sweep_table& table, const std::string& coverage, const std::string& device,
                   const std::string& method, const std::vector<drawn_plot>& plots, std::size_t resumed) {
  std::ostringstream md;
  md << "# vplkit sweep" << (request.title.empty() ? "" : ": " + markdown_text(request.title)) << "\n\n"
     << markdown_code_block("vplkit sweep " + request.command, "sh") << "\n"
     << "Technique family: " << plan.family->title << ". ";
  std::vector<std::string> varied;
  for (const sweep_axis& axis : request.axes) {
    std::vector<std::string> points;
    for (const auto& point : axis.values) points.push_back(joined(point, ":"));
    varied.push_back(joined(axis.names, ":") + " = " + joined(points, ", "));
  }
  md << "Varied: " << (varied.empty() ? std::string("nothing") : markdown_text(joined(varied, "; "))) << ". " << plan.configurations.size() << " configurations x "
     << plan.scenes.size() << " scene(s). The settings in effect before --vary" << (request.seeds > 1 ? " (the seed is 1 to " + std::to_string(request.seeds) + ")" : "")
     << ":\n\n" << markdown_code_block(settings_json(*plan.defaults, 0), "json") << "\n";
  md << "**Time**: " << method << ", on:\n\n```\n" << device << "\n```\n\nEvery pass of a frame (the frame the papers time), a warm-up frame first; the "
     << "configurations of a scene are timed interleaved, " << request.group << " at a time (A B C A B C ...), so that they share whatever else the "
     << "machine does: compare times within one run. frame_ms is the mean over the rounds of the sum of the passes, frame_ms_spread the rounds' "
     << "relative standard deviation, frame_ms_noise the mean's relative standard error; rounds are repeated until every configuration's noise is "
     << "below " << fixed(100.0 * request.max_noise, 1) << " % (at least " << request.min_rounds << ", at most " << request.repeat << " rounds; the noise "
     << "criterion of NVBench). ";
  std::vector<std::string> noisy;
  for (const auto& row : table.rows)
    if (cell(row, "noise_met") == "no") noisy.push_back(cell(row, "scene") + " " + cell(row, "technique") + " " + cell(row, "key").substr(0, 6));
  md << (noisy.empty() ? "Every configuration reached it.\n\n"
                       : std::to_string(noisy.size()) + " configuration(s) stopped at " + std::to_string(request.repeat) +
                             " rounds without reaching it (noise_met = no in the CSV).\n\n");
  md << "**Quality**: " << coverage << " ";
  if (request.reference.kind != reference_kind::none)
    md << (request.seeds > 1 ? "Each number is the mean over seeds 1 to " + std::to_string(request.seeds) +
                                   " (the techniques that read a seed); _sd is the seeds' sample standard deviation, _worst the seed furthest from the reference."
                             : "One seed.")
       << " The Pareto front: per scene, the configurations that no other beats on both frame_ms and rel_rmse (pareto = 1 in the CSV, * below)."
       << (plan.base ? " rank: [LW]'s Eq. 5.3 (Table 5.10), the frames per second gained over the base configuration (is_base = 1) divided by the "
                       "% of similarity lost, where the base configuration is one of the rows."
                     : "");
  md << "\n\n";
  if (resumed > 0)
    md << resumed << " row(s) were kept from an earlier run of this sweep (resumed): they were timed in another session; compare their times with "
       << "the others' with care.\n\n";
  // One table per scene.
  std::vector<std::string> metrics;
  for (const std::string& column : table.columns) {
    const bool quality = std::find(head_columns.begin(), head_columns.end(), column) == head_columns.end() &&
                         std::find(tail_columns.begin(), tail_columns.end(), column) == tail_columns.end() &&
                         std::find(plan.axis_columns.begin(), plan.axis_columns.end(), column) == plan.axis_columns.end() && column.rfind("frame_ms", 0) != 0 &&
                         column != "timing_rounds" && column != "noise_met" && column != "timing" && column.find("_sd") == std::string::npos &&
                         column.find("_worst") == std::string::npos && !(column.size() > 3 && column.compare(column.size() - 3, 3, "_ms") == 0);
    if (quality) metrics.push_back(column);
  }
  std::vector<std::string> scenes;
  for (const auto& row : table.rows)
    if (std::find(scenes.begin(), scenes.end(), cell(row, "scene")) == scenes.end()) scenes.push_back(cell(row, "scene"));
  for (const std::string& scene : scenes) {
    md << "## " << markdown_text(scene) << "\n\n| " << (plan.technique_axis ? "technique | " : "");
    for (const std::string& column : plan.axis_columns) md << column << " | ";
    const bool ranked = std::find(table.columns.begin(), table.columns.end(), "rank") != table.columns.end();
    md << "frame ms | spread | ";
    for (const std::string& metric : metrics) md << metric << " | ";
    md << (ranked ? "rank (Eq. 5.3) | " : "") << "Pareto |\n|" << (plan.technique_axis ? "---|" : "");
    for (std::size_t i = 0; i < plan.axis_columns.size(); ++i) md << "---:|";
    md << "---:|---:|";
    for (std::size_t i = 0; i < metrics.size(); ++i) md << "---:|";
    md << (ranked ? "---:|" : "") << ":---:|\n";
    for (const auto& row : table.rows) {
      if (cell(row, "scene") != scene) continue;
      md << "| " << (plan.technique_axis ? markdown_text(cell(row, "technique")) + " | " : "");
      for (const std::string& column : plan.axis_columns) md << (cell(row, column).empty() ? "-" : markdown_text(cell(row, column))) << " | ";
      const auto number = [&](const std::string& column, int digits) {
        const std::optional<double> v = sweep_table::number(row, column);
        return v ? fixed(*v, digits) : std::string(cell(row, column) == "undefined" ? "undefined" : "-");
      };
      md << number("frame_ms", 2) << " | " << number("frame_ms_spread", 3) << " | ";
      for (const std::string& metric : metrics) {
        md << number(metric, 4);
        if (sweep_table::number(row, metric + "_sd")) md << " ± " << number(metric + "_sd", 4);
        md << " | ";
      }
      if (ranked) md << (cell(row, "is_base") == "1" ? std::string("base") : number("rank", 2)) << " | ";
      md << (cell(row, "pareto") == "1" ? "*" : "") << " |\n";
    }
    md << "\n";
  }
  // Why numbers are undefined, each reason once with its rows' count.
  std::map<std::string, int> undefined;
  for (const auto& row : table.rows)
    if (!cell(row, "undefined").empty()) ++undefined[cell(row, "undefined")];
  if (!undefined.empty()) {
    md << "**Undefined numbers**: a relative number has no level to be relative to against a reference that is black where it counts, "
       << "and none over no receiver (an empty leak region). It is \"undefined\" in the CSV (the column undefined says why), not 0, and a "
       << "row whose rel_rmse is undefined is never on the Pareto front:\n\n";
    for (const auto& [why, rows] : undefined) md << "- " << rows << " row(s): " << markdown_text(why) << "\n";
    md << "\n";
  }
  // The plots, and why any is missing: gnuplot's own reason.
  for (const drawn_plot& plot : plots)
    if (plot.failure.empty()) md << "![" << plot.caption << "](" << plot.name << ".png)\n\n";
  for (const drawn_plot& plot : plots)
    if (!plot.failure.empty()) md << "No " << plot.name << ".png: " << markdown_text(plot.failure) << "\n\n";
  if (plots.empty()) md << "(no plot: nothing to draw)\n";
  return md.str();
}

}  // namespace

void run_sweep(const session& io, const sweep_request& request, const sweep_plan& plan) {
  fs::create_directories(request.out);
  const fs::path csv = request.out / "sweep.csv";
  sweep_table table;
  if (fs::exists(csv)) table = read_sweep_csv(csv);
  std::set<std::string> done;
  for (const auto& row : table.rows) done.insert(cell(row, "key"));
  const std::size_t resumed = table.rows.size();
  for (const std::string& column : head_columns) table.add_column(column);
  for (const std::string& column : plan.axis_columns) table.add_column(column);

  const headless_session gl(request.common);
  reference_options reference = request.reference;
  reference.threads = hardware_threads();
  const std::string method = describe(timing_method_for_current_context());
  const bool wall_clock = timing_method_for_current_context() == timing_method::wall_clock;
  const std::string device = describe_current_context();
  const technique_family& family = *plan.family;

  // The work, for the estimate: per configuration and scene, one unit for its timing and one per seed.
  const auto seeds_of = [&](const technique_settings& settings) { return settings.reads("seed") ? request.seeds : 1; };
  const auto key_of = [&](const sweep_configuration& c, const std::string& scene) {
    return hashed(identity(*c.settings) + "|scene=" + scene + "|reference=" + reference_name(reference.kind) + "|stride=" +
                  std::to_string(reference.receiver_stride) + "|samples=" + std::to_string(reference.samples) + "|seeds=" + std::to_string(seeds_of(*c.settings)) +
                  (plan.base ? "|base=" + identity(*plan.base) : std::string()));
  };
  // The scene as the command line named it (a file's path: the key), and as the rows show it.
  const auto scene_of = [&](const sweep_configuration& c, const std::string& scene) {
    return family.reads_scene() ? scene : drawn_scene_name(request.common, *c.settings);
  };
  const auto shown_scene = [](const std::string& name) { return fs::path(name).stem().string(); };
  double total_units = 0.0, done_units = 0.0;
  for (const std::string& scene : plan.scenes)
    for (const sweep_configuration& c : plan.configurations)
      if (!done.count(key_of(c, scene_of(c, scene)))) total_units += 1.0 + seeds_of(*c.settings);
  const auto started = std::chrono::steady_clock::now();
  const auto progress = [&](const std::string& what) {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    io.out << "sweep: " << fixed(total_units > 0.0 ? 100.0 * done_units / total_units : 100.0, 0) << " % " << what << "; " << duration(elapsed) << " so far";
    if (done_units > 0.0 && done_units < total_units) io.out << ", about " << duration(elapsed / done_units * (total_units - done_units)) << " left";
    io.out << std::endl;
  };
  if (resumed > 0) io.out << "sweep: resuming " << csv.string() << ": " << resumed << " row(s) already there are kept\n";

  std::string coverage = scene_references(gl.shaders, reference, nullptr).coverage();
  for (const std::string& scene_name : plan.scenes) {
    std::unique_ptr<scene> source;
    if (family.reads_scene()) source = std::make_unique<scene>(load_scene(request.common, scene_name));
    scene_references references(gl.shaders, reference, source.get());
    const auto build = [&](const technique_settings& settings) {
      std::unique_ptr<scene> none;
      return family.reads_scene() ? family.make_pipeline(gl.shaders, source.get(), settings) : make_posed_pipeline(gl.shaders, request.common, settings, none);
    };
    std::vector<const sweep_configuration*> pending;
    for (const sweep_configuration& c : plan.configurations)
      if (!done.count(key_of(c, scene_of(c, scene_name)))) pending.push_back(&c);
    if (pending.empty()) continue;
    if (plan.base) {
      // The base configuration at every seed the rows are measured with (once where it reads none).
      const int base_seeds = seeds_of(*plan.base);
      for (int seed = 1; seed <= base_seeds; ++seed) {
        std::unique_ptr<technique_settings> seeded_base = plan.base->clone();
        if (base_seeds > 1) seeded_base->set("seed", std::to_string(seed));
        const std::unique_ptr<pipeline> base = build(*seeded_base);
        base->draw();
        references.set_base(base->output().read_image(), seeded_base->reads("seed") ? seeded_base->get("seed") : std::string());
        base->collect_pass_times();
      }
    }
    for (std::size_t first = 0; first < pending.size(); first += static_cast<std::size_t>(request.group)) {
      const std::size_t last = std::min(pending.size(), first + static_cast<std::size_t>(request.group));
      // The group's pipelines at the first seed, timed interleaved.
      std::vector<std::unique_ptr<technique_settings>> seeded;
      std::vector<std::unique_ptr<pipeline>> pipelines;
      for (std::size_t i = first; i < last; ++i) {
        seeded.push_back(pending[i]->settings->clone());
        if (seeds_of(*seeded.back()) > 1) seeded.back()->set("seed", "1");
        pipelines.push_back(build(*seeded.back()));
        pipelines.back()->draw();  // warm-up: the shader compilers' lazy work
        pipelines.back()->collect_pass_times();
      }
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
      done_units += static_cast<double>(pipelines.size());
      progress("timed " + std::to_string(pipelines.size()) + " configuration(s) of " + (scene_name.empty() ? family.name : shown_scene(scene_name)) + " in " +
               std::to_string(rounds) + " round(s)");
      // Quality, seed by seed, and the rows.
      for (std::size_t i = 0; i < pipelines.size(); ++i) {
        const sweep_configuration& configuration = *pending[first + i];
        const std::string scene = scene_of(configuration, scene_name);
        std::map<std::string, std::string> row;
        row["scene"] = shown_scene(scene);
        row["technique"] = configuration.settings->technique();
        for (std::size_t a = 0; a < plan.axis_columns.size(); ++a) row[plan.axis_columns[a]] = configuration.axis_values[a];
        const statistics frames = of(timings[i].frames);
        for (const char* column : {"frame_ms", "frame_ms_spread", "frame_ms_noise", "timing_rounds", "noise_met", "timing", "receivers", "seeds", "key"})
          table.add_column(column);
        row["frame_ms"] = number_text(frames.mean);
        row["frame_ms_spread"] = number_text(frames.mean > 0.0 ? frames.sd / frames.mean : 0.0);
        row["frame_ms_noise"] = number_text(timings[i].noise());
        row["timing_rounds"] = std::to_string(rounds);
        row["noise_met"] = timings[i].noise() <= request.max_noise ? "yes" : "no";
        row["timing"] = wall_clock ? "wall clock" : "timer queries";
        for (const std::string& pass : timings[i].pass_order) {
          table.add_column(slug(pass) + "_ms");
          row[slug(pass) + "_ms"] = number_text(of(timings[i].passes[pass]).mean);
        }
        const int seeds = seeds_of(*configuration.settings);
        std::map<std::string, std::vector<double>> metrics;  // the seeds' values of the defined ones
        std::vector<std::string> metric_order;
        std::map<std::string, std::string> undefined;  // metric -> why, where a seed's is undefined
        std::vector<image> raws;
        std::size_t receivers = 0;
        if (reference.kind != reference_kind::none) {
          for (int seed = 1; seed <= seeds; ++seed) {
            std::unique_ptr<pipeline> other;
            pipeline* drawn = pipelines[i].get();
            std::unique_ptr<technique_settings> settings = seeded[i]->clone();
            if (seed > 1) {
              settings->set("seed", std::to_string(seed));
              other = build(*settings);
              drawn = other.get();
            }
            drawn->draw();
            drawn->collect_pass_times();
            frame_quality quality = references.measure(*drawn, *settings);
            for (const quality_metric& metric : quality.metrics) {
              if (std::find(metric_order.begin(), metric_order.end(), metric.name) == metric_order.end()) metric_order.push_back(metric.name);
              if (metric.defined) metrics[metric.name].push_back(metric.value);
              else undefined.emplace(metric.name, metric.why_undefined);
            }
            receivers = quality.receivers;
            if (!quality.raw.texels.empty()) raws.push_back(std::move(quality.raw));
            done_units += 1.0;
          }
          coverage = references.coverage();
        } else {
          done_units += static_cast<double>(seeds);
        }
        for (const std::string& name : metric_order) {
          table.add_column(name);
          // Undefined at one seed is undefined for the mean: never a number a ranking could read.
          if (undefined.count(name)) {
            row[name] = "undefined";
            continue;
          }
          const std::vector<double>& values = metrics[name];
          row[name] = number_text(of(values).mean);
          if (values.size() > 1) {
            table.add_column(name + "_sd");
            row[name + "_sd"] = number_text(of(values).sd);
            if (name == "rel_rmse" || name == "rel_bias") {
              // The seed furthest from the reference.
              double worst = values.front();
              for (double v : values)
                if (std::fabs(v) > std::fabs(worst)) worst = v;
              table.add_column(name + "_worst");
              row[name + "_worst"] = number_text(worst);
            }
          }
        }
        if (raws.size() > 1) {
          table.add_column("seed_noise");
          const quality_metric noise = references.seed_noise(raws, *seeded[i]);
          row["seed_noise"] = noise.defined ? number_text(noise.value) : "undefined";
          if (!noise.defined) undefined.emplace("seed_noise", noise.why_undefined);
        }
        if (!undefined.empty()) {
          // "rel_bias rel_rmse: why | leak_rmse: why", the metrics of one reason together (no comma
          // or semicolon: the cell needs no CSV quoting in either dialect).
          std::map<std::string, std::string> by_reason;
          for (const auto& [name, reason] : undefined) by_reason[reason] += (by_reason[reason].empty() ? "" : " ") + name;
          std::string why;
          for (const auto& [reason, names] : by_reason) why += (why.empty() ? "" : " | ") + names + ": " + reason;
          table.add_column("undefined");
          row["undefined"] = why;
        }
        row["receivers"] = reference.kind == reference_kind::none ? "" : std::to_string(receivers);
        row["seeds"] = std::to_string(reference.kind == reference_kind::none ? 0 : seeds);
        row["key"] = key_of(configuration, scene);
        if (plan.base) {
          table.add_column("is_base");
          row["is_base"] = identity(*configuration.settings) == identity(*plan.base) ? "1" : "0";
        }
        std::string summary = shown_scene(scene) + ": " + configuration.label + ": " + fixed(frames.mean, 2) + " ms";
        for (const char* name : {"rel_rmse", "rel_bias"})
          if (row.count(name)) summary += std::string(", ") + name + " " + (row[name] == "undefined" ? std::string("undefined") : fixed(of(metrics[name]).mean, 4));
        progress(summary);
        table.rows.push_back(std::move(row));
      }
      write_table(csv, table, plan.axis_columns);
    }
  }
  write_table(csv, table, plan.axis_columns);

  // A plot per varied setting (and the technique when it is varied), and the Pareto front.
  std::vector<drawn_plot> plots;
  std::vector<std::string> axes = plan.axis_columns;
  if (plan.technique_axis) axes.insert(axes.begin(), "technique");
  std::vector<std::string> errors;
  for (const char* name : {"rel_rmse", "rel_bias"})
    if (std::find(table.columns.begin(), table.columns.end(), name) != table.columns.end()) errors.emplace_back(name);
  for (const std::string& axis : axes) {
    std::vector<std::string> series = {"scene"};
    for (const std::string& other : axes)
      if (other != axis) series.push_back(other);
    if (const std::optional<gnuplot_plot> plot = axis_plot(table, axis, series, "frame_ms", errors))
      plots.push_back({slug(axis), "frame_ms and the relative errors against " + axis, draw(request.out, slug(axis), *plot)});
  }
  if (!errors.empty())
    if (const std::optional<gnuplot_plot> plot = pareto_plot(table, "frame_ms", "rel_rmse"))
      plots.push_back({"pareto", "rel_rmse against frame_ms, the Pareto front joined", draw(request.out, "pareto", *plot)});
  const std::string md = report(request, plan, table, coverage, device, method, plots, resumed);
  write_bytes_atomically(request.out / "sweep.md", std::vector<std::uint8_t>(md.begin(), md.end()));
  io.out << "wrote " << fs::absolute(csv).string() << "\nwrote " << fs::absolute(request.out / "sweep.md").string() << "\n";
  for (const drawn_plot& plot : plots) {
    if (plot.failure.empty()) io.out << "wrote " << fs::absolute(request.out / (plot.name + ".png")).string() << "\n";
    else io.out << "sweep: no plot " << fs::absolute(request.out / (plot.name + ".png")).string() << ": " << plot.failure << "\n";
  }
}

}  // namespace vplkit::cli
