// Properties of the temporal accumulation (include/vplkit/temporal_accumulation.hpp): the history
// clamped to the neighbourhood's box and blended, its convergence and its noise (an exponential
// moving average's closed forms), and the reprojected history's depth test.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include <vplkit/temporal_accumulation.hpp>

using namespace vplkit;

namespace {

neighbourhood_moments<double> moments_of(std::initializer_list<glm::dvec3> values) {
  neighbourhood_moments<double> moments;
  for (const glm::dvec3& value : values) neighbourhood_add(moments, value);
  return moments;
}

}  // namespace

TEST_CASE("temporal_resolve: no history (or no neighbourhood) is the current value; a history inside the box is blended as it is") {
  const temporal_settings<double> settings{0.25, 1.0, 0.02};
  const glm::dvec3 current(1.0, 2.0, 3.0), history(1.2, 1.8, 3.1);
  const neighbourhood_moments<double> wide = moments_of({{0.0, 0.0, 0.0}, {2.0, 4.0, 6.0}});  // mean (1, 2, 3), sd (1, 2, 3)
  CHECK(temporal_resolve(current, history, false, wide, settings) == current);
  CHECK(temporal_resolve(current, history, true, neighbourhood_moments<double>{}, settings) == current);
  const glm::dvec3 blended = temporal_resolve(current, history, true, wide, settings);
  for (int c = 0; c < 3; ++c) CHECK(blended[c] == doctest::Approx(0.75 * history[c] + 0.25 * current[c]));
  // blend 1 keeps nothing of the history.
  CHECK(temporal_resolve(current, history, true, wide, temporal_settings<double>{1.0, 1.0, 0.02}) == current);
}

TEST_CASE("temporal_resolve: a history outside mean +- clamp_width sd is clamped to the box first (per channel)") {
  const temporal_settings<double> settings{0.5, 1.5, 0.02};
  // Values 1 and 3 in every channel: mean 2, sd 1, the box [0.5, 3.5].
  const neighbourhood_moments<double> box = moments_of({glm::dvec3(1.0), glm::dvec3(3.0)});
  const glm::dvec3 current(2.0), history(10.0, 0.0, 3.0);
  const glm::dvec3 resolved = temporal_resolve(current, history, true, box, settings);
  CHECK(resolved.x == doctest::Approx(0.5 * 3.5 + 0.5 * 2.0));
  CHECK(resolved.y == doctest::Approx(0.5 * 0.5 + 0.5 * 2.0));
  CHECK(resolved.z == doctest::Approx(0.5 * 3.0 + 0.5 * 2.0));
  // A flat neighbourhood (sd 0) clamps the history to its mean: a light jump is taken at once.
  const neighbourhood_moments<double> flat = moments_of({glm::dvec3(4.0), glm::dvec3(4.0), glm::dvec3(4.0)});
  CHECK(temporal_resolve(glm::dvec3(4.0), glm::dvec3(0.0), true, flat, settings) == glm::dvec3(4.0));
}

TEST_CASE("temporal accumulation of a step converges like (1 - blend)^n; of noise, its variance is blend / (2 - blend) of the frames'") {
  const temporal_settings<double> settings{0.2, 16.0, 0.02};  // a box wide enough never to clamp
  const neighbourhood_moments<double> wide = moments_of({glm::dvec3(-100.0), glm::dvec3(100.0)});
  glm::dvec3 accumulated(0.0);
  for (int n = 1; n <= 20; ++n) {
    accumulated = temporal_resolve(glm::dvec3(1.0), accumulated, true, wide, settings);
    CHECK(1.0 - accumulated.x == doctest::Approx(std::pow(0.8, n)).epsilon(1e-12));
  }
  std::mt19937 random(3);
  std::normal_distribution<double> noise(5.0, 1.0);
  double value = 5.0, sum = 0.0, squares = 0.0;
  const int frames = 200000;
  for (int n = 0; n < frames; ++n) {
    value = temporal_resolve(glm::dvec3(noise(random)), glm::dvec3(value), true, wide, settings).x;
    sum += value;
    squares += value * value;
  }
  const double mean = sum / frames, variance = squares / frames - mean * mean;
  CHECK(mean == doctest::Approx(5.0).epsilon(0.01));
  CHECK(variance == doctest::Approx(0.2 / 1.8).epsilon(0.05));
}

TEST_CASE("temporal_history_matches: the stored depth within the tolerance of the expected one, both in front of the camera") {
  const temporal_settings<double> settings{0.2, 1.0, 0.02};
  CHECK(temporal_history_matches(-10.0, -10.1, settings));
  CHECK(temporal_history_matches(-10.0, -9.81, settings));
  CHECK_FALSE(temporal_history_matches(-10.0, -10.3, settings));
  CHECK_FALSE(temporal_history_matches(-10.0, 0.0, settings));  // no surface stored there
  CHECK_FALSE(temporal_history_matches(0.5, 0.5, settings));    // behind the previous camera
}

TEST_CASE("temporal_settings are validated with the field's name") {
  CHECK_FALSE(validate(temporal_settings<float>{}));
  CHECK_FALSE(validate(temporal_settings<float>{1.0f, 0.0f, 0.0f}));
  CHECK(std::string(validate(temporal_settings<float>{0.0f, 1.0f, 0.02f}).message()).find("blend") != std::string::npos);
  CHECK(std::string(validate(temporal_settings<float>{0.5f, -1.0f, 0.02f}).message()).find("clamp_width") != std::string::npos);
  CHECK(std::string(validate(temporal_settings<float>{0.5f, 1.0f, 2.0f}).message()).find("depth_tolerance") != std::string::npos);
}
