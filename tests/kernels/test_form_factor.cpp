// Form factors (include/vplkit/form_factor.hpp, [FG]): closed-form configuration factors
// from the heat-transfer literature, Monte Carlo, closed surfaces, clipping, winding, and the
// convergence of the point-to-point kernel.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include <vplkit/form_factor.hpp>

#include "tests/closed_forms.hpp"
#include "tests/kernels/random_vectors.hpp"

using namespace vplkit;

namespace {

using closed_forms::pi;
using closed_forms::parallel_rectangle;
using closed_forms::perpendicular_rectangle;


}  // namespace

// polygon_form_factor's stated bound against the exact form factor (form_factor.hpp): 6 edges
// of 2.2e-8 rad each over 2 pi, plus double rounding.
constexpr double fast_bound = 2.2e-8;

TEST_CASE("polygon_form_factor equals Howell's B-3 (parallel rectangle): the exact form to 1e-9, the fast one to 2.2e-8 in double, 2e-6 in float") {
  for (const std::array<double, 3>& sides : std::vector<std::array<double, 3>>{{1, 1, 1}, {2, 0.5, 1}, {0.1, 0.3, 2}, {5, 7, 0.2}, {1e-3, 1e-3, 1}}) {
    const double a = sides[0], b = sides[1], c = sides[2];  // not a structured binding: CAPTURE's lambda cannot capture one (clang 14)
    const double exact = parallel_rectangle(a, b, c);
    const glm::dvec3 x(0.0), n(0, 0, 1);
    const double f = polygon_form_factor_exact(x, n, glm::dvec3(0, 0, c), glm::dvec3(a, 0, c), glm::dvec3(a, b, c), glm::dvec3(0, b, c));
    CAPTURE(a);
    CAPTURE(b);
    CAPTURE(c);
    CHECK(f == doctest::Approx(exact).epsilon(1e-9));
    CHECK(std::fabs(polygon_form_factor(x, n, glm::dvec3(0, 0, c), glm::dvec3(a, 0, c), glm::dvec3(a, b, c), glm::dvec3(0, b, c)) - exact) <= fast_bound);
    const float ff = polygon_form_factor(glm::vec3(0.0f), glm::vec3(0, 0, 1), glm::vec3(0, 0, c), glm::vec3(a, 0, c), glm::vec3(a, b, c), glm::vec3(0, b, c));
    CHECK(ff == doctest::Approx(exact).epsilon(2e-6));
  }
}

TEST_CASE("polygon_form_factor equals Howell's B-2 (perpendicular rectangle): the exact form to 1e-9, the fast one to 2.2e-8 in double, 2e-6 in float") {
  for (const std::array<double, 3>& sides : std::vector<std::array<double, 3>>{{1, 1, 1}, {2, 0.5, 1}, {0.3, 3, 0.5}, {4, 4, 0.1}}) {
    const double a = sides[0], b = sides[1], c = sides[2];
    const double exact = perpendicular_rectangle(a, b, c);
    // Element at the origin facing +z; the rectangle in the plane y = c, x in [0, a], z in [0, b].
    const double f = polygon_form_factor_exact(glm::dvec3(0.0), glm::dvec3(0, 0, 1), glm::dvec3(0, c, 0), glm::dvec3(a, c, 0), glm::dvec3(a, c, b),
                                               glm::dvec3(0, c, b));
    CAPTURE(a);
    CAPTURE(c);
    CHECK(f == doctest::Approx(exact).epsilon(1e-9));
    CHECK(std::fabs(polygon_form_factor(glm::dvec3(0.0), glm::dvec3(0, 0, 1), glm::dvec3(0, c, 0), glm::dvec3(a, c, 0), glm::dvec3(a, c, b),
                                        glm::dvec3(0, c, b)) - exact) <= fast_bound);
    const float ff = polygon_form_factor(glm::vec3(0.0f), glm::vec3(0, 0, 1), glm::vec3(0, c, 0), glm::vec3(a, c, 0), glm::vec3(a, c, b), glm::vec3(0, c, b));
    CHECK(ff == doctest::Approx(exact).epsilon(2e-6));
  }
}

TEST_CASE("polygon_form_factor agrees with a Monte Carlo integral of the point kernel, clipping included") {
  std::mt19937 random(40);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (int trial = 0; trial < 6; ++trial) {
    // A random planar parallelogram near a random point and normal: partly below the tangent
    // plane in some trials.
    const glm::dvec3 x(0.0), n = vplkit::testing::random_unit_vector<double>(random);
    const glm::dvec3 origin = vplkit::testing::random_unit_vector<double>(random) * (1.0 + uniform(random)), e1 = vplkit::testing::random_unit_vector<double>(random) * 0.8, e2 = vplkit::testing::random_unit_vector<double>(random) * 0.8;
    const glm::dvec3 normal = glm::normalize(glm::cross(e1, e2));
    const double area = glm::length(glm::cross(e1, e2));
    const int samples = 200000;
    double sum = 0.0, sum_squares = 0.0;
    for (int s = 0; s < samples; ++s) {
      const glm::dvec3 y = origin + e1 * uniform(random) + e2 * uniform(random);
      // A two-sided emitter: the form factor to the quad does not depend on which side faces x.
      const double k = std::max(point_form_factor(x, n, y, normal), point_form_factor(x, n, y, -normal)) * area;
      sum += k;
      sum_squares += k * k;
    }
    const double mean = sum / samples, sigma = std::sqrt((sum_squares / samples - mean * mean) / samples);
    const double f = polygon_form_factor(x, n, origin, origin + e1, origin + e1 + e2, origin + e2);
    CAPTURE(trial);
    CAPTURE(mean);
    CAPTURE(f);
    CHECK(std::fabs(f - mean) <= 4.0 * sigma + 1e-12);
  }
}

TEST_CASE("the six faces of a closed cube around a point give F = 1, for any normal") {
  std::mt19937 random(41);
  std::uniform_real_distribution<double> uniform(-0.9, 0.9);
  const glm::dvec3 c[8] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}};
  const int faces[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4}, {3, 2, 6, 7}, {0, 3, 7, 4}, {1, 2, 6, 5}};
  for (int trial = 0; trial < 200; ++trial) {
    const glm::dvec3 x(uniform(random), uniform(random), uniform(random)), n = vplkit::testing::random_unit_vector<double>(random);
    double total = 0.0;
    double fast_total = 0.0;
    for (const auto& face : faces) {
      total += polygon_form_factor_exact(x, n, c[face[0]], c[face[1]], c[face[2]], c[face[3]]);
      fast_total += polygon_form_factor(x, n, c[face[0]], c[face[1]], c[face[2]], c[face[3]]);
    }
    REQUIRE(total == doctest::Approx(1.0).epsilon(1e-9));
    REQUIRE(std::fabs(fast_total - 1.0) <= 6.0 * fast_bound);
  }
}

TEST_CASE("a quad rotated through the tangent plane falls continuously to 0; either winding gives the same F") {
  const glm::dvec3 x(0.0), n(0, 0, 1);
  double previous = -1.0;
  for (int step = 0; step <= 400; ++step) {
    // A unit square at distance 1, tilted about the x axis through the point (0, 1, 0.3) until
    // it lies entirely below the tangent plane.
    const double angle = pi * step / 400.0;
    const glm::dvec3 centre(0.0, 1.0, 0.3);
    const glm::dvec3 u(1, 0, 0), v(0, std::cos(angle), std::sin(angle));
    const glm::dvec3 q0 = centre - 0.5 * u - 0.5 * v, q1 = centre + 0.5 * u - 0.5 * v, q2 = centre + 0.5 * u + 0.5 * v, q3 = centre - 0.5 * u + 0.5 * v;
    const double f = polygon_form_factor(x, n, q0, q1, q2, q3);
    REQUIRE(f >= 0.0);
    REQUIRE(f == doctest::Approx(polygon_form_factor(x, n, q3, q2, q1, q0)).epsilon(1e-12));  // winding
    if (previous >= 0.0) REQUIRE(std::fabs(f - previous) < 0.01);  // no jump at the crossing
    previous = f;
  }
  // Entirely below: nothing; the paper's unclipped variant disagrees with the clipped one only
  // when the quad straddles the plane.
  CHECK(polygon_form_factor(x, n, glm::dvec3(0, 0, -1), glm::dvec3(1, 0, -1), glm::dvec3(1, 1, -1), glm::dvec3(0, 1, -1)) == 0.0);
  const glm::dvec3 a(-1, -1, 1), b(-1, 1, 1), c(1, 1, 1), d(1, -1, 1);  // counter-clockwise seen from x
  CHECK(polygon_form_factor_unclipped(x, n, a, b, c, d) == doctest::Approx(polygon_form_factor(x, n, a, b, c, d)).epsilon(1e-12));
  const glm::dvec3 s0(-1, 1, -0.5), s1(-1, 1, 1), s2(1, 1, 1), s3(1, 1, -0.5);  // straddles the tangent plane
  CHECK(std::fabs(polygon_form_factor_unclipped(x, n, s0, s1, s2, s3) - polygon_form_factor(x, n, s0, s1, s2, s3)) > 0.01);
  // Degenerate quads (all corners on a line, or at one point): 0, not NaN.
  CHECK(polygon_form_factor(x, n, glm::dvec3(0, 0, 1), glm::dvec3(1, 0, 1), glm::dvec3(2, 0, 1), glm::dvec3(3, 0, 1)) == 0.0);
  CHECK(polygon_form_factor(x, n, glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1)) == 0.0);
}

TEST_CASE("point_form_factor x area converges to the polygon form factor as the quad shrinks, and diverges near it") {
  const glm::dvec3 x(0.0), n(0, 0, 1), ny(0, 0, -1);
  double previous_error = 1e30;
  for (double size : {0.8, 0.4, 0.2, 0.1, 0.05, 0.025}) {
    const double h = 0.5 * size;
    const double polygon = polygon_form_factor(x, n, glm::dvec3(-h, -h, 1), glm::dvec3(h, -h, 1), glm::dvec3(h, h, 1), glm::dvec3(-h, h, 1));
    const double point = point_form_factor(x, n, glm::dvec3(0, 0, 1), ny) * size * size;
    const double error = std::fabs(point / polygon - 1.0);
    CAPTURE(size);
    CHECK(error < previous_error);  // O(size^2)
    previous_error = error;
  }
  CHECK(previous_error < 1e-3);
  // Near the quad the point kernel explodes (1 / r^2), the polygon stays below 1.
  const double near = 0.01;
  const double polygon = polygon_form_factor(x, n, glm::dvec3(-0.5, -0.5, near), glm::dvec3(0.5, -0.5, near), glm::dvec3(0.5, 0.5, near), glm::dvec3(-0.5, 0.5, near));
  const double point = point_form_factor(x, n, glm::dvec3(0, 0, near), ny) * 1.0;
  CHECK(polygon < 1.0);
  CHECK(point / polygon > 1000.0);
}

TEST_CASE("the polynomial acos of lambert_edge is within 2.2e-8 of acos over [0, 1], and within 1e-6 of its value at 1 near it") {
  // Dense in x, and dense near 1 where acos's own slope is infinite: the bound is on
  // sqrt(1 - x) P(x), the angle the edge term uses.
  double worst = 0.0;
  for (int i = 0; i <= 1000000; ++i) {
    const double x = i / 1000000.0;
    worst = std::max(worst, std::fabs(std::sqrt(1.0 - x) * detail::acos_over_sqrt_one_minus(x) - std::acos(x)));
  }
  for (int i = 1; i <= 60; ++i) {
    const double x = 1.0 - std::ldexp(1.0, -i);
    worst = std::max(worst, std::fabs(std::sqrt(1.0 - x) * detail::acos_over_sqrt_one_minus(x) - std::acos(x)));
  }
  CAPTURE(worst);
  CHECK(worst <= 2.2e-8);
  CHECK(worst > 1e-9);  // the bound is the polynomial's, not vacuous: a wrong coefficient would show
  // P(1) = acos(x) / sqrt(1 - x) at x -> 1, which is sqrt(2).
  CHECK(detail::acos_over_sqrt_one_minus(1.0) == doctest::Approx(std::sqrt(2.0)).epsilon(1e-6));
}

TEST_CASE("lambert_edge is within 2.2e-8 of the exact (atan2) term for every angle, small ones included") {
  std::mt19937 random(43);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  double worst = 0.0;
  for (int trial = 0; trial < 200000; ++trial) {
    const glm::dvec3 n = vplkit::testing::random_unit_vector<double>(random), a = vplkit::testing::random_unit_vector<double>(random) * (0.1 + 2.0 * std::fabs(uniform(random)));
    // Angles from 1e-6 rad to pi - 1e-3 (nearer pi the edge passes through x: ill-conditioned in any form).
    const double gamma = trial % 4 == 0 ? std::pow(10.0, -6.0 + 6.0 * std::fabs(uniform(random))) : (pi - 1e-3) * std::fabs(uniform(random));
    const glm::dvec3 axis = glm::normalize(glm::cross(a, vplkit::testing::random_unit_vector<double>(random)));
    const glm::dvec3 unit_a = glm::normalize(a), perpendicular = glm::cross(axis, unit_a);
    const glm::dvec3 b = (unit_a * std::cos(gamma) + perpendicular * std::sin(gamma)) * (0.1 + 2.0 * std::fabs(uniform(random)));
    const double fast = detail::lambert_edge(a, detail::inverse_length(a), b, detail::inverse_length(b), n);
    worst = std::max(worst, std::fabs(fast - detail::lambert_edge_exact(a, b, n)));
  }
  CAPTURE(worst);
  CHECK(worst <= 2.2e-8);
  // Degenerate edges: a zero vector, or both ends on one ray: 0, not NaN; an antipodal edge stays in [-pi, pi].
  const glm::dvec3 n(0, 0, 1), a(1, 0, 0);
  CHECK(detail::lambert_edge(a, 1.0, glm::dvec3(0.0), detail::inverse_length(glm::dvec3(0.0)), n) == 0.0);
  CHECK(detail::lambert_edge(a, 1.0, 2.0 * a, 0.5, n) == 0.0);
  const double antipodal = detail::lambert_edge(a, 1.0, glm::dvec3(-1, 1e-9, 0), 1.0, n);
  CHECK(std::fabs(antipodal) <= pi);
}

TEST_CASE("polygon_form_factor is within its bound of the exact form for random quads across the tangent plane, non-convex ones included") {
  std::mt19937 random(44);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  int straddling = 0, four_crossings = 0;
  double worst = 0.0;
  for (int trial = 0; trial < 100000; ++trial) {
    const glm::dvec3 x(0.0), n = vplkit::testing::random_unit_vector<double>(random);
    glm::dvec3 c[4];
    if (trial % 2 == 0) {  // a planar parallelogram
      const glm::dvec3 origin = vplkit::testing::random_unit_vector<double>(random) * (0.2 + std::fabs(uniform(random))), e1 = vplkit::testing::random_unit_vector<double>(random) * 0.8, e2 = vplkit::testing::random_unit_vector<double>(random) * 0.8;
      c[0] = origin, c[1] = origin + e1, c[2] = origin + e1 + e2, c[3] = origin + e2;
    } else {  // any four points: non-planar, non-convex, crossing the plane up to four times
      for (glm::dvec3& corner : c) corner = vplkit::testing::random_unit_vector<double>(random) * (0.2 + std::fabs(uniform(random)));
    }
    int crossings = 0;
    for (int k = 0; k < 4; ++k) crossings += (glm::dot(n, c[k]) >= 0.0) != (glm::dot(n, c[(k + 1) % 4]) >= 0.0) ? 1 : 0;
    straddling += crossings > 0 ? 1 : 0;
    four_crossings += crossings == 4 ? 1 : 0;
    const double error = std::fabs(polygon_form_factor(x, n, c[0], c[1], c[2], c[3]) - polygon_form_factor_exact(x, n, c[0], c[1], c[2], c[3]));
    worst = std::max(worst, error);
  }
  CAPTURE(worst);
  CHECK(straddling > 10000);
  CHECK(four_crossings > 100);  // the pairing of two exits with two entries was exercised
  CHECK(worst <= fast_bound);
  // In float, against the exact form in double: rounding, not the polynomial, dominates.
  double worst_float = 0.0;
  for (int trial = 0; trial < 20000; ++trial) {
    const glm::dvec3 n = vplkit::testing::random_unit_vector<double>(random);
    const glm::dvec3 origin = vplkit::testing::random_unit_vector<double>(random) * (0.5 + std::fabs(uniform(random))), e1 = vplkit::testing::random_unit_vector<double>(random) * 0.5, e2 = vplkit::testing::random_unit_vector<double>(random) * 0.5;
    const glm::vec3 fn(n), f0(origin), f1(origin + e1), f2(origin + e1 + e2), f3(origin + e2);
    const double exact = polygon_form_factor_exact(glm::dvec3(0.0), glm::dvec3(fn), glm::dvec3(f0), glm::dvec3(f1), glm::dvec3(f2), glm::dvec3(f3));
    worst_float = std::max(worst_float, std::fabs(double(polygon_form_factor(glm::vec3(0.0f), fn, f0, f1, f2, f3)) - exact));
  }
  CAPTURE(worst_float);
  CHECK(worst_float <= 2e-6);
}
