// Seeded random vectors shared by the kernels' tests: one definition, so that the test files
// (compiled together in unity batches, tests/CMakeLists.txt) cannot each bring their own.
#pragma once

#include <random>

#include <glm/glm.hpp>

namespace vplkit::testing {

// A direction uniform on the unit sphere: a normalised standard normal triple.
template <typename T>
glm::vec<3, T> random_unit_vector(std::mt19937& random) {
  std::normal_distribution<T> normal(0, 1);
  const glm::vec<3, T> v(normal(random), normal(random), normal(random));
  return glm::normalize(v);
}

}  // namespace vplkit::testing
