// The files of `vplkit sweep`: DIR/sweep.csv (one row per configuration and scene, a column per
// varied setting named as the setting, the frame time and its passes, the quality numbers with
// their spread over seeds, whether the row is on the Pareto front of error against time), read
// back to resume; DIR/sweep.md; and a gnuplot plot per varied setting (DIR/<setting>.png) and of
// the Pareto front (DIR/pareto.png), each with its script and data kept beside it.
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

/// Reads DIR/sweep.csv back (RFC 4180: a quoted cell may hold commas, quotes and line ends);
/// throws vplkit::error for a file this writer did not write.
sweep_table read_sweep_csv(const std::filesystem::path& path);
/// The CSV text: RFC 4180 quoting where a cell holds a comma, a quote or a line end.
std::string sweep_csv(const sweep_table& table);

/// The standard error of a row's `time`: its mean's relative standard error (the column
/// `<time>_noise`) times the time; 0 where either is not measured.
double time_se(const std::map<std::string, std::string>& row, const std::string& time);
/// The standard error of a row's quality `column`: the seeds' (`<column>_sd` / sqrt(`seeds`)) and
/// the reference's (`<column>_ref_se`) together, in quadrature; 0 where neither is known.
double quality_se(const std::map<std::string, std::string>& row, const std::string& column);

/// Marks `pareto` = 1 on the rows no other row of the same scene beats beyond the noise on both
/// `time` and `error` (lower is better), 0 on the others, and empty where either is not measured
/// (empty, not a number, or not finite). With each value +- its standard error (time_se,
/// quality_se), B beats A when B's upper bound is at most A's lower bound on both axes and below
/// it on one; without noise, when B is at most as slow and as wrong and better on one. `tie`: the
/// rows of a scene's front, by time, each within the noise of the next on both axes (their
/// intervals overlap) share a number (1, 2, ... per scene); empty for a row alone. O(n log n).
void mark_pareto(sweep_table& table, const std::string& time, const std::string& error);

/// A plot for gnuplot: the script and the data it draws. Nothing a user named (a file name, a
/// path, a scene name, a setting's value) is in the script: it is run as
/// `gnuplot -c SCRIPT DATA PNG`, reading the data file and the PNG's path as the strings ARG1 and
/// ARG2, and the titles and category names as fields of the data file (columnheader, xtic),
/// which gnuplot shows and never runs.
struct gnuplot_plot {
  std::string script;
  std::string data;
};

/// `ys` against the column `x` (numbers, else categories in row order), one line per distinct
/// value of `series`, time on the left axis and the other columns on the right; nullopt when
/// nothing can be drawn.
std::optional<gnuplot_plot> axis_plot(const sweep_table& table, const std::string& x, const std::vector<std::string>& series, const std::string& time,
                                      const std::vector<std::string>& errors);
/// `error` against `time`, per scene, the Pareto front joined; nullopt when nothing is measured.
std::optional<gnuplot_plot> pareto_plot(const sweep_table& table, const std::string& time, const std::string& error);

/// Runs `gnuplot -c script data png` (found on PATH, no shell between), its output kept for the
/// message. "" when it succeeded; else why not: "gnuplot is not installed (...)", or its exit
/// status and the last lines it printed.
std::string run_gnuplot(const std::filesystem::path& script, const std::filesystem::path& data, const std::filesystem::path& png);

/// `text` as markdown shows it literally in a table cell or a heading: every ASCII punctuation
/// character backslash-escaped (no link, no HTML, no cell boundary), control characters and line
/// ends as spaces.
std::string markdown_text(const std::string& text);
/// `text` as a fenced code block: the fence longer than any run of backticks in it.
std::string markdown_code_block(const std::string& text, const std::string& language = {});

}  // namespace vplkit::cli
