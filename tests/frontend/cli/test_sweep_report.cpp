// The files of `vplkit sweep` (frontend/cli/sweep_report.hpp): the Pareto marking is the
// brute force's (every row against every row) on random tables with ties, without noise and
// within the noise, and takes well under a second on 20,000 rows; rows within each other's noise
// on the front are ties; the reference's noise (frontend/image/reference_noise.hpp) is what
// synthetic noise of a known size gives; the CSV reads back every cell a hostile name can hold; no name reaches a
// gnuplot script; markdown shows names as text; the sweep's folder lock refuses a second holder
// and leaves the output lock free for the sweep's own writes.
#include <doctest/doctest.h>

#include <filesystem>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "frontend/cli/sweep_report.hpp"
#include "frontend/core/files.hpp"
#include "frontend/core/setting.hpp"
#include "frontend/image/metrics.hpp"
#include "frontend/image/reference_noise.hpp"
#include "tests/gl_test_helpers.hpp"

namespace fs = std::filesystem;
using namespace vplkit;
using vplkit::cli::sweep_table;

namespace {

using vplkit::testing::scratch_folder;

// The definition, pair by pair: B beats A when B's upper bounds are at most A's lower bounds on
// both axes and below on one, each value +- its standard error when `within_noise`, else exact
// (B at most as slow and as wrong as A, and strictly better on one). A row never beats itself:
// its bounds are not below its own.
std::vector<std::string> brute_force_pareto(const sweep_table& table, bool within_noise = false) {
  const auto noise = [&](const std::map<std::string, std::string>& row) {
    return within_noise ? std::pair(cli::time_se(row, "frame_ms"), cli::quality_se(row, "rel_rmse")) : std::pair(0.0, 0.0);
  };
  std::vector<std::string> marks;
  for (const auto& row : table.rows) {
    const std::optional<double> t = sweep_table::number(row, "frame_ms"), e = sweep_table::number(row, "rel_rmse");
    if (!t || !e) {
      marks.emplace_back();
      continue;
    }
    const auto [dt, de] = noise(row);
    bool beaten = false;
    for (const auto& other : table.rows) {
      if (other.at("scene") != row.at("scene")) continue;
      const std::optional<double> ot = sweep_table::number(other, "frame_ms"), oe = sweep_table::number(other, "rel_rmse");
      if (!ot || !oe) continue;
      const auto [odt, ode] = noise(other);
      const double t_high = *ot + odt, e_high = *oe + ode, t_low = *t - dt, e_low = *e - de;
      if (t_high <= t_low && e_high <= e_low && (t_high < t_low || e_high < e_low)) beaten = true;
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

// Its time on 20,000 rows is bench/sweep_pareto.cpp's (vplkit_sweep_bench), not asserted here.
TEST_CASE("the Pareto marking of 20,000 rows keeps a front, not every row") {
  std::mt19937 random(20000);
  sweep_table table = random_table(random, 20000, 5000, 4);
  cli::mark_pareto(table, "frame_ms", "rel_rmse");
  int on_front = 0;
  for (const auto& row : table.rows) on_front += row.at("pareto") == "1";
  CHECK(on_front > 0);
  CHECK(on_front < 2000);
}

namespace {

}  // namespace

TEST_CASE("the Pareto front within the noise is the brute force's on random noisy tables") {
  std::mt19937 random(41);
  int fronts = 0, kept_by_noise = 0, tied = 0;
  for (int trial = 0; trial < 300; ++trial) {
    sweep_table table = random_table(random, 1 + static_cast<std::size_t>(trial % 50), 3 + trial % 9, 1 + trial % 2);
    std::uniform_int_distribution<int> noise(0, 4), seeds(1, 3);
    for (auto& row : table.rows) {
      // Relative timing noise 0 to 20 %, the error's from seeds and the reference, some rows without.
      row["frame_ms_noise"] = format_real(0.05 * noise(random));
      row["rel_rmse_ref_se"] = noise(random) == 0 ? std::string() : format_real(0.004 * noise(random));
      row["rel_rmse_sd"] = format_real(0.01 * noise(random));
      row["seeds"] = std::to_string(seeds(random));
    }
    const std::vector<std::string> exact = brute_force_pareto(table), expected = brute_force_pareto(table, true);
    cli::mark_pareto(table, "frame_ms", "rel_rmse");
    REQUIRE(pareto_column(table) == expected);
    for (std::size_t i = 0; i < expected.size(); ++i) {
      fronts += expected[i] == "1";
      kept_by_noise += expected[i] == "1" && exact[i] == "0";
      tied += !table.rows[i].at("tie").empty();
      // A tie is a row of the front.
      if (!table.rows[i].at("tie").empty()) CHECK(expected[i] == "1");
    }
  }
  // The noise kept rows the exact front drops, and ties were marked.
  CHECK(fronts > 300);
  CHECK(kept_by_noise > 100);
  CHECK(tied > 100);
}

TEST_CASE("a noisy machine's front: rows within each other's noise are ties, a row beyond it is dominated") {
  sweep_table table;
  table.columns = {"scene", "frame_ms", "frame_ms_noise", "rel_rmse", "rel_rmse_ref_se"};
  const std::vector<std::vector<std::string>> rows = {
      {"a", "1.0", "0.2", "0.50", "0.02"},   // A
      {"a", "1.1", "0.2", "0.49", "0.02"},   // B: within A's noise on both: a tie with A
      {"a", "1.05", "0.2", "0.60", "0.01"},  // C: slower and worse than A, but not beyond the time's noise: kept, no tie
      {"a", "3.0", "0.05", "0.70", "0.01"},  // D: slower and worse beyond both noises: dominated
      {"a", "5.0", "0.05", "0.10", "0.01"},  // E: slow, far better: on the front alone
  };
  for (const auto& cells : rows)
    table.rows.push_back({{"scene", cells[0]}, {"frame_ms", cells[1]}, {"frame_ms_noise", cells[2]}, {"rel_rmse", cells[3]}, {"rel_rmse_ref_se", cells[4]}});
  cli::mark_pareto(table, "frame_ms", "rel_rmse");
  CHECK(pareto_column(table) == std::vector<std::string>{"1", "1", "1", "0", "1"});
  std::vector<std::string> ties;
  for (const auto& row : table.rows) ties.push_back(row.at("tie"));
  CHECK(ties == std::vector<std::string>{"1", "1", "", "", ""});
  // Without the noise columns, the exact front: C and D are dominated by A, B and E stay.
  for (auto& row : table.rows) row.erase("frame_ms_noise"), row.erase("rel_rmse_ref_se");
  cli::mark_pareto(table, "frame_ms", "rel_rmse");
  CHECK(pareto_column(table) == std::vector<std::string>{"1", "1", "0", "0", "1"});
}

TEST_CASE("the Pareto marking within the noise of 20,000 rows keeps at least the exact front") {
  // Within the noise fewer rows are beaten: every row on the exact front stays on it.
  std::mt19937 random(2041);
  sweep_table table = random_table(random, 20000, 5000, 4);
  cli::mark_pareto(table, "frame_ms", "rel_rmse");
  const std::vector<std::string> exact = pareto_column(table);
  for (auto& row : table.rows) {
    row["frame_ms_noise"] = "0.1";
    row["rel_rmse_ref_se"] = "0.01";
  }
  cli::mark_pareto(table, "frame_ms", "rel_rmse");
  const std::vector<std::string> noisy = pareto_column(table);
  int exact_front = 0, noisy_front = 0, dropped = 0;
  for (std::size_t i = 0; i < exact.size(); ++i) {
    dropped += exact[i] == "1" && noisy[i] != "1";
    exact_front += exact[i] == "1";
    noisy_front += noisy[i] == "1";
  }
  CHECK(dropped == 0);
  CHECK(noisy_front > exact_front);
}

TEST_CASE("the reference's noise: synthetic Gaussian noise of a known size is what reference_noise_of reports") {
  // A truth of level 1 +- 0.5, a candidate 10 % off it everywhere (its rel_rmse against the truth
  // is known), two references with noise sigma = 0.2 per value.
  std::mt19937 random(64);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> level(0.5, 1.5);
  const int w = 96, h = 64;
  const double sigma = 0.2;
  image truth(w, h), candidate(w, h);
  for (std::size_t i = 0; i < truth.texels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      truth.texels[i][c] = static_cast<float>(level(random));
      candidate.texels[i][c] = truth.texels[i][c] * 1.1f;
    }
  const double true_rmse = relative_error_of(candidate, truth).rmse;
  std::vector<double> biases, rmses;
  double bias_se = 0.0, rmse_se = 0.0;
  const int trials = 60;
  for (int trial = 0; trial < trials; ++trial) {
    image first(w, h), second(w, h);
    for (std::size_t i = 0; i < truth.texels.size(); ++i)
      for (int c = 0; c < 3; ++c) {
        first.texels[i][c] = static_cast<float>(truth.texels[i][c] + sigma * gauss(random));
        second.texels[i][c] = static_cast<float>(truth.texels[i][c] + sigma * gauss(random));
      }
    const reference_noise noise = reference_noise_of(candidate, first, variance_of_two(first, second));
    REQUIRE(noise.defined);
    const relative_error raw = relative_error_of(candidate, first);
    // The noise as a rel_rmse: sigma / mean level (1), within the estimate's own spread.
    CHECK(noise.noise == doctest::Approx(sigma).epsilon(0.03));
    // Raw: the truth's error and the noise in quadrature; corrected: the truth's error alone.
    CHECK(raw.rmse == doctest::Approx(std::sqrt(true_rmse * true_rmse + sigma * sigma)).epsilon(0.03));
    CHECK(noise.rmse_corrected == doctest::Approx(true_rmse).epsilon(0.05));
    CHECK(noise.share == doctest::Approx(noise.noise / raw.rmse).epsilon(1e-9));
    biases.push_back(raw.bias);
    rmses.push_back(raw.rmse);
    bias_se += noise.bias_se / trials;
    rmse_se += noise.rmse_se / trials;
  }
  // The standard errors are the trials' spreads (within what 60 trials resolve, about 20 %).
  const auto spread = [](const std::vector<double>& values) {
    double mean = 0.0, squares = 0.0;
    for (double v : values) mean += v / static_cast<double>(values.size());
    for (double v : values) squares += (v - mean) * (v - mean);
    return std::sqrt(squares / static_cast<double>(values.size() - 1));
  };
  CHECK(bias_se == doctest::Approx(spread(biases)).epsilon(0.25));
  CHECK(rmse_se == doctest::Approx(spread(rmses)).epsilon(0.25));
  // Refusals: a negative variance, another size.
  image negative(w, h);
  negative.texels[3] = glm::vec4(-1.0f);
  CHECK_THROWS_WITH_AS(reference_noise_of(candidate, truth, negative), doctest::Contains("variance is negative"), vplkit::error);
  CHECK_THROWS_AS(reference_noise_of(candidate, truth, image(4, 4)), vplkit::error);
}

TEST_CASE("the CSV reads back every cell a hostile name can hold") {
  const scratch_folder folder("sweep-report");
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
  // Columns x, time, its error bar, rel_rmse, its error bar, the label.
  CHECK(axis->script.find(":xtic(6)") != std::string::npos);
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
  const scratch_folder folder("sweep-report");
  const folder_lock sweep(folder.path, 0.0, ".vplkit-sweep.lock");
  CHECK(fs::exists(folder.path / ".vplkit-sweep.lock"));
  CHECK_THROWS_AS(folder_lock(folder.path, 0.0, ".vplkit-sweep.lock"), folder_lock_busy);
  // The holder's own writes take the output lock, another file: they do not wait on themselves.
  write_bytes_atomically(folder.path / "sweep.csv", {'x'});
  CHECK(fs::file_size(folder.path / "sweep.csv") == 1);
}
