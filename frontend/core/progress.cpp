#include "frontend/core/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>

#include "frontend/core/error.hpp"
#include "frontend/core/setting.hpp"

namespace vplkit {

double steady_seconds() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

std::string count_text(double count) {
  char text[32];
  if (count < 1e6) std::snprintf(text, sizeof text, "%.0f", count);
  else std::snprintf(text, sizeof text, "%.3g", count);
  return text;
}

std::string duration_text(double seconds) {
  char text[32];
  if (!std::isfinite(seconds)) return "forever";
  if (seconds < 90.0) std::snprintf(text, sizeof text, "%.0f s", std::max(seconds, 0.0));
  else if (seconds < 90.0 * 60.0) std::snprintf(text, sizeof text, "%.0f min", seconds / 60.0);
  else if (seconds < 48.0 * 3600.0) std::snprintf(text, sizeof text, "%.1f h", seconds / 3600.0);
  else std::snprintf(text, sizeof text, "%.1f days", seconds / 86400.0);
  return text;
}

double progress_interval_from_text(const char* text) {
  if (!text || !*text) return progress_settings{}.interval_seconds;
  const std::string_view digits(text);
  // Digits with at most one point and nothing else: parse_real alone would also take spaces, a
  // sign, an exponent, "inf" and "nan".
  if (digits.find_first_not_of("0123456789.") != std::string_view::npos || std::count(digits.begin(), digits.end(), '.') > 1 || digits == ".")
    throw error("VPLKIT_PROGRESS_SECONDS must be digits with at most one point (like 2.5), a number of seconds in [0.1, 86400]; got '" + excerpt(digits) + "'");
  // Such digits that parse_real refuses are beyond a double's range.
  const std::optional<double> seconds = parse_real(digits);
  if (!seconds || !(*seconds >= 0.1 && *seconds <= 86400.0))
    throw error("VPLKIT_PROGRESS_SECONDS must be a number of seconds in [0.1, 86400]; got '" + excerpt(digits) + "'");
  return *seconds;
}

double progress_interval_from_environment() { return progress_interval_from_text(std::getenv("VPLKIT_PROGRESS_SECONDS")); }

progress_settings progress_on_stderr() {
  progress_settings settings;
  settings.out = &std::cerr;
  settings.terminal = isatty(2) != 0;
  settings.interval_seconds = progress_interval_from_environment();
  return settings;
}

progress_monitor::progress_monitor(std::string label, std::uint64_t total, std::string unit, progress_settings settings)
    : label_(std::move(label)), unit_(std::move(unit)), total_(std::max<std::uint64_t>(total, 1)), settings_(std::move(settings)), start_(steady_seconds()) {
  if (settings_.out || std::isfinite(settings_.deadline)) reporter_ = std::thread([this] { run(); });
}

progress_monitor::~progress_monitor() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    finishing_ = true;
  }
  wake_.notify_all();
  if (reporter_.joinable()) reporter_.join();
}

void progress_monitor::run() {
  // A bar is redrawn 4 times a second; plain lines every interval.
  const double step = settings_.terminal ? 0.25 : std::max(settings_.interval_seconds, 0.01);
  double next_line = start_ + step;
  std::unique_lock<std::mutex> lock(mutex_);
  while (!finishing_) {
    const double now = steady_seconds();
    const double wake_at = std::min(next_line, settings_.deadline);
    if (now < wake_at) {
      wake_.wait_for(lock, std::chrono::duration<double>(wake_at - now));
      continue;
    }
    if (now >= settings_.deadline) stopped_.store(true, std::memory_order_relaxed);
    if (now >= next_line) {
      if (settings_.out && !stopped()) report(false);
      next_line = now + step;
    }
    if (stopped()) {
      // Nothing more to time: wait for finish().
      wake_.wait(lock, [this] { return finishing_; });
    }
  }
}

void progress_monitor::report(bool last) {
  const double elapsed = steady_seconds() - start_;
  const std::uint64_t now_done = std::min(done(), total_);
  const double fraction = static_cast<double>(now_done) / static_cast<double>(total_);
  const int percent = static_cast<int>(std::floor(100.0 * fraction));
  std::ostream& out = *settings_.out;
  if (last) {
    if (settings_.terminal) out << "\r";
    out << label_ << ": done in " << duration_text(elapsed) << (settings_.terminal ? std::string(40, ' ') : std::string()) << "\n";
  } else if (settings_.terminal) {
    const int filled = percent / 4;
    char eta[64] = "";
    if (now_done > 0) std::snprintf(eta, sizeof eta, " about %s left", duration_text(elapsed * (1.0 - fraction) / fraction).c_str());
    out << "\r" << label_ << " [" << std::string(static_cast<std::size_t>(filled), '=') << std::string(static_cast<std::size_t>(25 - filled), ' ') << "] " << percent
        << "%" << eta << "      ";
  } else {
    out << label_ << ": " << percent << "% (" << count_text(static_cast<double>(now_done)) << " of " << count_text(static_cast<double>(total_)) << " " << unit_
        << "), " << duration_text(elapsed) << " elapsed";
    if (now_done > 0) out << ", about " << duration_text(elapsed * (1.0 - fraction) / fraction) << " left";
    out << "\n";
  }
  out.flush();
}

void progress_monitor::finish() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (finished_) return;
    finishing_ = true;
    finished_ = true;
  }
  wake_.notify_all();
  if (reporter_.joinable()) reporter_.join();
  // Work that completed is kept even when the deadline passed during its last units.
  if (done() < total_ && (stopped() || steady_seconds() >= settings_.deadline)) {
    stopped_.store(true);
    const double elapsed = steady_seconds() - start_;
    const int percent = static_cast<int>(std::floor(100.0 * static_cast<double>(std::min(done(), total_)) / static_cast<double>(total_)));
    if (settings_.out && settings_.terminal) *settings_.out << "\n";
    throw error(label_ + ": stopped after " + duration_text(elapsed) + " at " + std::to_string(percent) + "% (" +
                (settings_.deadline_name.empty() ? std::string("its deadline") : settings_.deadline_name) + "); nothing is written");
  }
  if (settings_.out) report(true);
}

}  // namespace vplkit
