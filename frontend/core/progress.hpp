// Long work announced, reported and bounded (the references: minutes to hours of ray casting).
// A progress_monitor counts the units the workers finish and, from a thread of its own, reports
// them: a bar redrawn in place on a terminal, a plain line every few seconds otherwise (a log, a
// pipe, CI), so that a run nobody watches still says how far it is. It also holds the deadline
// (--max-seconds): once passed, stopped() turns true, the workers return, and finish() throws a
// vplkit::error saying so, before anything is written.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <limits>
#include <mutex>
#include <ostream>
#include <string>
#include <thread>

namespace vplkit {

/// Seconds on the steady clock (for deadlines and elapsed times).
double steady_seconds();

/// "1.2e+09", "3400": a count as a message shows it (3 significant digits from a million on).
std::string count_text(double count);
/// "45 s", "12 min", "3.4 h", "2.1 days": a duration as a message shows it.
std::string duration_text(double seconds);

/// Where and how a monitor reports, and when the work must stop.
struct progress_settings {
  std::ostream* out = nullptr;   ///< nullptr: silent
  bool terminal = false;         ///< a bar redrawn in place, else a plain line every interval
  double interval_seconds = 5.0; ///< between plain lines
  double deadline = std::numeric_limits<double>::infinity();  ///< steady_seconds() at which the work stops
  std::string deadline_name;     ///< what set the deadline, for the message ("--max-seconds 60")
};

/// The interval of the plain progress lines that `text` asks for: digits with at most one point
/// (2.5, 10, .5), in [0.1, 86400] seconds; nullptr or "" is the default, 5 s. Throws vplkit::error
/// naming VPLKIT_PROGRESS_SECONDS otherwise (a sign, an exponent, spaces, "inf": refused, not
/// guessed at).
double progress_interval_from_text(const char* text);
/// $VPLKIT_PROGRESS_SECONDS read by progress_interval_from_text: a log that keeps fewer lines sets
/// more, a test that must see several lines in a short run sets less.
double progress_interval_from_environment();

/// Progress on stderr (a bar when it is a terminal, else lines every
/// progress_interval_from_environment() seconds), no deadline. Throws as that does.
progress_settings progress_on_stderr();

class progress_monitor {
 public:
  /// Starts reporting `label` over `total` units named `unit` ("pixels", "receivers").
  progress_monitor(std::string label, std::uint64_t total, std::string unit, progress_settings settings);
  ~progress_monitor();
  progress_monitor(const progress_monitor&) = delete;
  progress_monitor& operator=(const progress_monitor&) = delete;

  /// `count` more units done (any thread).
  void advance(std::uint64_t count = 1) { done_.fetch_add(count, std::memory_order_relaxed); }
  /// Whether the deadline has passed: workers check it and return early.
  bool stopped() const { return stopped_.load(std::memory_order_relaxed); }
  std::uint64_t done() const { return done_.load(std::memory_order_relaxed); }
  /// Stops the reporter and prints the last line. Throws vplkit::error when the deadline stopped
  /// the work ("... stopped after 61 s at 40 % (--max-seconds 60); nothing is written").
  void finish();

 private:
  void report(bool last);
  void run();

  std::string label_, unit_;
  std::uint64_t total_;
  progress_settings settings_;
  double start_;
  std::atomic<std::uint64_t> done_{0};
  std::atomic<bool> stopped_{false};
  std::mutex mutex_;
  std::condition_variable wake_;
  bool finishing_ = false;
  bool finished_ = false;
  std::thread reporter_;
};

}  // namespace vplkit
