// The vplkit executable: frontend/cli/cli.hpp does the work.
#include <iostream>

#include "frontend/cli/cli.hpp"

int main(int argc, char** argv) { return vplkit::run_command_line(argc, argv, std::cout, std::cerr); }
