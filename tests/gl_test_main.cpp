// doctest's main for the test binaries that open GL contexts: after the tests, any error the driver
// reported through KHR_debug that no check_gl turned into a vplkit::error fails the run, so a GL
// error cannot hide after a pipeline's last check point.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <cstdio>

#include "frontend/gl/debug_output.hpp"

int main(int argc, char** argv) {
  doctest::Context context(argc, argv);
  const int result = context.run();
  if (context.shouldExit()) return result;
  if (const std::size_t unchecked = vplkit::unchecked_gl_error_count(); unchecked > 0) {
    std::fprintf(stderr, "FAILED: the GL driver reported %zu error(s) through KHR_debug that no check_gl saw\n", unchecked);
    return result != 0 ? result : 1;
  }
  return result;
}
