// Numbers and text as reports print them: one formatting for the sweep's tables and the studies'
// reports.
#pragma once

#include <iomanip>
#include <sstream>
#include <string>

namespace vplkit {

/// `value` in fixed notation with `digits` decimals ("0.125" for 0.125 and 3).
inline std::string fixed(double value, int digits) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(digits) << value;
  return out.str();
}

/// `text` as one quoted CSV field (RFC 4180: its quotes doubled), whatever it holds: a frame's
/// label, a pose file's comment, may hold commas, quotes and line ends.
inline std::string csv_quoted(const std::string& text) {
  std::string quoted = "\"";
  for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

}  // namespace vplkit
