// The doctest adapter of vplkit::parity (vplkit/parity/parity.hpp): require_parity prints a
// comparison's summary and, when the comparison failed, fails the test case with the worst texel
// and the first mismatches, both at the line that called it. Include it in a doctest test file;
// the core library does not depend on doctest.
#pragma once

#include <doctest/doctest.h>

#include <string>

#include <vplkit/parity/parity.hpp>

namespace vplkit::parity {

/// Prints the summary (a doctest message) and, when the comparison failed, records a failed
/// check with the report; the test case goes on. `file` and `line` default to the caller's.
inline void require_parity(const comparison& result, const char* file = __builtin_FILE(), int line = __builtin_LINE()) {
  DOCTEST_ADD_MESSAGE_AT(file, line, result.summary());
  if (result.passed()) {
    DOCTEST_CHECK(result.passed());  // counts the comparison among the assertions that passed
  } else {
    const std::string report = "parity of " + result.kernel + " failed: " + std::to_string(result.mismatches) +
                               " values outside tolerance, " + std::to_string(result.allowed_mismatches) + " allowed\n  worst " +
                               result.worst + "\n  mismatches:" + result.mismatch_list;
    DOCTEST_ADD_FAIL_CHECK_AT(file, line, report);
  }
}

}  // namespace vplkit::parity
