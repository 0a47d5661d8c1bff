// The main of vplkit_gl_tests: the cases, then the GL errors no check point saw (gl_test_run.hpp).
#include "tests/gl_test_run.hpp"

int main(int argc, char** argv) { return vplkit::testing::run_tests_then_check_gl_errors(argc, argv); }
