// vplkit sweep: any setting of any technique, on any scene the command line reads, timed and
// measured against a reference (sweep_engine.hpp):
//   vplkit sweep --technique T [--scene S ...] --vary NAME=v1,v2,... [--vary ...]
//                [--reference rsm-brute-force|monte-carlo|base|none] [--seeds N] [--repeat N] --out DIR
// NAME is a setting's option name without the dashes (radius, slots, shadow-maps), or technique;
// several --vary make a grid, and `--vary a:b=1:2,3:4` varies two settings together. Every other
// setting option sets the base configuration. --spec FILE runs a specification: the arguments of
// one sweep per [section] (the lines before the first section are every section's), each into
// DIR/<section>; the options given next to --spec are added to every section's, a --vary of a
// setting the section varies replaces it, and --scene replaces the section's scenes. Everything
// is checked before anything is written: a usage error exits 2 and leaves no file; a grid of more
// than --max-configurations points (100000) is one, refused before it is planned. A sweep holds a
// lock on its folder while it runs: a second sweep into the same folder is refused (exit 1).
#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>
#include <string_view>

#include "frontend/cli/commands.hpp"
#include "frontend/cli/sweep_engine.hpp"
#include "frontend/cli/sweep_report.hpp"
#include "frontend/core/files.hpp"

namespace vplkit::cli {

namespace fs = std::filesystem;

namespace {

struct sweep_arguments {
  std::string technique = "rsm-alg6";
  given_settings given;
  common_options common;
  std::vector<std::string> scenes;
  std::vector<std::string> vary;
  std::string reference = "none";
  reference_options reference_settings;
  option_scope reference_scope;
  std::string base_technique;
  int seeds = 1;
  int repeat = 20;
  int min_rounds = 3;
  double max_noise_percent = 2.0;
  int interleave = 8;
  long long max_configurations = 100000;
  std::string out, spec, section, shard;
  bool plan_only = false;
};

// Registers the options of one sweep (and, at the top level, --spec and --section).
void register_sweep_options(CLI::App& app, sweep_arguments& a, bool top_level) {
  app.add_option("--technique", a.technique, "the technique swept (with --vary technique=..., the first of the family's)")
      ->check(CLI::IsMember(technique_names()))->capture_default_str();
  app.add_option("--scene", a.scenes, "a scene to sweep on (several: one row per configuration and scene): built-in, .obj, .gltf or .glb [the family's]")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  app.add_option("--vary", a.vary,
                 "NAME=v1,v2,...: an axis of the grid over the setting NAME (its option's name without the dashes, or technique); "
                 "A:B=a1:b1,a2:b2 varies two settings together; values with commas (x,y,z) are separated by ';'")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  app.add_option("--reference", a.reference,
                 "what the quality is measured against: rsm-brute-force (the RSM gather's brute force with exact visibility), monte-carlo (the "
                 "one-bounce path-traced image), base (the base configuration's image: Light Wave's % similar) or none")
      ->check(CLI::IsMember({"none", "rsm-brute-force", "monte-carlo", "base"}))->capture_default_str();
  add_reference_options(app, a.reference_settings, a.reference_scope);
  a.reference_scope.add(app.add_option("--base-technique", a.base_technique, "base: the base configuration's technique [--technique]"), "--reference base",
                        [](const std::string& reference) { return reference == "base"; });
  app.add_option("--seeds", a.seeds, "quality: the mean and spread over seeds 1 to N (techniques that read a seed)")->check(CLI::Range(1, 64))->capture_default_str();
  app.add_option("--repeat", a.repeat, "timing: at most this many rounds per configuration")->check(CLI::Range(1, 1000))->capture_default_str();
  app.add_option("--min-rounds", a.min_rounds, "timing: at least this many rounds")->check(CLI::Range(1, 1000))->capture_default_str();
  app.add_option("--max-noise", a.max_noise_percent, "timing: stop once the mean frame time's relative standard error is below this (%)")
      ->check(CLI::Range(0.0, 100.0))->capture_default_str();
  app.add_option("--interleave", a.interleave, "timing: configurations timed interleaved at once (their pipelines live together)")
      ->check(CLI::Range(1, 256))->capture_default_str();
  app.add_option("--max-configurations", a.max_configurations,
                 "the most configurations the grid may have (the product of the --vary axes' lengths): a larger one is refused before it is planned")
      ->check(CLI::Range(1LL, 1000000000LL))->capture_default_str();
  add_pose_options(app, a.common);
  add_common_options(app, a.common);
  add_setting_options(app, a.given);
  app.add_option("--out", a.out, "the folder for sweep.csv, sweep.md and the plots (with --spec: a folder per section)");
  if (top_level) {
    app.add_option("--shard", a.shard,
                   "K/N: measure only shard K of N of the rows (the same deterministic split on every machine); `vplkit sweep merge` combines the "
                   "shards' folders");
    app.add_option("--spec", a.spec, "a sweep specification: the arguments of one sweep per [section] (bench/*.sweep)");
    app.add_option("--section", a.section, "with --spec: run only this section");
    app.add_flag("--plan", a.plan_only, "check every sweep and print its configurations, then stop (nothing is drawn or written)");
  }
}

// "NAME=v1,v2" or "A:B=a1:b1,a2:b2" into an axis.
sweep_axis parse_axis(const std::string& text) {
  const std::string usage = "--vary " + text + ": expected NAME=v1,v2,... (two settings together: A:B=a1:b1,a2:b2)";
  const std::size_t equals = text.find('=');
  if (equals == std::string::npos || equals == 0 || equals + 1 == text.size()) throw usage_error(usage);
  sweep_axis axis;
  const auto split = [](const std::string& whole, char separator) {
    std::vector<std::string> parts(1);
    for (char c : whole) {
      if (c == separator) parts.emplace_back();
      else parts.back() += c;
    }
    return parts;
  };
  axis.names = split(text.substr(0, equals), ':');
  const std::string list = text.substr(equals + 1);
  for (const std::string& point : split(list, list.find(';') != std::string::npos ? ';' : ',')) {
    std::vector<std::string> values = axis.names.size() > 1 ? split(point, ':') : std::vector<std::string>{point};
    if (values.size() != axis.names.size()) throw usage_error(usage);
    for (const std::string& value : values)
      if (value.empty()) throw usage_error(usage);
    axis.values.push_back(values);
  }
  for (const std::string& name : axis.names)
    if (name.empty()) throw usage_error(usage);
  return axis;
}

// "K/N" with 1 <= K <= N.
std::pair<int, int> parse_shard(const std::string& text) {
  const std::size_t slash = text.find('/');
  const auto whole = [](const std::string& digits) {
    if (digits.empty() || digits.size() > 6 || !std::all_of(digits.begin(), digits.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }))
      return 0;
    return std::stoi(digits);
  };
  const int k = slash == std::string::npos ? 0 : whole(text.substr(0, slash)), n = slash == std::string::npos ? 0 : whole(text.substr(slash + 1));
  if (k < 1 || n < 1 || k > n) throw usage_error("--shard " + text + ": expected K/N, shard K of N with 1 <= K <= N (e.g. --shard 2/4)");
  return {k, n};
}

sweep_request make_request(const sweep_arguments& a, const std::string& title, const std::string& command, const fs::path& out) {
  a.reference_scope.require_read_by(a.reference, "--reference");
  sweep_request request;
  request.title = title;
  request.command = command;
  request.technique = a.technique;
  request.given = a.given;
  request.common = a.common;
  request.scenes = a.scenes;
  for (const std::string& text : a.vary) {
    sweep_axis axis = parse_axis(text);
    // A later --vary of the same settings replaces the earlier (a specification's, overridden).
    const auto same = std::find_if(request.axes.begin(), request.axes.end(), [&](const sweep_axis& other) { return other.names == axis.names; });
    if (same != request.axes.end()) *same = std::move(axis);
    else request.axes.push_back(std::move(axis));
  }
  request.reference = a.reference_settings;
  request.reference.kind = reference_from_name(a.reference);
  request.base_technique = a.base_technique;
  request.seeds = a.seeds;
  request.repeat = a.repeat;
  request.min_rounds = std::min(a.min_rounds, a.repeat);
  request.max_noise = a.max_noise_percent / 100.0;
  request.group = a.interleave;
  request.max_configurations = static_cast<std::uint64_t>(a.max_configurations);
  request.out = out;
  return request;
}

// The words of the options given on `command`, as name-value pairs, without those named in `left_out`.
std::vector<std::string> option_words(const CLI::App& command, const std::vector<std::string>& left_out) {
  std::vector<std::string> words;
  for (const CLI::Option* option : command.get_options()) {
    if (option->count() == 0 || std::find(left_out.begin(), left_out.end(), option->get_name()) != left_out.end()) continue;
    for (const std::string& value : option->results()) words.insert(words.end(), {option->get_name(), value});
  }
  return words;
}

// The request and plan that a sweep's words make (the words of one section, or of a shard's record).
sweep_request parse_request(const std::vector<std::string>& words, const std::string& where, const std::string& title, const std::string& command, const fs::path& out) {
  CLI::App app{"vplkit sweep (" + where + ")"};
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  sweep_arguments arguments;
  register_sweep_options(app, arguments, false);
  std::vector<std::string> reversed(words.rbegin(), words.rend());
  try {
    app.parse(reversed);
  } catch (const CLI::ParseError& failure) {
    throw usage_error(where + ": " + failure.what());
  }
  sweep_request request = make_request(arguments, title, command, out);
  request.arguments = words;
  return request;
}

// The output folder and a CSV already in it: a file in the folder's way, or a CSV of another
// sweep (other varied settings), is a usage error before anything is written.
void check_output(const sweep_request& request, const sweep_plan& plan) {
  std::error_code code;
  if (fs::exists(request.out, code) && !fs::is_directory(request.out, code)) throw usage_error("--out " + request.out.string() + " is a file, not a folder");
  const fs::path csv = request.out / "sweep.csv";
  if (!fs::exists(csv, code)) return;
  sweep_table table;
  try {
    table = read_sweep_csv(csv);
  } catch (const error& failure) {
    throw usage_error(std::string(failure.what()) + "; give another --out");
  }
  std::vector<std::string> varied;
  for (const std::string& column : table.columns) {
    if (column == "scene" || column == "technique") continue;
    if (column == "frame_ms") break;
    varied.push_back(column);
  }
  if (varied != plan.axis_columns) {
    std::string listed;
    for (const std::string& column : varied) listed += (listed.empty() ? "" : ", ") + column;
    throw usage_error(csv.string() + " holds a sweep over other settings (" + (listed.empty() ? std::string("none") : listed) +
                      "): resuming needs the same --vary; give another --out");
  }
}

// The lock a sweep holds on its folder for its whole run (folder_lock, the mechanism renders
// install their outputs under, on a file of its own), so that two sweeps into one folder never
// interleave their rewrites of sweep.csv (each rewrote the rows it had read, and the other's were
// lost). A second sweep is refused at once rather than made to wait: a sweep runs for hours.
folder_lock lock_output(const sweep_request& request) {
  std::error_code code;
  fs::create_directories(request.out, code);
  if (code) throw error("cannot create the folder " + request.out.string() + " (" + code.message() + ")");
  try {
    return folder_lock(request.out, 0.0, ".vplkit-sweep.lock");
  } catch (const folder_lock_busy&) {
    throw error("another vplkit sweep is writing to " + request.out.string() + " (it holds " + (request.out / ".vplkit-sweep.lock").string() +
                "): wait for it to finish, then run this one to add its rows, or give another --out");
  }
}

// Whitespace-separated words, "double quotes" around a word with spaces.
std::vector<std::string> words_of(const std::string& line, const std::string& where) {
  std::vector<std::string> words;
  std::string word;
  bool quoted = false, have = false;
  for (char c : line) {
    if (c == '"') {
      quoted = !quoted;
      have = true;
    } else if (!quoted && (c == ' ' || c == '\t' || c == '\r')) {
      if (have) words.push_back(word);
      word.clear();
      have = false;
    } else {
      word += c;
      have = true;
    }
  }
  if (quoted) throw usage_error(where + ": a quote is not closed");
  if (have) words.push_back(word);
  return words;
}

struct spec_section {
  std::string name;
  std::vector<std::string> words;
};

// The sections of a specification, each with the common lines' words first.
std::vector<spec_section> read_spec(const fs::path& path) {
  std::string text;
  try {
    text = read_file(path, std::uintmax_t{1} << 20, "sweep specification");
  } catch (const error& failure) {
    throw usage_error(failure.what());
  }
  std::vector<std::string> common;
  std::vector<spec_section> sections;
  std::istringstream lines(text);
  std::string line;
  int number = 0;
  while (std::getline(lines, line)) {
    ++number;
    const std::string where = path.string() + ":" + std::to_string(number);
    const std::size_t start = line.find_first_not_of(" \t\r");
    if (start == std::string::npos || line[start] == '#') continue;
    if (line[start] == '[') {
      const std::size_t close = line.find(']', start);
      if (close == std::string::npos || close == start + 1) throw usage_error(where + ": a section is [name]");
      sections.push_back({line.substr(start + 1, close - start - 1), common});
      continue;
    }
    for (const std::string& word : words_of(line, where)) (sections.empty() ? common : sections.back().words).push_back(word);
  }
  if (sections.empty()) sections.push_back({"", common});
  return sections;
}

std::string folder_name(const std::string& section) {
  std::string name;
  for (char c : section) name += std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' ? c : '-';
  return name;
}

// The words as a POSIX shell reads them back, for sweep.md's command: a word of other than
// letters, digits and _@%+=:,./- in single quotes, in which the shell reads nothing but the closing
// quote ('\'' for a quote). A scene named `x"; rm -rf ~; "` is a word again, not a command.
std::string shell_words(const std::vector<std::string>& words) {
  std::string all;
  for (const std::string& word : words) {
    const bool plain = !word.empty() && std::all_of(word.begin(), word.end(), [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || std::string_view("_@%+=:,./-").find(c) != std::string_view::npos;
    });
    std::string quoted = "'";
    for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    all += (all.empty() ? "" : " ") + (plain ? word : quoted + "'");
  }
  return all;
}

int run(const session& io, CLI::App& command, const sweep_arguments& top) {
  if (top.out.empty()) throw usage_error("--out is required: the folder for sweep.csv, sweep.md and the plots");
  std::vector<std::pair<sweep_request, sweep_plan>> sweeps;
  if (top.spec.empty()) {
    if (!top.section.empty()) throw usage_error("--section needs --spec");
    const std::vector<std::string> words = option_words(command, {"--help", "--plan", "--shard"});
    sweeps.emplace_back(make_request(top, "", shell_words(words), top.out), sweep_plan{});
    sweeps.back().first.arguments = option_words(command, {"--help", "--plan", "--shard", "--out"});
  } else {
    // The options given next to --spec, as words added to every section's.
    std::vector<std::string> overrides;
    bool scenes_given = false;
    for (const CLI::Option* option : command.get_options()) {
      const std::string name = option->get_name();
      if (option->count() == 0 || name == "--spec" || name == "--section" || name == "--out" || name == "--plan" || name == "--help" || name == "--shard") continue;
      scenes_given = scenes_given || name == "--scene";
      for (const std::string& value : option->results()) overrides.insert(overrides.end(), {name, value});
    }
    bool found = false;
    for (spec_section& section : read_spec(top.spec)) {
      if (!top.section.empty() && section.name != top.section) continue;
      found = true;
      std::vector<std::string> words;
      for (std::size_t i = 0; i < section.words.size(); ++i) {
        if (scenes_given && section.words[i] == "--scene") {
          ++i;  // the command line's --scene replaces the section's
          continue;
        }
        words.push_back(section.words[i]);
      }
      words.insert(words.end(), overrides.begin(), overrides.end());
      const fs::path out = section.name.empty() ? fs::path(top.out) : fs::path(top.out) / folder_name(section.name);
      // The command that runs this section again, as sweep.md quotes it.
      std::vector<std::string> command_words = {"--spec", top.spec};
      if (!section.name.empty()) command_words.insert(command_words.end(), {"--section", section.name});
      command_words.insert(command_words.end(), overrides.begin(), overrides.end());
      command_words.insert(command_words.end(), {"--out", top.out});
      sweeps.emplace_back(parse_request(words, top.spec + (section.name.empty() ? "" : " [" + section.name + "]"), section.name, shell_words(command_words), out),
                          sweep_plan{});
    }
    if (!found) throw usage_error("--section " + top.section + ": " + top.spec + " has no such section");
  }
  // Every sweep planned and checked before the first runs.
  if (!top.shard.empty()) {
    const auto [k, n] = parse_shard(top.shard);
    for (auto& [request, plan] : sweeps) {
      request.shard = k;
      request.shards = n;
    }
  }
  for (auto& [request, plan] : sweeps) {
    try {
      plan = plan_sweep(request);
    } catch (const usage_error& failure) {
      throw usage_error((request.title.empty() ? "" : "[" + request.title + "] ") + failure.what());
    }
    check_output(request, plan);
  }
  if (top.plan_only) {
    for (const auto& [request, plan] : sweeps) {
      io.out << (request.title.empty() ? std::string("sweep") : "[" + request.title + "]") << ": " << plan.configurations.size() << " configuration(s) of "
             << plan.family->name << " on " << plan.scenes.size() << " scene(s), reference " << reference_name(request.reference.kind) << ", into "
             << request.out.string() << "\n";
      for (const sweep_configuration& configuration : plan.configurations) io.out << "  " << configuration.label << "\n";
    }
    return 0;
  }
  if (io.dry_run) return 0;
  for (const auto& [request, plan] : sweeps) {
    if (!request.title.empty()) io.out << "sweep [" << request.title << "] into " << request.out.string() << "\n";
    const folder_lock lock = lock_output(request);
    check_output(request, plan);  // again under the lock: another sweep may have written its CSV since
    run_sweep(io, request, plan);
  }
  return 0;
}

struct merge_arguments {
  std::vector<std::string> folders;
  std::string out;
};

// vplkit sweep merge DIR... --out OUT: the shards' records planned again (one sweep's, every
// shard once), their rows in an unsharded run's order, written as one sweep.
int run_merge(const session& io, const CLI::App& sweep, const merge_arguments& m) {
  const std::vector<std::string> given = option_words(sweep, {"--help"});
  if (!given.empty()) throw usage_error("sweep merge: " + given.front() + " is an option of a sweep, not of merge (merge reads each shard's sweep-shard.txt)");
  std::vector<fs::path> folders;
  std::vector<sweep_record> records;
  for (const std::string& folder : m.folders) {
    if (same_file(folder, m.out)) throw usage_error("--out " + m.out + " is the shard folder " + folder + ": merge into a new folder");
    try {
      records.push_back(read_sweep_record(folder));
    } catch (const error& failure) {
      throw usage_error(failure.what());
    }
    folders.emplace_back(folder);
    if (records.back().arguments != records.front().arguments)
      throw usage_error(folder + " holds a shard of another sweep than " + m.folders.front() + " (their sweep-shard.txt name other arguments): merge the shards of one sweep");
  }
  std::error_code code;
  if (fs::exists(fs::path(m.out) / "sweep.csv", code)) throw usage_error("--out " + m.out + " already holds a sweep.csv: merge into a new folder");
  std::vector<std::string> command_words = records.front().arguments;
  command_words.insert(command_words.end(), {"--out", m.out});
  const sweep_request request = parse_request(records.front().arguments, folders.front().string() + "/sweep-shard.txt", records.front().title, shell_words(command_words), m.out);
  sweep_plan plan;
  try {
    plan = plan_sweep(request);
  } catch (const usage_error& failure) {
    throw usage_error(folders.front().string() + "/sweep-shard.txt: " + failure.what());
  }
  if (io.dry_run) return 0;
  const folder_lock lock = lock_output(request);
  merge_sweep(io, request, plan, folders, records);
  return 0;
}

}  // namespace

command add_sweep_command(CLI::App& app) {
  auto state = std::make_shared<sweep_arguments>();
  auto merging = std::make_shared<merge_arguments>();
  CLI::App* sweep = app.add_subcommand("sweep",
                                       "time and measure a grid of settings of one technique (--vary NAME=v1,v2,...) on one or more scenes against a "
                                       "reference: DIR/sweep.csv, sweep.md and plots; resumable; --shard K/N and `sweep merge` spread it over machines");
  register_sweep_options(*sweep, *state, true);
  CLI::App* merge = sweep->add_subcommand("merge", "combine the folders of a sweep's shards (--shard K/N) into one sweep.csv, sweep.md and plots, as an "
                                                   "unsharded run writes them (up to the timing)");
  merge->add_option("folders", merging->folders, "the shards' folders (every shard of one sweep, once)")->required();
  merge->add_option("--out", merging->out, "the folder for the merged sweep.csv, sweep.md and plots (new)")->required();
  const auto reset_state = restorer(state), reset_merging = restorer(merging);
  return {sweep,
          [state, merging, sweep, merge](const session& io) { return merge->parsed() ? run_merge(io, *sweep, *merging) : run(io, *sweep, *state); },
          [reset_state, reset_merging] {
            reset_state();
            reset_merging();
          }};
}

}  // namespace vplkit::cli
