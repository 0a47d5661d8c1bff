// Properties of include/vplkit/transform.hpp: the explicit sums equal GLM's products, a
// direction ignores the translation, and map_coordinate puts the frustum's corners on the map's.
#include <doctest/doctest.h>

#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/transform.hpp>

using namespace vplkit;

TEST_CASE("transform_point and transform_direction are GLM's products with and without the translation") {
  const glm::dmat4 view = glm::lookAt(glm::dvec3(0.3, 4.0, 1.0), glm::dvec3(0.2, 0.0, -0.1), glm::dvec3(0, 0, -1));
  std::mt19937 random(5);
  std::uniform_real_distribution<double> uniform(-3.0, 3.0);
  for (int i = 0; i < 1000; ++i) {
    const glm::dvec3 p(uniform(random), uniform(random), uniform(random));
    const glm::dvec3 point = transform_point(view, p), direction = transform_direction(view, p);
    const glm::dvec3 by_glm = glm::dvec3(view * glm::dvec4(p, 1.0)), turned = glm::dmat3(view) * p;
    for (int k = 0; k < 3; ++k) {
      CHECK(point[k] == doctest::Approx(by_glm[k]).epsilon(1e-12));
      CHECK(direction[k] == doctest::Approx(turned[k]).epsilon(1e-12));
    }
    // A rigid view keeps lengths of directions and distances between points.
    CHECK(glm::length(direction) == doctest::Approx(glm::length(p)).epsilon(1e-12));
    CHECK(glm::length(point - transform_point(view, glm::dvec3(0.0))) == doctest::Approx(glm::length(p)).epsilon(1e-12));
  }
}

TEST_CASE("map_coordinate maps the frustum's edges onto the map's edges, in texels") {
  const glm::dmat4 projection = glm::ortho(-2.0, 2.0, -1.0, 1.0, 0.1, 10.0);
  const glm::dvec2 corner = map_coordinate(projection, glm::dvec3(-2.0, -1.0, -5.0), glm::ivec2(64, 32));
  const glm::dvec2 opposite = map_coordinate(projection, glm::dvec3(2.0, 1.0, -5.0), glm::ivec2(64, 32));
  CHECK(corner.x == doctest::Approx(0.0));
  CHECK(corner.y == doctest::Approx(0.0));
  CHECK(opposite.x == doctest::Approx(64.0));
  CHECK(opposite.y == doctest::Approx(32.0));
}
