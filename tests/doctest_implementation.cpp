// doctest's implementation, compiled once for every test binary (the vplkit_doctest library):
// each binary's own file then holds only its main.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>
