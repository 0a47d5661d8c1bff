// Per-pass GPU times from GL_TIME_ELAPSED timer queries (core since 3.3). Passes are timed one
// after another (elapsed-time queries cannot nest). Results are read once the frame is done.
#pragma once

#include <string>
#include <vector>

#include "frontend/gl/gl_object.hpp"

namespace vplkit {

struct pass_time {
  std::string pass;
  double milliseconds;
};

class gpu_timer {
 public:
  void begin(const std::string& pass);
  void end();
  /// Waits for every query and returns the passes in order. Clears the timer.
  std::vector<pass_time> collect();

 private:
  struct pending {
    std::string pass;
    gl_query query;
  };
  std::vector<pending> queries_;
  bool open_ = false;
};

/// "pass | ms | %" table with a total row, in the layout of Table 5.3 of [RSMV].
std::string format_pass_table(const std::vector<pass_time>& times);

}  // namespace vplkit
