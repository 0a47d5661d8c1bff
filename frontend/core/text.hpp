// Numbers as reports print them: one formatting for the sweep's tables and the studies' reports.
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

}  // namespace vplkit
