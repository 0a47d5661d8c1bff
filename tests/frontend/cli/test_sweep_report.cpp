// The files of `vplkit sweep` (frontend/cli/sweep_report.hpp): the Pareto marking is the
// brute force's (every row against every row) on random tables with ties, and takes well under a
// second on 20,000 rows.
#include <doctest/doctest.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "frontend/cli/sweep_report.hpp"
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
