#include "tests/gl_test_run.hpp"

#include <doctest/doctest.h>

#include <cstddef>
#include <cstdio>

#include "frontend/gl/debug_output.hpp"

namespace vplkit::testing {

int run_tests_then_check_gl_errors(int argc, char** argv) {
  doctest::Context context(argc, argv);
  const int result = context.run();
  if (context.shouldExit()) return result;  // --help, --list-test-cases: nothing ran
  if (const std::size_t unchecked = unchecked_gl_error_count(); unchecked > 0) {
    std::fprintf(stderr, "FAILED: the GL driver reported %zu error(s) through KHR_debug that no check_gl saw\n", unchecked);
    return result != 0 ? result : 1;
  }
  return result;
}

}  // namespace vplkit::testing
