// The GoogleTest adapter of vplkit::parity (vplkit/parity/parity.hpp):
//   EXPECT_PARITY(compare(...));   ASSERT_PARITY(compare(...));
// or EXPECT_TRUE(vplkit::parity::parity_holds(result)). A failure prints the summary (the
// measured errors, the worst texel with its inputs, the tolerance and its reason) and the first
// mismatching values; a pass records the summary as the test's "parity" property. The core
// library does not depend on GoogleTest.
#pragma once

#include <gtest/gtest.h>

#include <vplkit/parity/parity.hpp>

namespace vplkit::parity {

/// Success or failure of a comparison, with its report as the message.
inline ::testing::AssertionResult parity_holds(const comparison& result) {
  if (result.passed()) {
    ::testing::Test::RecordProperty("parity", result.summary());
    return ::testing::AssertionSuccess() << result.summary();
  }
  return ::testing::AssertionFailure() << result.summary() << "\n  mismatches:" << result.mismatch_list;
}

}  // namespace vplkit::parity

#define EXPECT_PARITY(comparison_result) EXPECT_TRUE(::vplkit::parity::parity_holds(comparison_result))
#define ASSERT_PARITY(comparison_result) ASSERT_TRUE(::vplkit::parity::parity_holds(comparison_result))
