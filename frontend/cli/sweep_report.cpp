#include "frontend/cli/sweep_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <set>
#include <sstream>

#include "frontend/core/error.hpp"
#include "frontend/core/files.hpp"
#include "frontend/core/setting.hpp"

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

std::string csv_cell(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

// The cells of one CSV line (quotes as csv_cell writes them).
std::vector<std::string> csv_cells(const std::string& line) {
  std::vector<std::string> cells(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        cells.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        cells.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      cells.emplace_back();
    } else {
      cells.back() += c;
    }
  }
  return cells;
}

// A title gnuplot shows between single quotes.
std::string gnuplot_text(std::string text) {
  std::replace(text.begin(), text.end(), '\'', '`');  // the terminals are noenhanced: the rest shows as it is
  return text;
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
  std::istringstream lines(text);
  std::string line;
  sweep_table table;
  if (!std::getline(lines, line)) throw error(path.string() + ": an empty file, not a sweep's CSV");
  table.columns = csv_cells(line);
  for (const char* required : {"scene", "technique", "key"})
    if (std::find(table.columns.begin(), table.columns.end(), required) == table.columns.end())
      throw error(path.string() + ": not a vplkit sweep's CSV (no '" + required + "' column)");
  int number = 1;
  while (std::getline(lines, line)) {
    ++number;
    if (line.empty()) continue;
    const std::vector<std::string> cells = csv_cells(line);
    if (cells.size() != table.columns.size())
      throw error(path.string() + ":" + std::to_string(number) + ": " + std::to_string(cells.size()) + " cells, the header has " + std::to_string(table.columns.size()));
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < cells.size(); ++i) row[table.columns[i]] = cells[i];
    table.rows.push_back(std::move(row));
  }
  return table;
}

void mark_pareto(sweep_table& table, const std::string& time, const std::string& error) {
  table.add_column("pareto");
  struct point {
    double time, error;
    std::size_t row;
  };
  std::map<std::string, std::vector<point>> scenes;
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    auto& row = table.rows[i];
    const std::optional<double> t = sweep_table::number(row, time), e = sweep_table::number(row, error);
    row["pareto"] = "";
    if (t && e && std::isfinite(*t) && std::isfinite(*e)) scenes[row["scene"]].push_back({*t, *e, i});
  }
  // Sorted by time, then error: a row is beaten exactly when a faster row has an error at most
  // its own, or a row as fast has a smaller one. So one pass that carries the least error of the
  // faster rows decides each group of equal times: O(n log n) for the sort. (Comparing every row
  // with every other took 5.5 min per rewrite of a 20,000-row sweep.)
  for (auto& [scene, points] : scenes) {
    std::sort(points.begin(), points.end(), [](const point& a, const point& b) { return a.time < b.time || (a.time == b.time && a.error < b.error); });
    double faster = std::numeric_limits<double>::infinity();
    for (std::size_t first = 0; first < points.size();) {
      std::size_t last = first;
      while (last < points.size() && points[last].time == points[first].time) ++last;
      const double fastest = points[first].error;  // the group's least error: the sort put it first
      for (std::size_t k = first; k < last; ++k)
        table.rows[points[k].row]["pareto"] = std::string(1, faster <= points[k].error || fastest < points[k].error ? '0' : '1');
      faster = std::min(faster, fastest);
      first = last;
    }
  }
}

std::string axis_plot_script(const sweep_table& table, const std::string& x, const std::vector<std::string>& series, const std::string& time,
                             const std::vector<std::string>& errors, const fs::path& png) {
  // Numbers on x when every cell is one, else categories in the order they first appear.
  bool numeric = true;
  std::vector<std::string> categories;
  for (const auto& row : table.rows) {
    const auto cell = row.find(x);
    if (cell == row.end() || cell->second.empty()) continue;
    numeric = numeric && parse_real(cell->second).has_value();
    if (std::find(categories.begin(), categories.end(), cell->second) == categories.end()) categories.push_back(cell->second);
  }
  if (categories.empty()) return {};
  std::vector<std::string> measured;
  for (const std::string& e : errors)
    for (const auto& row : table.rows)
      if (sweep_table::number(row, e)) {
        measured.push_back(e);
        break;
      }
  // One data block per series: x, time, then each error, sorted by x.
  std::map<std::string, std::vector<std::pair<double, std::string>>> blocks;
  for (const auto& row : table.rows) {
    const auto cell = row.find(x);
    if (cell == row.end() || cell->second.empty()) continue;
    const double position = numeric ? *parse_real(cell->second)
                                    : static_cast<double>(std::find(categories.begin(), categories.end(), cell->second) - categories.begin());
    std::string line = format_real(position);
    for (const std::string& column : std::vector<std::string>{time}) line += " " + (sweep_table::number(row, column) ? row.at(column) : std::string("NaN"));
    for (const std::string& column : measured) line += " " + (sweep_table::number(row, column) ? row.at(column) : std::string("NaN"));
    blocks[series_of(row, series)].emplace_back(position, line);
  }
  std::ostringstream script;
  script << "set terminal pngcairo size 960,600 noenhanced\nset output '" << png.string() << "'\nset key outside bottom center horizontal\nset grid\n"
         << "set xlabel '" << gnuplot_text(x) << "'\nset ylabel '" << gnuplot_text(time) << " (solid)'\nset ytics nomirror\n";
  if (!measured.empty()) script << "set y2label 'relative error (dashed)'\nset y2tics\n";
  if (!numeric) {
    script << "set xtics (";
    for (std::size_t i = 0; i < categories.size(); ++i) script << (i ? ", " : "") << "'" << gnuplot_text(categories[i]) << "' " << i;
    script << ")\nset xrange [-0.5:" << static_cast<double>(categories.size()) - 0.5 << "]\n";
  } else {
    script << "set offsets graph 0.05, graph 0.05, 0, 0\n";
  }
  int index = 0;
  for (auto& [name, lines] : blocks) {
    std::sort(lines.begin(), lines.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    script << "$s" << index++ << " << EOD\n";
    for (const auto& [position, line] : lines) script << line << "\n";
    script << "EOD\n";
  }
  script << "plot ";
  index = 0;
  bool first = true;
  for (const auto& [name, lines] : blocks) {
    const std::string data = "$s" + std::to_string(index);
    script << (first ? "" : ", \\\n     ") << data << " using 1:2 with linespoints lw 2 lc " << index + 1 << " title '" << gnuplot_text(time + ", " + name) << "'";
    first = false;
    for (std::size_t e = 0; e < measured.size(); ++e)
      script << ", \\\n     " << data << " using 1:" << e + 3 << " axes x1y2 with linespoints dt " << e + 2 << " lc " << index + 1 << " title '"
             << gnuplot_text(measured[e] + ", " + name) << "'";
    ++index;
  }
  script << "\n";
  return script.str();
}

std::string pareto_plot_script(const sweep_table& table, const std::string& time, const std::string& error, const fs::path& png) {
  std::map<std::string, std::vector<std::pair<double, double>>> points, front;
  for (const auto& row : table.rows) {
    const std::optional<double> t = sweep_table::number(row, time), e = sweep_table::number(row, error);
    if (!t || !e) continue;
    points[row.at("scene")].emplace_back(*t, *e);
    const auto pareto = row.find("pareto");
    if (pareto != row.end() && pareto->second == "1") front[row.at("scene")].emplace_back(*t, *e);
  }
  if (points.empty()) return {};
  std::ostringstream script;
  script << "set terminal pngcairo size 960,600 noenhanced\nset output '" << png.string() << "'\nset key outside bottom center horizontal\nset grid\n"
         << "set xlabel '" << gnuplot_text(time) << "'\nset ylabel '" << gnuplot_text(error) << "'\nset offsets graph 0.05, graph 0.05, graph 0.05, graph 0.05\n";
  int index = 0;
  for (auto& [scene, all] : points) {
    std::vector<std::pair<double, double>>& line = front[scene];
    std::sort(line.begin(), line.end());
    script << "$p" << index << " << EOD\n";
    for (const auto& [t, e] : all) script << format_real(t) << " " << format_real(e) << "\n";
    script << "EOD\n$f" << index << " << EOD\n";
    for (const auto& [t, e] : line) script << format_real(t) << " " << format_real(e) << "\n";
    script << "EOD\n";
    ++index;
  }
  script << "plot ";
  index = 0;
  for (const auto& [scene, all] : points) {
    script << (index ? ", \\\n     " : "") << "$p" << index << " using 1:2 with points pt 7 lc " << index + 1 << " title '" << gnuplot_text(scene) << "', \\\n     $f"
           << index << " using 1:2 with lines lw 2 lc " << index + 1 << " title '" << gnuplot_text("Pareto front, " + scene) << "'";
    ++index;
  }
  script << "\n";
  return script.str();
}

bool run_gnuplot(const fs::path& script_path, const std::string& script) {
  write_bytes_atomically(script_path, std::vector<std::uint8_t>(script.begin(), script.end()));
  std::string quoted = "'";
  for (char c : script_path.string()) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  quoted += "'";
  return std::system(("gnuplot " + quoted + " > /dev/null 2>&1").c_str()) == 0;
}

}  // namespace vplkit::cli
