// Per-pass times of a frame, measured the way the current renderer supports:
// - on a hardware GPU, GL_TIME_ELAPSED timer queries (core since 3.3), one after another
//   (elapsed-time queries cannot nest), read once the frame is done;
// - on a software renderer (GL_RENDERER names llvmpipe, softpipe or swrast), wall clock between
//   two glFinish calls around each pass: llvmpipe's timer queries measure only the span of its
//   last rasterizer tiles, not the pass (a Light Wave main pass of 1.4 s read as 0.00 ms).
// The pass table says which method measured it.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "frontend/gl/gl_object.hpp"

namespace vplkit {

struct pass_time {
  std::string pass;
  double milliseconds;
};

enum class timing_method { timer_queries, wall_clock };

/// The method for the current context: wall clock on a software renderer, timer queries otherwise.
timing_method timing_method_for_current_context();
/// "GL timer queries" or "wall clock around glFinish per pass (software renderer: <GL_RENDERER>)".
std::string describe(timing_method method);

class pass_timer {
 public:
  /// Picks the method for the context current at construction.
  pass_timer();
  timing_method method() const { return method_; }
  void begin(const std::string& pass);
  void end();
  /// Waits for every measurement and returns the passes in order. Clears the timer.
  std::vector<pass_time> collect();

 private:
  struct pending {
    std::string pass;
    gl_query query;  // timer queries only
    double milliseconds = 0.0;
  };
  timing_method method_;
  std::vector<pending> passes_;
  std::chrono::steady_clock::time_point started_;
  bool open_ = false;
};

/// "pass | ms | %" table with a total row, in the layout of Table 5.3 of [RSMV], headed by the
/// method that measured it (the current context's).
std::string format_pass_table(const std::vector<pass_time>& times);

}  // namespace vplkit
