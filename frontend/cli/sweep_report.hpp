// The files of `vplkit sweep`: DIR/sweep.csv (one row per configuration and scene, a column per
// varied setting named as the setting, the frame time and its passes, the quality numbers with
// their spread over seeds, whether the row is on the Pareto front of error against time), read
// back to resume; DIR/sweep.md; and a gnuplot plot per varied setting (DIR/<setting>.png) and of
// the Pareto front (DIR/pareto.png).
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace vplkit::cli {

/// A sweep's rows: the columns in order and each row's cells by column.
struct sweep_table {
  std::vector<std::string> columns;
  std::vector<std::map<std::string, std::string>> rows;

  void add_column(const std::string& name);
  /// The cell as a number, or nullopt when empty or not a number.
  static std::optional<double> number(const std::map<std::string, std::string>& row, const std::string& column);
};

/// Reads DIR/sweep.csv back; throws vplkit::error for a file this writer did not write.
sweep_table read_sweep_csv(const std::filesystem::path& path);
/// The CSV text: RFC 4180 quoting where a cell holds a comma or a quote.
std::string sweep_csv(const sweep_table& table);

/// Marks `pareto` = 1 on the rows no other row of the same scene beats on both `time` and
/// `error` (lower is better; one of them strictly), 0 on the others, and empty where either is
/// not measured (empty, not a number, or not finite). O(n log n): per scene, one pass over the
/// rows sorted by time.
void mark_pareto(sweep_table& table, const std::string& time, const std::string& error);

/// A gnuplot script drawing `ys` against the column `x` (numbers, else categories in row order),
/// one line per distinct value of `series`, time on the left axis and the other columns on the
/// right; returns "" when nothing can be drawn.
std::string axis_plot_script(const sweep_table& table, const std::string& x, const std::vector<std::string>& series, const std::string& time,
                             const std::vector<std::string>& errors, const std::filesystem::path& png);
/// A gnuplot script of `error` against `time`, per scene, the Pareto front joined.
std::string pareto_plot_script(const sweep_table& table, const std::string& time, const std::string& error, const std::filesystem::path& png);

/// Runs gnuplot on `script` (kept as `script_path`); false when gnuplot is missing or fails.
bool run_gnuplot(const std::filesystem::path& script_path, const std::string& script);

}  // namespace vplkit::cli
