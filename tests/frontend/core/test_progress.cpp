// Long work announced and bounded (frontend/core/progress.hpp, frontend/core/parallel.hpp): plain
// progress lines at the interval when the output is not a terminal, a deadline that stops the
// workers and fails finish(), and exceptions from worker threads brought back to the caller.
#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <new>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>

#include "frontend/core/error.hpp"
#include "frontend/core/parallel.hpp"
#include "frontend/core/progress.hpp"

using namespace vplkit;

namespace {

int count_lines(const std::string& text) { return static_cast<int>(std::count(text.begin(), text.end(), '\n')); }

}  // namespace

TEST_CASE("progress on a pipe: a plain line every interval, the last one says done") {
  std::ostringstream out;
  progress_settings settings;
  settings.out = &out;
  settings.terminal = false;
  settings.interval_seconds = 0.05;
  progress_monitor monitor("test work", 100, "items", settings);
  for (int i = 0; i < 100; ++i) {
    monitor.advance();
    std::this_thread::sleep_for(std::chrono::milliseconds(4));
  }
  monitor.finish();
  const std::string text = out.str();
  CAPTURE(text);
  // About 0.4 s of work at 0.05 s: several lines (a loaded machine may skip some), each a whole line.
  CHECK(count_lines(text) >= 3);
  CHECK(text.find("test work: ") != std::string::npos);
  CHECK(text.find(" of 100 items), ") != std::string::npos);
  CHECK(text.find(" elapsed") != std::string::npos);
  CHECK(text.find("\r") == std::string::npos);  // no bar redrawn in place on a pipe
  CHECK(text.rfind("test work: done in ") != std::string::npos);
}

TEST_CASE("a deadline stops the workers and finish() refuses the partial work") {
  std::ostringstream out;
  progress_settings settings;
  settings.out = &out;
  settings.deadline = steady_seconds() + 0.2;
  settings.deadline_name = "--max-seconds 0.2";
  progress_monitor monitor("slow work", 1000, "items", settings);
  std::atomic<int> done{0};
  const double start = steady_seconds();
  parallel_for(1000, 2, [&](int) {
    if (monitor.stopped()) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    ++done;
    monitor.advance();
  });
  const double took = steady_seconds() - start;
  CHECK(took < 2.0);  // 1000 x 10 ms on 2 threads would be 5 s
  CHECK(done < 1000);
  CHECK_THROWS_WITH_AS(monitor.finish(), doctest::Contains("slow work: stopped after"), vplkit::error);
  // Work that completes before its deadline is kept.
  progress_settings generous;
  generous.deadline = steady_seconds() + 60.0;
  progress_monitor quick("quick work", 10, "items", generous);
  quick.advance(10);
  CHECK_NOTHROW(quick.finish());
  CHECK(!quick.stopped());
}

TEST_CASE("parallel_for brings a worker's exception back to the caller and stops the others") {
  std::atomic<int> ran{0};
  CHECK_THROWS_WITH_AS(parallel_for(10000, 4,
                                    [&](int i) {
                                      ++ran;
                                      if (i == 7) throw vplkit::error("item 7 refused");
                                      std::this_thread::sleep_for(std::chrono::microseconds(50));
                                    }),
                       "item 7 refused", vplkit::error);
  CHECK(ran < 10000);
  CHECK_THROWS_AS(parallel_for(3, 3, [](int i) { if (i == 2) throw std::bad_alloc(); }), std::bad_alloc);
}

TEST_CASE("counts and durations as messages show them") {
  CHECK(count_text(3400) == "3400");
  CHECK(count_text(5.5e11) == "5.5e+11");
  CHECK(duration_text(45) == "45 s");
  CHECK(duration_text(12 * 60) == "12 min");
  CHECK(duration_text(44.3 * 3600) == "44.3 h");
  CHECK(duration_text(3 * 86400) == "3.0 days");
}

TEST_CASE("VPLKIT_PROGRESS_SECONDS sets the interval of the plain lines: 5 s without it, seconds in [0.1, 86400]") {
  CHECK(progress_interval_from_text(nullptr) == 5.0);
  CHECK(progress_interval_from_text("") == 5.0);
  CHECK(progress_interval_from_text("1") == 1.0);
  CHECK(progress_interval_from_text("2.5") == 2.5);
  CHECK(progress_interval_from_text(".5") == 0.5);
  CHECK(progress_interval_from_text("5.") == 5.0);
  CHECK(progress_interval_from_text("00001") == 1.0);
  CHECK(progress_interval_from_text("0.1") == 0.1);
  CHECK(progress_interval_from_text("86400") == 86400.0);
  CHECK(progress_interval_from_text("1.00000000000000000000") == 1.0);
  const std::string format = "VPLKIT_PROGRESS_SECONDS must be digits with at most one point (like 2.5), a number of seconds in [0.1, 86400]; got '";
  for (const char* refused : {"-1", "+5", "1e1", "inf", "nan", "5 s", " 5", "5x", "0x10p-4", "1.2.3", ".", "junk"}) {
    CAPTURE(refused);
    CHECK_THROWS_WITH_AS(progress_interval_from_text(refused), (format + refused + "'").c_str(), vplkit::error);
  }
  const std::string range = "VPLKIT_PROGRESS_SECONDS must be a number of seconds in [0.1, 86400]; got '";
  for (const char* refused : {"0", "0.", "0.05", "0.0999", "86400.5", "86401", "99999999999999999999999999999"}) {
    CAPTURE(refused);
    CHECK_THROWS_WITH_AS(progress_interval_from_text(refused), (range + refused + "'").c_str(), vplkit::error);
  }
  // A long value is echoed shortened, not whole.
  const std::string long_value(300, '7');
  CHECK_THROWS_WITH_AS(progress_interval_from_text(long_value.c_str()), (range + excerpt(long_value) + "'").c_str(), vplkit::error);
  CHECK(excerpt(long_value).size() < long_value.size());
  // Digits beyond double's range are too many seconds, not a malformed value.
  const std::string huge(400, '9');
  CHECK_THROWS_WITH_AS(progress_interval_from_text(huge.c_str()), (range + excerpt(huge) + "'").c_str(), vplkit::error);
  // The monitor on stderr takes the variable's interval: the process's own environment, read, not
  // set here (setenv while the GL driver's threads may call getenv is a race).
  CHECK(progress_on_stderr().interval_seconds == progress_interval_from_text(std::getenv("VPLKIT_PROGRESS_SECONDS")));
}
