// frontend/scene/pose.hpp: the --camera/--light text reads back the floats it was written from,
// bad text is refused with the reason, and a pose moves a camera and each kind of light.
#include <doctest/doctest.h>

#include <cstring>
#include <random>

#include "frontend/core/error.hpp"
#include "frontend/scene/pose.hpp"

using namespace vplkit;

TEST_CASE("format_pose and parse_pose round-trip every float exactly") {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> exponent(-20.0f, 6.9f), sign(-1.0f, 1.0f);
  for (int trial = 0; trial < 2000; ++trial) {
    pose written;
    for (int axis = 0; axis < 3; ++axis) {
      written.position[axis] = std::copysign(std::pow(10.0f, exponent(random)), sign(random));
      written.target[axis] = std::copysign(std::pow(10.0f, exponent(random)), sign(random));
    }
    pose read;
    REQUIRE(parse_pose(format_pose(written), read).empty());
    for (int axis = 0; axis < 3; ++axis) {
      CHECK(std::memcmp(&read.position[axis], &written.position[axis], sizeof(float)) == 0);
      CHECK(std::memcmp(&read.target[axis], &written.target[axis], sizeof(float)) == 0);
    }
  }
}

TEST_CASE("parse_pose refuses what is not a pose and leaves the pose as it was") {
  const pose before{{1, 2, 3}, {4, 5, 6}};
  for (const char* text : {"", "1,2,3", "1,2,3,4,5", "1,2,3,4,5,6,7", "1,2,3,4,5,x", "nan,0,0,1,1,1", "inf,0,0,1,1,1", "2e7,0,0,0,0,0",
                           "1,,3,4,5,6", "1 2 3 4 5 6", "1,2,3,1,2,3"}) {
    CAPTURE(text);
    pose target = before;
    CHECK_FALSE(parse_pose(text, target).empty());
    CHECK(target.position == before.position);
    CHECK(target.target == before.target);
  }
  pose spaced;
  CHECK(parse_pose(" 1 , +2,-3,4 ,5, 6 ", spaced).empty());
  CHECK(spaced.position == glm::vec3(1, 2, -3));
  CHECK(spaced.target == glm::vec3(4, 5, 6));
}

TEST_CASE("apply_pose moves a camera, a spot light and a directional light") {
  camera view;
  apply_pose({{1, 2, 3}, {0, 1, 0}}, view, "test");
  CHECK(view.position == glm::vec3(1, 2, 3));
  CHECK(view.target == glm::vec3(0, 1, 0));
  CHECK(view.up == camera().up);
  CHECK_THROWS_WITH_AS(apply_pose({{0, 1, 0}, {0, 2, 0}}, view, "--camera"), doctest::Contains("--camera: the camera looks along its up vector"), error);
  CHECK(view.position == glm::vec3(1, 2, 3));  // unchanged by the refusal

  scene_light spot;
  spot.spot.cos_inner = 0.9f;
  apply_pose({{0, 2, 0}, {0, 2, -4}}, spot, "test");
  CHECK(spot.spot.position == glm::vec3(0, 2, 0));
  CHECK(spot.spot.direction == glm::vec3(0, 0, -1));  // unit
  CHECK(spot.spot.cos_inner == 0.9f);                 // the cone is kept
  const pose back = pose_of(spot);
  CHECK(back.target == glm::vec3(0, 2, -1));

  scene_light sun;
  sun.kind = light_kind::directional;
  apply_pose({{0, 5, 0}, {3, 1, 0}}, sun, "test");
  CHECK(sun.directional.direction.x == doctest::Approx(0.6));
  CHECK(sun.directional.direction.y == doctest::Approx(-0.8));
  const pose sun_pose = pose_of(sun);
  CHECK(glm::length(sun_pose.target - sun_pose.position - sun.directional.direction) < 1e-6f);
  CHECK_THROWS_AS(apply_pose({{1, 1, 1}, {1, 1, 1}}, sun, "test"), error);
}
