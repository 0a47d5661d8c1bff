#include "frontend/cli/sweep_report.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <limits>
#include <sstream>
#include <string_view>
#include <system_error>

#include "frontend/core/error.hpp"
#include "frontend/core/files.hpp"
#include "frontend/core/setting.hpp"
#include "frontend/core/text.hpp"

namespace vplkit::cli {

namespace fs = std::filesystem;

void sweep_table::add_column(const std::string& name) {
  if (std::find(columns.begin(), columns.end(), name) == columns.end()) columns.push_back(name);
}

std::optional<double> sweep_table::number(const std::map<std::string, std::string>& row, const std::string& column) {
  const auto found = row.find(column);
  if (found == row.end() || found->second.empty()) return std::nullopt;
  return parse_real(found->second);
}

namespace {

std::string csv_cell(const std::string& text) { return text.find_first_of(",\"\n\r") == std::string::npos ? text : csv_quoted(text); }

// The records of a CSV text (quotes as csv_cell writes them: a quoted cell may span lines, as a
// scene's name with a line end does), each with the line it starts on; CRLF reads as LF. Throws
// vplkit::error for a quote that is not closed.
std::vector<std::pair<int, std::vector<std::string>>> csv_records(const std::string& text, const fs::path& path) {
  std::vector<std::pair<int, std::vector<std::string>>> records;
  int line = 1, start = 1;
  std::vector<std::string> cells(1);
  bool quoted = false, any = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        cells.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        if (c == '\n') ++line;
        cells.back() += c;
      }
    } else if (c == '"') {
      quoted = any = true;
    } else if (c == ',') {
      cells.emplace_back();
      any = true;
    } else if (c == '\n' || (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n')) {
      if (c == '\r') ++i;
      if (any) records.emplace_back(start, std::move(cells));
      cells.assign(1, std::string());
      any = false;
      start = ++line;
    } else {
      cells.back() += c;
      any = true;
    }
  }
  if (quoted) throw error(path.string() + ":" + std::to_string(start) + ": a quoted cell is not closed");
  if (any) records.emplace_back(start, std::move(cells));
  return records;
}

// Text as a field of a gnuplot data file (a title read by columnheader, a category by xtic):
// data, never a command. The fields are tab-separated and the blocks line-separated, so tabs and
// line ends become spaces; gnuplot's reader ends a field at a double quote and reads backslash
// escapes, so " shows as '' and a backslash is doubled to show as itself.
std::string data_label(const std::string& text) {
  std::string out;
  for (char c : text) {
    const auto code = static_cast<unsigned char>(c);
    if (c == '"') out += "''";
    else if (c == '\\') out += "\\\\";
    else if (code < 0x20 || code == 0x7f) out += ' ';
    else out += c;
  }
  return out;
}

// One of the sweep's own names (a column: a setting's name, frame_ms) as a gnuplot string
// constant: single quotes, in which gnuplot reads no escape and a quote is doubled; control
// characters, which would end the line and the command, become spaces.
std::string gnuplot_quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    const auto code = static_cast<unsigned char>(c);
    if (c == '\'') out += "''";
    else if (code < 0x20 || code == 0x7f) out += ' ';
    else out += c;
  }
  return out + "'";
}

// The lines every script starts with: how to run it, the terminal, the output (ARG2) and the
// data's format (tab-separated, no comment character: a name may hold a #).
std::string script_head(const std::string& what) {
  return "# vplkit sweep: " + what + ".\n# Run in the sweep's folder: gnuplot -c NAME.gnuplot NAME.dat NAME.png (every name shown is read from the data file)\n"
         "set terminal pngcairo size 960,600 noenhanced\nset output ARG2\nset datafile separator \"\\t\"\nset datafile commentschars \"\"\n"
         "set key outside bottom center horizontal\nset grid\n";
}

std::string series_of(const std::map<std::string, std::string>& row, const std::vector<std::string>& series) {
  std::string name;
  for (const std::string& column : series) {
    const auto found = row.find(column);
    if (found == row.end() || found->second.empty()) continue;
    name += (name.empty() ? "" : " ") + (column == "scene" ? found->second : column + "=" + found->second);
  }
  return name.empty() ? "all" : name;
}

}  // namespace

std::string sweep_csv(const sweep_table& table) {
  std::ostringstream out;
  for (std::size_t i = 0; i < table.columns.size(); ++i) out << (i ? "," : "") << csv_cell(table.columns[i]);
  out << "\n";
  for (const auto& row : table.rows) {
    for (std::size_t i = 0; i < table.columns.size(); ++i) {
      const auto found = row.find(table.columns[i]);
      out << (i ? "," : "") << csv_cell(found == row.end() ? std::string() : found->second);
    }
    out << "\n";
  }
  return out.str();
}

sweep_table read_sweep_csv(const fs::path& path) {
  const std::string text = read_file(path, std::uintmax_t{1} << 28, "sweep CSV");
  const std::vector<std::pair<int, std::vector<std::string>>> records = csv_records(text, path);
  sweep_table table;
  if (records.empty()) throw error(path.string() + ": an empty file, not a sweep's CSV");
  table.columns = records.front().second;
  for (const char* required : {"scene", "technique", "key"})
    if (std::find(table.columns.begin(), table.columns.end(), required) == table.columns.end())
      throw error(path.string() + ": not a vplkit sweep's CSV (no '" + required + "' column)");
  for (std::size_t r = 1; r < records.size(); ++r) {
    const auto& [line, cells] = records[r];
    if (cells.size() != table.columns.size())
      throw error(path.string() + ":" + std::to_string(line) + ": " + std::to_string(cells.size()) + " cells, the header has " + std::to_string(table.columns.size()));
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < cells.size(); ++i) row[table.columns[i]] = cells[i];
    table.rows.push_back(std::move(row));
  }
  return table;
}

double time_se(const std::map<std::string, std::string>& row, const std::string& time) {
  const std::optional<double> t = sweep_table::number(row, time), noise = sweep_table::number(row, time + "_noise");
  return t && noise && std::isfinite(*t * *noise) && *noise > 0.0 ? std::fabs(*t * *noise) : 0.0;
}

double quality_se(const std::map<std::string, std::string>& row, const std::string& column) {
  double variance = 0.0;
  const std::optional<double> sd = sweep_table::number(row, column + "_sd"), seeds = sweep_table::number(row, "seeds");
  if (sd && seeds && *seeds >= 2.0 && std::isfinite(*sd)) variance += *sd * *sd / *seeds;
  const std::optional<double> reference = sweep_table::number(row, column + "_ref_se");
  if (reference && std::isfinite(*reference) && *reference > 0.0) variance += *reference * *reference;
  return std::sqrt(variance);
}

void mark_pareto(sweep_table& table, const std::string& time, const std::string& error) {
  table.add_column("pareto");
  table.add_column("tie");
  // Each row as its value +- its standard error on both axes.
  struct point {
    double time, error, time_low, time_high, error_low, error_high;
    std::size_t row;
  };
  std::map<std::string, std::vector<point>> scenes;
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    auto& row = table.rows[i];
    const std::optional<double> t = sweep_table::number(row, time), e = sweep_table::number(row, error);
    row["pareto"] = "";
    row["tie"] = "";
    if (!t || !e || !std::isfinite(*t) || !std::isfinite(*e)) continue;
    const double dt = time_se(row, time), de = quality_se(row, error);
    scenes[row["scene"]].push_back({*t, *e, *t - dt, *t + dt, *e - de, *e + de, i});
  }
  // B dominates A when B is better beyond both their noises on both axes: B's upper time at most
  // A's lower time, B's upper error at most A's lower error, and one of them strictly (without
  // noise: at most as slow and as wrong, and better on one). One sweep over the rows sorted by
  // their upper time answers each row in the order of its lower time, carrying the least upper
  // error of the rows strictly faster and, for an equal bound, of the rows at it: O(n log n) for
  // the sorts (comparing every row with every other took 5.5 min per rewrite of a 20,000-row sweep).
  for (auto& [scene, points] : scenes) {
    std::vector<const point*> by_high(points.size()), by_low(points.size());
    for (std::size_t k = 0; k < points.size(); ++k) by_high[k] = by_low[k] = &points[k];
    std::sort(by_high.begin(), by_high.end(), [](const point* a, const point* b) { return a->time_high < b->time_high; });
    std::sort(by_low.begin(), by_low.end(), [](const point* a, const point* b) { return a->time_low < b->time_low; });
    // The least upper error of each run of equal upper times, at every index of the run.
    std::vector<double> run_least(by_high.size());
    for (std::size_t first = 0; first < by_high.size();) {
      std::size_t last = first;
      double least = std::numeric_limits<double>::infinity();
      for (; last < by_high.size() && by_high[last]->time_high == by_high[first]->time_high; ++last) least = std::min(least, by_high[last]->error_high);
      std::fill(run_least.begin() + static_cast<std::ptrdiff_t>(first), run_least.begin() + static_cast<std::ptrdiff_t>(last), least);
      first = last;
    }
    double strictly_faster = std::numeric_limits<double>::infinity();
    std::size_t next = 0;
    for (const point* a : by_low) {
      while (next < by_high.size() && by_high[next]->time_high < a->time_low) strictly_faster = std::min(strictly_faster, by_high[next++]->error_high);
      const double at_bound = next < by_high.size() && by_high[next]->time_high == a->time_low ? run_least[next] : std::numeric_limits<double>::infinity();
      const bool beaten = strictly_faster <= a->error_low || at_bound < a->error_low;
      table.rows[a->row]["pareto"] = std::string(1, beaten ? '0' : '1');
    }
    // Ties: the front's rows within each other's noise on both axes (their intervals overlap),
    // joined (union-find) into groups numbered per scene in time order; a row alone is no tie.
    // Sorted by lower time, a row is compared only with the rows whose lower time is below its
    // upper time: those it can overlap.
    std::vector<const point*> front;
    for (const point& p : points)
      if (table.rows[p.row]["pareto"] == "1") front.push_back(&p);
    std::sort(front.begin(), front.end(), [](const point* a, const point* b) { return a->time_low < b->time_low || (a->time_low == b->time_low && a->error < b->error); });
    std::vector<std::size_t> parent(front.size());
    for (std::size_t k = 0; k < front.size(); ++k) parent[k] = k;
    const auto root = [&](std::size_t k) {
      while (parent[k] != k) k = parent[k] = parent[parent[k]];
      return k;
    };
    for (std::size_t k = 0; k < front.size(); ++k)
      for (std::size_t j = k + 1; j < front.size() && front[j]->time_low <= front[k]->time_high; ++j)
        if (front[j]->error_low <= front[k]->error_high && front[k]->error_low <= front[j]->error_high) parent[root(j)] = root(k);
    std::map<std::size_t, std::size_t> members;
    for (std::size_t k = 0; k < front.size(); ++k) ++members[root(k)];
    std::map<std::size_t, int> numbers;
    for (std::size_t k = 0; k < front.size(); ++k) {
      const std::size_t group = root(k);
      if (members[group] < 2) continue;
      const auto [number, fresh] = numbers.emplace(group, static_cast<int>(numbers.size()) + 1);
      table.rows[front[k]->row]["tie"] = std::to_string(number->second);
    }
  }
}

namespace {

std::string data_number(const std::map<std::string, std::string>& row, const std::string& column) {
  const std::optional<double> value = sweep_table::number(row, column);
  return value && std::isfinite(*value) ? format_real(*value) : std::string("NaN");
}

}  // namespace

std::optional<gnuplot_plot> axis_plot(const sweep_table& table, const std::string& x, const std::vector<std::string>& series, const std::string& time,
                                      const std::vector<std::string>& errors) {
  // Numbers on x when every cell is one, else categories in the order they first appear.
  bool numeric = true;
  std::vector<std::string> categories;
  std::map<std::string, std::size_t> category_index;
  for (const auto& row : table.rows) {
    const auto cell = row.find(x);
    if (cell == row.end() || cell->second.empty()) continue;
    const std::optional<double> value = parse_real(cell->second);
    numeric = numeric && value && std::isfinite(*value);
    if (category_index.emplace(cell->second, categories.size()).second) categories.push_back(cell->second);
  }
  if (categories.empty()) return std::nullopt;
  std::vector<std::string> measured;
  for (const std::string& e : errors)
    for (const auto& row : table.rows)
      if (sweep_table::number(row, e)) {
        measured.push_back(e);
        break;
      }
  // One block of the data file per series: x, time, each error, and x's text (the category's
  // tic label), sorted by x; its first line the titles.
  std::map<std::string, std::vector<std::pair<double, std::string>>> blocks;
  for (const auto& row : table.rows) {
    const auto cell = row.find(x);
    if (cell == row.end() || cell->second.empty()) continue;
    const double position = numeric ? *parse_real(cell->second) : static_cast<double>(category_index.at(cell->second));
    // Each value with its standard error beside it (the error bars).
    std::string line = format_real(position) + "\t" + data_number(row, time) + "\t" + format_real(time_se(row, time));
    for (const std::string& column : measured) line += "\t" + data_number(row, column) + "\t" + format_real(quality_se(row, column));
    blocks[series_of(row, series)].emplace_back(position, line + "\t" + data_label(cell->second));
  }
  gnuplot_plot plot;
  std::ostringstream data, script;
  script << script_head("the frame time (left axis) and the relative errors (right axis) against a varied setting, a line per series, each value +- its standard error")
         << "set xlabel " << gnuplot_quoted(x) << "\nset ylabel " << gnuplot_quoted(time + " (solid)") << "\nset ytics nomirror\n";
  if (!measured.empty()) script << "set y2label 'relative error (dashed)'\nset y2tics\n";
  if (!numeric) script << "set xrange [-0.5:" << static_cast<double>(categories.size()) - 0.5 << "]\n";
  else script << "set offsets graph 0.05, graph 0.05, 0, 0\n";
  script << "plot ";
  int index = 0;
  // Columns: x, time, its standard error, each error and its standard error, x's text.
  const std::size_t label_column = 4 + 2 * measured.size();
  for (auto& [name, lines] : blocks) {
    std::sort(lines.begin(), lines.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    data << (index ? "\n\n" : "") << "x\t" << data_label(time + ", " + name) << "\tse";
    for (const std::string& e : measured) data << "\t" << data_label(e + ", " + name) << "\tse";
    data << "\t" << data_label(x) << "\n";
    for (const auto& [position, line] : lines) data << line << "\n";
    script << (index ? ", \\\n     " : "") << "ARG1 index " << index << " using 1:2:3" << (numeric ? "" : ":xtic(" + std::to_string(label_column) + ")")
           << " with yerrorlines lw 2 lc " << index + 1 << " title columnheader(2)";
    for (std::size_t e = 0; e < measured.size(); ++e)
      script << ", \\\n     ARG1 index " << index << " using 1:" << 2 * e + 4 << ":" << 2 * e + 5 << " axes x1y2 with yerrorlines dt " << e + 2 << " lc " << index + 1
             << " title columnheader(" << 2 * e + 4 << ")";
    ++index;
  }
  script << "\n";
  plot.script = script.str();
  plot.data = data.str();
  return plot;
}

std::optional<gnuplot_plot> pareto_plot(const sweep_table& table, const std::string& time, const std::string& error) {
  std::map<std::string, std::vector<std::array<double, 4>>> points;
  std::map<std::string, std::vector<std::pair<double, double>>> front;
  for (const auto& row : table.rows) {
    const std::optional<double> t = sweep_table::number(row, time), e = sweep_table::number(row, error);
    if (!t || !e || !std::isfinite(*t) || !std::isfinite(*e)) continue;
    const std::string scene = row.count("scene") ? row.at("scene") : std::string();
    points[scene].push_back({*t, *e, time_se(row, time), quality_se(row, error)});
    const auto pareto = row.find("pareto");
    if (pareto != row.end() && pareto->second == "1") front[scene].emplace_back(*t, *e);
  }
  if (points.empty()) return std::nullopt;
  std::ostringstream data, script;
  script << script_head("the relative error against the frame time, per scene, each +- its standard errors, the Pareto front joined") << "set xlabel " << gnuplot_quoted(time)
         << "\nset ylabel " << gnuplot_quoted(error) << "\nset offsets graph 0.05, graph 0.05, graph 0.05, graph 0.05\nplot ";
  int index = 0;
  for (auto& [scene, all] : points) {
    std::vector<std::pair<double, double>>& line = front[scene];
    std::sort(line.begin(), line.end());
    // Two blocks per scene: its points, then its front.
    data << (index ? "\n\n" : "") << "t\t" << data_label(scene) << "\tt_se\te_se\n";
    for (const auto& [t, e, dt, de] : all) data << format_real(t) << "\t" << format_real(e) << "\t" << format_real(dt) << "\t" << format_real(de) << "\n";
    data << "\n\nt\t" << data_label("Pareto front, " + scene) << "\n";
    for (const auto& [t, e] : line) data << format_real(t) << "\t" << format_real(e) << "\n";
    script << (index ? ", \\\n     " : "") << "ARG1 index " << 2 * index << " using 1:2:3:4 with xyerrorbars pt 7 lc " << index + 1
           << " title columnheader(2), \\\n     ARG1 index " << 2 * index + 1 << " using 1:2 with lines lw 2 lc " << index + 1 << " title columnheader(2)";
    ++index;
  }
  script << "\n";
  return gnuplot_plot{script.str(), data.str()};
}

std::string run_gnuplot(const fs::path& script, const fs::path& data, const fs::path& png) {
  const auto reason_of = [](int code) { return std::generic_category().message(code); };
  // gnuplot's output through a pipe, for the message when it fails.
  int ends[2];
  if (::pipe2(ends, O_CLOEXEC) != 0) return "cannot run gnuplot (a pipe: " + reason_of(errno) + ")";
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, ends[1], 1);
  posix_spawn_file_actions_adddup2(&actions, ends[1], 2);
  // The arguments as they are: no shell parses them, and gnuplot -c reads those after the
  // script as the strings ARG1 and ARG2.
  std::vector<std::string> arguments = {"gnuplot", "-c", script.string(), data.string(), png.string()};
  std::vector<char*> argv;
  for (std::string& argument : arguments) argv.push_back(argument.data());
  argv.push_back(nullptr);
  pid_t child = 0;
  const int spawned = ::posix_spawnp(&child, "gnuplot", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(ends[1]);
  if (spawned != 0) {
    ::close(ends[0]);
    if (spawned == ENOENT) return "gnuplot is not installed (no gnuplot on PATH)";
    return "cannot run gnuplot (" + reason_of(spawned) + ")";
  }
  std::string output;
  char buffer[4096];
  for (;;) {
    const ssize_t got = ::read(ends[0], buffer, sizeof buffer);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) break;
    output.append(buffer, static_cast<std::size_t>(got));
    if (output.size() > (std::size_t{1} << 16)) output.erase(0, output.size() - 4096);  // the end says why
  }
  ::close(ends[0]);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0)
    if (errno != EINTR) return "gnuplot's exit status is unknown (" + reason_of(errno) + ")";
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return {};
  // Its last lines, as one line.
  while (!output.empty() && std::isspace(static_cast<unsigned char>(output.back()))) output.pop_back();
  std::size_t from = output.size();
  for (int lines = 0; from > 0; --from)
    if (output[from - 1] == '\n' && ++lines == 3) break;
  std::string said;
  for (char c : output.substr(from)) said += static_cast<unsigned char>(c) < 0x20 ? ' ' : c;
  said = excerpt(said, 400);
  const std::string how = WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                                            : "signal " + std::to_string(WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  return "gnuplot failed (" + how + ")" + (said.empty() ? std::string() : ": " + said);
}

std::string markdown_text(const std::string& text) {
  std::string out;
  for (char c : text) {
    const auto code = static_cast<unsigned char>(c);
    if (code < 0x20 || code == 0x7f) out += ' ';
    else if (std::string_view("\\`*_[]()<>|#!&~$").find(c) != std::string_view::npos) out += std::string("\\") + c;
    else out += c;
  }
  return out;
}

std::string markdown_code_block(const std::string& text, const std::string& language) {
  std::size_t longest = 0, run = 0;
  for (char c : text) {
    run = c == '`' ? run + 1 : 0;
    longest = std::max(longest, run);
  }
  const std::string fence(std::max<std::size_t>(3, longest + 1), '`');
  return fence + language + "\n" + text + (text.empty() || text.back() != '\n' ? "\n" : "") + fence + "\n";
}

}  // namespace vplkit::cli
