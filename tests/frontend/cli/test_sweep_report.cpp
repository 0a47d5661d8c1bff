// The files of `vplkit sweep` (frontend/cli/sweep_report.hpp): the Pareto marking is the
// brute force's (every row against every row) on random tables with ties, and takes well under a
// second on 20,000 rows; the CSV reads back every cell a hostile name can hold; no name reaches a
// gnuplot script; markdown shows names as text; the sweep's folder lock refuses a second holder
// and leaves the output lock free for the sweep's own writes.
#include <doctest/doctest.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "frontend/cli/sweep_report.hpp"
#include "frontend/core/files.hpp"
#include "frontend/core/setting.hpp"

namespace fs = std::filesystem;
using namespace vplkit;
using vplkit::cli::sweep_table;

namespace {

struct scratch_folder {
  fs::path path = fs::temp_directory_path() / ("vplkit-sweep-report-" + std::to_string(std::random_device{}()));
  scratch_folder() { fs::create_directories(path); }
  ~scratch_folder() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
};

// The definition, pair by pair: beaten when another row of the scene is at most as slow and at
// most as wrong, and strictly better on one of them.
std::vector<std::string> brute_force_pareto(const sweep_table& table) {
  std::vector<std::string> marks;
  for (const auto& row : table.rows) {
    const std::optional<double> t = sweep_table::number(row, "frame_ms"), e = sweep_table::number(row, "rel_rmse");
    if (!t || !e) {
      marks.emplace_back();
      continue;
    }
    bool beaten = false;
    for (const auto& other : table.rows) {
      if (&other == &row || other.at("scene") != row.at("scene")) continue;
      const std::optional<double> ot = sweep_table::number(other, "frame_ms"), oe = sweep_table::number(other, "rel_rmse");
      if (ot && oe && *ot <= *t && *oe <= *e && (*ot < *t || *oe < *e)) beaten = true;
    }
    marks.emplace_back(beaten ? "0" : "1");
  }
  return marks;
}

sweep_table random_table(std::mt19937& random, std::size_t rows, int distinct_values, int scenes) {
  sweep_table table;
  table.columns = {"scene", "technique", "frame_ms", "rel_rmse", "key"};
  std::uniform_int_distribution<int> value(0, distinct_values - 1), scene(0, scenes - 1), missing(0, 19);
  for (std::size_t i = 0; i < rows; ++i) {
    std::map<std::string, std::string> row;
    row["scene"] = "scene " + std::to_string(scene(random));
    row["technique"] = "rsm-alg6";
    // Few distinct values: equal times, equal errors and whole duplicates are common.
    row["frame_ms"] = missing(random) == 0 ? std::string() : format_real(0.5 * value(random));
    row["rel_rmse"] = missing(random) == 0 ? std::string("not measured") : format_real(0.01 * value(random));
    row["key"] = std::to_string(i);
    table.rows.push_back(std::move(row));
  }
  return table;
}

std::vector<std::string> pareto_column(const sweep_table& table) {
  std::vector<std::string> marks;
  for (const auto& row : table.rows) marks.push_back(row.at("pareto"));
  return marks;
}

}  // namespace

TEST_CASE("the Pareto front is the brute force's on random tables, ties and duplicates included") {
  std::mt19937 random(36);
  int fronts = 0, ties = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const std::size_t rows = 1 + static_cast<std::size_t>(trial % 60);
    sweep_table table = random_table(random, rows, 2 + trial % 7, 1 + trial % 3);
    const std::vector<std::string> expected = brute_force_pareto(table);
    cli::mark_pareto(table, "frame_ms", "rel_rmse");
    REQUIRE(pareto_column(table) == expected);
    for (const std::string& mark : expected) fronts += mark == "1";
    std::map<std::string, int> seen;
    for (const auto& row : table.rows) ties += ++seen[row.at("scene") + "|" + row.at("frame_ms")] > 1;
  }
  // The trials exercised what they are for: rows on and off the front, and equal times.
  CHECK(fronts > 400);
  CHECK(ties > 1000);
}

TEST_CASE("the Pareto front of hand-made cases: equal rows both on it, an equal time with a larger error off it, unmeasured rows unmarked") {
  sweep_table table;
  table.columns = {"scene", "frame_ms", "rel_rmse"};
  const std::vector<std::vector<std::string>> rows = {
      {"a", "1", "0.5"}, {"a", "1", "0.5"},  // duplicates: neither beats the other
      {"a", "1", "0.6"},                     // as fast, larger error: beaten
      {"a", "2", "0.5"},                     // slower, same error: beaten
      {"a", "2", "0.1"},                     // slower, smaller error: on the front
      {"b", "5", "0.9"},                     // another scene: its own front
      {"a", "", "0.01"}, {"a", "1", "inf"}, {"a", "nan", "0.2"}};
  for (const auto& cells : rows) table.rows.push_back({{"scene", cells[0]}, {"frame_ms", cells[1]}, {"rel_rmse", cells[2]}});
  cli::mark_pareto(table, "frame_ms", "rel_rmse");
  CHECK(pareto_column(table) == std::vector<std::string>{"1", "1", "0", "0", "1", "1", "", "", ""});
}

TEST_CASE("the Pareto marking of 20,000 rows takes well under a second") {
  std::mt19937 random(20000);
  sweep_table table = random_table(random, 20000, 5000, 4);
  const auto start = std::chrono::steady_clock::now();
  cli::mark_pareto(table, "frame_ms", "rel_rmse");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  MESSAGE("mark_pareto on 20,000 rows: " << seconds << " s");
  // Comparing every pair took minutes; the bound leaves room for a loaded machine and the
  // sanitizers, and still catches the quadratic version by a factor of tens.
  CHECK(seconds < 2.0);
  int on_front = 0;
  for (const auto& row : table.rows) on_front += row.at("pareto") == "1";
  CHECK(on_front > 0);
  CHECK(on_front < 2000);
}

TEST_CASE("the CSV reads back every cell a hostile name can hold") {
  const scratch_folder folder;
  sweep_table table;
  table.columns = {"scene", "technique", "radius", "key"};
  const std::vector<std::string> scenes = {"evil\nsystem \"touch MARKER\"\n#", "comma, quote \" and \\ backslash", "cr\rlf\r\nend",
                                           "'apostrophe'", "", "\"", "=1+2", "tab\there"};
  for (std::size_t i = 0; i < scenes.size(); ++i)
    table.rows.push_back({{"scene", scenes[i]}, {"technique", "rsm-alg6"}, {"radius", "0.5"}, {"key", std::to_string(i)}});
  const std::string text = cli::sweep_csv(table);
  write_bytes_atomically(folder.path / "sweep.csv", std::vector<std::uint8_t>(text.begin(), text.end()));
  const sweep_table back = cli::read_sweep_csv(folder.path / "sweep.csv");
  CHECK(back.columns == table.columns);
  REQUIRE(back.rows.size() == table.rows.size());
  for (std::size_t i = 0; i < scenes.size(); ++i) CHECK(back.rows[i].at("scene") == scenes[i]);

  // A row cut in the middle of a quoted cell is named, not read as something else.
  const std::string cut = text.substr(0, text.find("system"));
  write_bytes_atomically(folder.path / "cut.csv", std::vector<std::uint8_t>(cut.begin(), cut.end()));
  CHECK_THROWS_WITH_AS(cli::read_sweep_csv(folder.path / "cut.csv"), doctest::Contains("cut.csv:2: a quoted cell is not closed"), vplkit::error);
}

TEST_CASE("no name reaches a gnuplot script: the titles and categories are fields of the data file") {
  const std::string hostile = "evil\nsystem \"touch MARKER\"\n#'\\ `id` $(id)";
  sweep_table table;
  table.columns = {"scene", "technique", "frame_ms", "rel_rmse", "pareto"};
  for (int i = 0; i < 4; ++i)
    table.rows.push_back({{"scene", hostile + std::to_string(i % 2)},
                          {"technique", i < 2 ? "rsm-alg6" : hostile},
                          {"frame_ms", format_real(1.0 + i)},
                          {"rel_rmse", format_real(0.5 - 0.1 * i)},
                          {"pareto", "1"}});
  const std::optional<cli::gnuplot_plot> axis = cli::axis_plot(table, "technique", {"scene"}, "frame_ms", {"rel_rmse"});
  const std::optional<cli::gnuplot_plot> pareto = cli::pareto_plot(table, "frame_ms", "rel_rmse");
  REQUIRE(axis);
  REQUIRE(pareto);
  for (const cli::gnuplot_plot* plot : {&*axis, &*pareto}) {
    for (const char* piece : {"touch", "system", "MARKER", "`id`", "$(id)", "evil"}) CHECK(plot->script.find(piece) == std::string::npos);
    // Every title in the data: one line each (a line end would split the block), no double
    // quote (gnuplot ends a field there), the backslash doubled (gnuplot reads escapes).
    CHECK(plot->data.find("evil system ''touch MARKER'' #'\\\\ `id` $(id)") != std::string::npos);
    CHECK(plot->data.find('"') == std::string::npos);
    // The output and the data are the strings ARG2 and ARG1, never a path in the script.
    CHECK(plot->script.find("set output ARG2") != std::string::npos);
    CHECK(plot->script.find("ARG1 index 0") != std::string::npos);
  }
  // The categories (technique names here) are tic labels read from the data too.
  CHECK(axis->script.find(":xtic(4)") != std::string::npos);
}

TEST_CASE("markdown shows names as text: no table cell, heading, link or HTML comes from a name") {
  const std::string text = cli::markdown_text("a|b\nc <script>x</script> [link](http://x) *em* _u_ `code` # \\ &amp;");
  CHECK(text.find('\n') == std::string::npos);
  for (std::size_t i = 0; i < text.size(); ++i)
    if (std::string("|<>[]()*_`#&").find(text[i]) != std::string::npos) {
      const bool escaped = i > 0 && text[i - 1] == '\\';
      CHECK_MESSAGE(escaped, "unescaped '" << text[i] << "' in " << text);
    }
  // A code block's fence is longer than any backtick run it holds.
  CHECK(cli::markdown_code_block("a ``` b ```` c", "sh") == "`````sh\na ``` b ```` c\n`````\n");
  CHECK(cli::markdown_code_block("plain", "") == "```\nplain\n```\n");
}

TEST_CASE("the sweep's lock: a second holder is refused at once, and the folder's output lock stays free for the holder's writes") {
  const scratch_folder folder;
  const folder_lock sweep(folder.path, 0.0, ".vplkit-sweep.lock");
  CHECK(fs::exists(folder.path / ".vplkit-sweep.lock"));
  CHECK_THROWS_AS(folder_lock(folder.path, 0.0, ".vplkit-sweep.lock"), folder_lock_busy);
  // The holder's own writes take the output lock, another file: they do not wait on themselves.
  write_bytes_atomically(folder.path / "sweep.csv", {'x'});
  CHECK(fs::file_size(folder.path / "sweep.csv") == 1);
}
