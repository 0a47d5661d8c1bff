// The write step of `vplkit sweep` (sweep_steps.hpp): sweep.csv, the plots and sweep.md, and the
// record beside them that `vplkit sweep merge` plans a shard's sweep from.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "frontend/cli/sweep_steps.hpp"
#include "frontend/core/error.hpp"
#include "frontend/core/files.hpp"
#include "frontend/core/setting.hpp"
#include "frontend/core/text.hpp"

namespace vplkit::cli {

namespace fs = std::filesystem;
using namespace sweep_steps;

namespace {

const std::vector<std::string> head_columns = {"scene", "technique"};
const std::vector<std::string> timing_head = {"frame_ms", "frame_ms_spread", "frame_ms_noise", "timing_rounds", "noise_met", "timing", "machine"};
// "undefined": why a row's relative numbers are "undefined" (a black reference), when one is.
const std::vector<std::string> tail_columns = {"undefined", "receivers", "seeds", "is_base", "rank", "pareto", "tie", "key"};

bool listed(const std::vector<std::string>& names, const std::string& name) { return std::find(names.begin(), names.end(), name) != names.end(); }
bool ends_with(const std::string& text, const std::string& end) { return text.size() > end.size() && text.compare(text.size() - end.size(), end.size(), end) == 0; }

// A column that describes a quality column rather than being one: its seeds, spread, worst seed,
// the reference's standard error.
bool derived_column(const std::string& name) {
  for (const char* end : {"_sd", "_worst", "_worst_seed", "_ref_se"})
    if (ends_with(name, end)) return true;
  const std::size_t seed = name.rfind("_seed");
  return seed != std::string::npos && seed + 5 < name.size() &&
         std::all_of(name.begin() + static_cast<std::ptrdiff_t>(seed + 5), name.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; });
}

// The columns in their order: scene, technique, the varied settings, the timing, the passes, the
// quality numbers, then the bookkeeping.
void order_columns(sweep_table& table, const std::vector<std::string>& axis_columns) {
  std::vector<std::string> ordered = head_columns;
  for (const std::string& name : axis_columns) ordered.push_back(name);
  for (const std::string& name : timing_head)
    if (listed(table.columns, name)) ordered.push_back(name);
  for (const std::string& name : table.columns)
    if (!listed(ordered, name) && !listed(tail_columns, name) && ends_with(name, "_ms")) ordered.push_back(name);
  for (const std::string& name : table.columns)
    if (!listed(ordered, name) && !listed(tail_columns, name)) ordered.push_back(name);
  for (const std::string& name : tail_columns)
    if (listed(table.columns, name)) ordered.push_back(name);
  table.columns = ordered;
}

// The family's rank against the base configuration ([LW] Table 5.10's Eq. 5.3 for Light Wave):
// the frames per second a configuration gains over the base's, with the % of similarity it keeps,
// where the base is one of the rows. The family says how (technique_family::base_rank).
void rank_against_base(sweep_table& table, const technique_family& family) {
  if (!listed(table.columns, "is_base") || !family.base_rank) return;
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
    row["rank"] = format_real(family.base_rank(1000.0 / *ms - 1000.0 / base->second, *similarity));
  }
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

// The paragraphs before the tables: the command, the grid, how it was timed and measured.
void report_head(std::ostringstream& md, const sweep_request& request, const sweep_plan& plan, const sweep_table& table, const sweep_context& context) {
  md << "# vplkit sweep" << (request.title.empty() ? "" : ": " + markdown_text(request.title)) << "\n\n"
     << markdown_code_block("vplkit sweep " + request.command, "sh") << "\n";
  if (request.shards > 1)
    md << "Shard " << request.shard << " of " << request.shards << " (--shard " << request.shard << "/" << request.shards
       << "): the rows of this shard only; `vplkit sweep merge` combines the shards' folders.\n\n";
  md << "Technique family: " << plan.family->title << ". ";
  std::vector<std::string> varied;
  for (const sweep_axis& axis : request.axes) {
    std::vector<std::string> points;
    for (const auto& point : axis.values) points.push_back(joined(point, ":"));
    varied.push_back(joined(axis.names, ":") + " = " + joined(points, ", "));
  }
  md << "Varied: " << (varied.empty() ? std::string("nothing") : markdown_text(joined(varied, "; "))) << ". " << plan.configurations.size() << " configurations x "
     << plan.scenes.size() << " scene(s). The settings in effect before --vary" << (request.seeds > 1 ? " (the seed is 1 to " + std::to_string(request.seeds) + ")" : "")
     << ":\n\n" << markdown_code_block(settings_json(*plan.defaults, 0), "json") << "\n";
  md << "**Time**: " << context.method << ", on:\n\n```\n" << context.device << "\n```\n\nEvery pass of a frame (the frame the papers time), a warm-up frame first; the "
     << "configurations of a scene are timed interleaved, " << request.group << " at a time (A B C A B C ...), so that they share whatever else the "
     << "machine does: compare times within one run. frame_ms is the mean over the rounds of the sum of the passes, frame_ms_spread the rounds' "
     << "relative standard deviation, frame_ms_noise the mean's relative standard error; rounds are repeated until every configuration's noise is "
     << "below " << fixed(100.0 * request.max_noise, 1) << " % (at least " << request.min_rounds << ", at most " << request.repeat << " rounds; the noise "
     << "criterion of NVBench). machine: the host and renderer a row was timed on. ";
  std::size_t noisy = 0;
  for (const auto& row : table.rows) noisy += cell(row, "noise_met") == "no";
  md << (noisy == 0 ? "Every configuration reached it.\n\n"
                    : std::to_string(noisy) + " configuration(s) stopped at " + std::to_string(request.repeat) +
                          " rounds without reaching it (noise_met = no in the CSV).\n\n");
  md << "**Quality**: " << context.coverage << " ";
  if (request.reference.kind != reference_kind::none)
    md << (request.seeds > 1 ? "Each number is the mean over seeds 1 to " + std::to_string(request.seeds) +
                                   " (the techniques that read a seed); the CSV keeps each seed's value (_seedN), the spread (_sd, the seeds' sample "
                                   "standard deviation, ± below), the worst seed's value (_worst: the furthest from the reference, the smallest "
                                   "similarity or SSIM) and which seed it was (_worst_seed)."
                             : "One seed.")
       << " The Pareto front: per scene, the configurations that no other beats beyond the noise on both frame_ms and rel_rmse (pareto = 1 in "
          "the CSV, * below): a row is dominated only when another is faster by more than the two times' standard errors together and has a "
          "smaller rel_rmse by more than the two errors' (the seeds' standard error and the reference's, _ref_se). Rows of the front within that "
          "noise of each other in both are ties (tie = the same number in the CSV, \"tie N\" below): their order is not measured."
       << (plan.base && plan.family->base_rank ? " rank: " + plan.family->base_rank_title +
                                                     ", the frames per second gained over the base configuration (is_base = 1) with the % of "
                                                     "similarity kept, where the base configuration is one of the rows."
                                               : "");
  md << "\n\n";
  for (const std::string& warning : context.warnings) md << "**Warning**: " << markdown_text(warning) << ".\n\n";
  if (context.resumed > 0)
    md << context.resumed << " row(s) were kept from an earlier run of this sweep (resumed): they were timed in another session; compare their times with "
       << "the others' with care.\n\n";
}

// The markdown report. Every name a user gave (a scene, a value, the command, a section) is
// escaped: shown as it is, never a link, HTML or a table's cell boundary.
std::string report(const sweep_request& request, const sweep_plan& plan, const sweep_table& table, const sweep_context& context,
                   const std::vector<drawn_plot>& plots) {
  std::ostringstream md;
  report_head(md, request, plan, table, context);
  // One table per scene, a column per quality number (its spread and the reference's standard
  // error in the cell).
  std::vector<std::string> metrics;
  for (const std::string& column : table.columns)
    if (!listed(head_columns, column) && !listed(tail_columns, column) && !listed(plan.axis_columns, column) && !listed(timing_head, column) &&
        !ends_with(column, "_ms") && !derived_column(column) && column != "ref_noise" && column != "ref_noise_share")
      metrics.push_back(column);
  const bool shares = listed(table.columns, "ref_noise_share"), ranked = listed(table.columns, "rank");
  std::vector<std::string> scenes;
  for (const auto& row : table.rows)
    if (!listed(scenes, cell(row, "scene"))) scenes.push_back(cell(row, "scene"));
  for (const std::string& scene : scenes) {
    md << "## " << markdown_text(scene) << "\n\n| " << (plan.technique_axis ? "technique | " : "");
    for (const std::string& column : plan.axis_columns) md << column << " | ";
    md << "frame ms | spread | ";
    for (const std::string& metric : metrics) md << metric << " | ";
    md << (shares ? "reference noise (% of rel_rmse) | " : "") << (ranked ? "rank | " : "") << "Pareto |\n|" << (plan.technique_axis ? "---|" : "");
    for (std::size_t i = 0; i < plan.axis_columns.size(); ++i) md << "---:|";
    md << "---:|---:|";
    for (std::size_t i = 0; i < metrics.size(); ++i) md << "---:|";
    md << (shares ? "---:|" : "") << (ranked ? "---:|" : "") << ":---:|\n";
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
        if (sweep_table::number(row, metric + "_ref_se")) md << " (reference ± " << number(metric + "_ref_se", 4) << ")";
        md << " | ";
      }
      if (shares) {
        const std::optional<double> share = sweep_table::number(row, "ref_noise_share");
        md << (share ? fixed(100.0 * *share, 1) + (*share > noise_share_warning ? " (!)" : "") : std::string("-")) << " | ";
      }
      if (ranked) md << (cell(row, "is_base") == "1" ? std::string("base") : number("rank", 2)) << " | ";
      md << (cell(row, "pareto") == "1" ? "*" : "") << (cell(row, "tie").empty() ? "" : " tie " + cell(row, "tie")) << " |\n";
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

// The record's escapes: a value on one line (a scene's name may hold a line end).
std::string escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '\\') out += "\\\\";
    else if (c == '\n') out += "\\n";
    else if (c == '\r') out += "\\r";
    else out += c;
  }
  return out;
}

std::string unescaped(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '\\' || i + 1 == text.size()) {
      out += text[i];
      continue;
    }
    const char next = text[++i];
    out += next == 'n' ? '\n' : next == 'r' ? '\r' : next;
  }
  return out;
}

const char* const record_head = "vplkit sweep record 1";

}  // namespace

namespace sweep_steps {

void write_table(const fs::path& path, sweep_table& table, const sweep_plan& plan) {
  mark_pareto(table, "frame_ms", "rel_rmse");
  rank_against_base(table, *plan.family);
  order_columns(table, plan.axis_columns);
  const std::string text = sweep_csv(table);
  write_bytes_atomically(path, std::vector<std::uint8_t>(text.begin(), text.end()));
}

void write_report(const session& io, const sweep_request& request, const sweep_plan& plan, const sweep_table& table, const sweep_context& context) {
  // A plot per varied setting (and the technique when it is varied), and the Pareto front.
  std::vector<drawn_plot> plots;
  std::vector<std::string> axes = plan.axis_columns;
  if (plan.technique_axis) axes.insert(axes.begin(), "technique");
  std::vector<std::string> errors;
  for (const char* name : {"rel_rmse", "rel_bias"})
    if (listed(table.columns, name)) errors.emplace_back(name);
  for (const std::string& axis : axes) {
    std::vector<std::string> series = {"scene"};
    for (const std::string& other : axes)
      if (other != axis) series.push_back(other);
    if (const std::optional<gnuplot_plot> plot = axis_plot(table, axis, series, "frame_ms", errors))
      plots.push_back({slug(axis), "frame_ms and the relative errors against " + axis + ", each ± its standard error", draw(request.out, slug(axis), *plot)});
  }
  if (!errors.empty())
    if (const std::optional<gnuplot_plot> plot = pareto_plot(table, "frame_ms", "rel_rmse"))
      plots.push_back({"pareto", "rel_rmse against frame_ms ± their standard errors, the Pareto front joined", draw(request.out, "pareto", *plot)});
  const std::string md = report(request, plan, table, context, plots);
  write_bytes_atomically(request.out / "sweep.md", std::vector<std::uint8_t>(md.begin(), md.end()));
  io.out << "wrote " << fs::absolute(request.out / "sweep.csv").string() << "\nwrote " << fs::absolute(request.out / "sweep.md").string() << "\n";
  for (const drawn_plot& plot : plots) {
    if (plot.failure.empty()) io.out << "wrote " << fs::absolute(request.out / (plot.name + ".png")).string() << "\n";
    else io.out << "sweep: no plot " << fs::absolute(request.out / (plot.name + ".png")).string() << ": " << plot.failure << "\n";
  }
}

}  // namespace sweep_steps

void write_sweep_record(const fs::path& folder, const sweep_record& record) {
  std::string text = std::string(record_head) + "\n";
  text += "shard " + std::to_string(record.shard) + "/" + std::to_string(record.shards) + "\n";
  for (const std::string& argument : record.arguments) text += "argument " + escaped(argument) + "\n";
  text += "title " + escaped(record.title) + "\ncommand " + escaped(record.command) + "\ndevice " + escaped(record.device) + "\nmethod " +
          escaped(record.method) + "\ncoverage " + escaped(record.coverage) + "\n";
  write_bytes_atomically(folder / "sweep-shard.txt", std::vector<std::uint8_t>(text.begin(), text.end()));
}

sweep_record read_sweep_record(const fs::path& folder) {
  const fs::path path = folder / "sweep-shard.txt";
  std::error_code code;
  if (!fs::exists(path, code))
    throw error(folder.string() + " holds no sweep-shard.txt: not the folder of a vplkit sweep (or of one older than sharding; run it again to resume it)");
  const std::string text = read_file(path, std::uintmax_t{1} << 24, "sweep record");
  std::istringstream lines(text);
  std::string line;
  if (!std::getline(lines, line) || line != record_head) throw error(path.string() + ": not a vplkit sweep record (its first line is not '" + record_head + "')");
  sweep_record record;
  bool sharded = false;
  for (int number = 2; std::getline(lines, line); ++number) {
    const std::size_t space = line.find(' ');
    const std::string name = line.substr(0, space), value = space == std::string::npos ? std::string() : unescaped(line.substr(space + 1));
    if (name == "shard") {
      int k = 0, n = 0;
      char slash = 0;
      std::istringstream numbers(value);
      if (!(numbers >> k >> slash >> n) || slash != '/' || n < 1 || k < 1 || k > n)
        throw error(path.string() + ":" + std::to_string(number) + ": a shard is K/N with 1 <= K <= N, not '" + value + "'");
      record.shard = k;
      record.shards = n;
      sharded = true;
    } else if (name == "argument") {
      record.arguments.push_back(value);
    } else if (name == "title") {
      record.title = value;
    } else if (name == "command") {
      record.command = value;
    } else if (name == "device") {
      record.device = value;
    } else if (name == "method") {
      record.method = value;
    } else if (name == "coverage") {
      record.coverage = value;
    } else {
      throw error(path.string() + ":" + std::to_string(number) + ": unknown field '" + excerpt(name, 40) + "'");
    }
  }
  if (!sharded) throw error(path.string() + ": no 'shard K/N' line");
  return record;
}

}  // namespace vplkit::cli
