#include "frontend/gl/pass_timer.hpp"

#include <cstdio>

#include "frontend/core/error.hpp"

namespace vplkit {

namespace {

std::string current_renderer() {
  const GLubyte* renderer = glGetString(GL_RENDERER);
  return renderer ? std::string(reinterpret_cast<const char*>(renderer)) : std::string();
}

}  // namespace

timing_method timing_method_for_current_context() {
  const std::string renderer = current_renderer();
  for (const char* software : {"llvmpipe", "softpipe", "swrast"})
    if (renderer.find(software) != std::string::npos) return timing_method::wall_clock;
  return timing_method::timer_queries;
}

std::string describe(timing_method method) {
  return method == timing_method::timer_queries ? "GL timer queries"
                                                : "wall clock around glFinish per pass (software renderer: " + current_renderer() + ")";
}

pass_timer::pass_timer() : method_(timing_method_for_current_context()) {}

void pass_timer::begin(const std::string& pass) {
  if (open_) throw error("pass_timer: pass '" + pass + "' begun while '" + passes_.back().pass + "' is open");
  if (method_ == timing_method::timer_queries) {
    passes_.push_back({pass, gl_query(generate_query())});
    glBeginQuery(GL_TIME_ELAPSED, passes_.back().query.get());
  } else {
    passes_.push_back({pass, gl_query(), 0.0});
    glFinish();  // the work before the pass is not the pass's
    started_ = std::chrono::steady_clock::now();
  }
  open_ = true;
}

void pass_timer::end() {
  if (!open_) throw error("pass_timer: end() without begin()");
  if (method_ == timing_method::timer_queries) {
    glEndQuery(GL_TIME_ELAPSED);
  } else {
    glFinish();
    passes_.back().milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started_).count();
  }
  open_ = false;
}

std::vector<pass_time> pass_timer::collect() {
  if (open_) end();
  std::vector<pass_time> times;
  for (const pending& entry : passes_) {
    double milliseconds = entry.milliseconds;
    if (method_ == timing_method::timer_queries) {
      GLuint64 nanoseconds = 0;
      glGetQueryObjectui64v(entry.query.get(), GL_QUERY_RESULT, &nanoseconds);
      milliseconds = static_cast<double>(nanoseconds) * 1e-6;
    }
    times.push_back({entry.pass, milliseconds});
  }
  passes_.clear();
  return times;
}

std::string format_pass_table(const std::vector<pass_time>& times) {
  double total = 0.0;
  for (const pass_time& time : times) total += time.milliseconds;
  std::string table = "timing: " + describe(timing_method_for_current_context()) + "\n| pass | ms | % |\n|---|---:|---:|\n";
  char row[160];
  for (const pass_time& time : times) {
    std::snprintf(row, sizeof row, "| %s | %.2f | %.1f |\n", time.pass.c_str(), time.milliseconds,
                  total > 0.0 ? 100.0 * time.milliseconds / total : 0.0);
    table += row;
  }
  std::snprintf(row, sizeof row, "| total | %.2f | 100.0 |\n", total);
  return table + row;
}

}  // namespace vplkit
