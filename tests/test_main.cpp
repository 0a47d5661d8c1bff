// The main of the test binaries without GL (doctest's implementation: doctest_implementation.cpp).
#include <doctest/doctest.h>

int main(int argc, char** argv) { return doctest::Context(argc, argv).run(); }
