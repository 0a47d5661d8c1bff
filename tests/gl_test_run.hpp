// The run shared by the test binaries that open GL contexts (tests/gl_test_run.cpp).
#pragma once

namespace vplkit::testing {

/// Runs the doctest cases of the command line; after them, any error the GL driver reported
/// through KHR_debug that no check_gl turned into a vplkit::error fails the run, so a GL error
/// cannot hide after a pipeline's last check point. Returns the process's exit status.
int run_tests_then_check_gl_errors(int argc, char** argv);

}  // namespace vplkit::testing
