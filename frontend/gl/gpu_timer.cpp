#include "frontend/gl/gpu_timer.hpp"

#include <cstdio>

#include "frontend/core/error.hpp"

namespace vplkit {

void gpu_timer::begin(const std::string& pass) {
  if (open_) throw error("gpu_timer: pass '" + pass + "' begun while '" + queries_.back().pass + "' is open");
  queries_.push_back({pass, gl_query(generate_query())});
  glBeginQuery(GL_TIME_ELAPSED, queries_.back().query.get());
  open_ = true;
}

void gpu_timer::end() {
  if (!open_) throw error("gpu_timer: end() without begin()");
  glEndQuery(GL_TIME_ELAPSED);
  open_ = false;
}

std::vector<pass_time> gpu_timer::collect() {
  if (open_) end();
  std::vector<pass_time> times;
  for (const pending& entry : queries_) {
    GLuint64 nanoseconds = 0;
    glGetQueryObjectui64v(entry.query.get(), GL_QUERY_RESULT, &nanoseconds);
    times.push_back({entry.pass, static_cast<double>(nanoseconds) * 1e-6});
  }
  queries_.clear();
  return times;
}

std::string format_pass_table(const std::vector<pass_time>& times) {
  double total = 0.0;
  for (const pass_time& time : times) total += time.milliseconds;
  std::string table = "| pass | ms | % |\n|---|---:|---:|\n";
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
