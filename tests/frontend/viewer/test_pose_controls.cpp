// frontend/viewer/pose_controls.hpp: each move keeps what it promises (the distance, the target,
// the position), turns by the angles asked for, and stops short of the poles.
#include <doctest/doctest.h>

#include <cmath>

#include "frontend/viewer/pose_controls.hpp"

using namespace vplkit;

namespace {

float distance(const pose& where) { return glm::length(where.target - where.position); }
float elevation(glm::vec3 direction) { return std::asin(glm::normalize(direction).y); }
bool near(glm::vec3 a, glm::vec3 b, float tolerance = 1e-5f) { return glm::length(a - b) <= tolerance; }

const pose start{{1.0f, 1.5f, 3.0f}, {0.0f, 1.0f, 0.0f}};

}  // namespace

TEST_CASE("orbit keeps the target and the distance and turns by yaw and pitch") {
  const pose turned = orbit(start, 0.4f, 0.2f);
  CHECK(turned.target == start.target);
  CHECK(distance(turned) == doctest::Approx(distance(start)).epsilon(1e-5));
  CHECK(elevation(turned.position - turned.target) == doctest::Approx(elevation(start.position - start.target) + 0.2f).epsilon(1e-4));
  // The azimuth about +Y changes by the yaw.
  const auto azimuth = [](glm::vec3 d) { return std::atan2(d.x, d.z); };
  CHECK(azimuth(turned.position - turned.target) == doctest::Approx(azimuth(start.position - start.target) + 0.4f).epsilon(1e-4));
  // A full turn comes back.
  CHECK(near(orbit(start, 6.2831853f, 0.0f).position, start.position, 1e-4f));
  // Pitch stops 1 degree short of the pole, however far it is pushed.
  const pose top = orbit(start, 0.0f, 10.0f);
  CHECK(elevation(top.position - top.target) == doctest::Approx(1.5707963f - 0.0174533f).epsilon(1e-4));
  CHECK(distance(top) == doctest::Approx(distance(start)).epsilon(1e-5));
}

TEST_CASE("look keeps the position and the distance and turns the view") {
  const pose turned = look(start, -0.3f, 0.1f);
  CHECK(turned.position == start.position);
  CHECK(distance(turned) == doctest::Approx(distance(start)).epsilon(1e-5));
  CHECK(elevation(turned.target - turned.position) == doctest::Approx(elevation(start.target - start.position) + 0.1f).epsilon(1e-4));
  const pose down = look(start, 0.0f, -10.0f);
  CHECK(elevation(down.target - down.position) == doctest::Approx(-1.5707963f + 0.0174533f).epsilon(1e-4));
}

TEST_CASE("dolly scales the distance along the same line and never reaches the target") {
  const pose closer = dolly(start, 0.5f);
  CHECK(closer.target == start.target);
  CHECK(distance(closer) == doctest::Approx(0.5f * distance(start)).epsilon(1e-5));
  CHECK(near(glm::normalize(closer.position - closer.target), glm::normalize(start.position - start.target)));
  CHECK(distance(dolly(start, 0.0f)) == doctest::Approx(1e-3f));
}

TEST_CASE("fly moves position and target together along the pose's axes") {
  const pose_axes axes = axes_of(start);
  CHECK(glm::dot(axes.forward, axes.right) == doctest::Approx(0.0f).epsilon(1e-6));
  CHECK(glm::dot(axes.forward, axes.up) == doctest::Approx(0.0f).epsilon(1e-6));
  CHECK(axes.right.y == doctest::Approx(0.0f));  // level: no roll
  CHECK(axes.up.y > 0.0f);
  const pose moved = fly(start, {0.5f, -0.25f, 2.0f});
  const glm::vec3 offset = 0.5f * axes.right - 0.25f * axes.up + 2.0f * axes.forward;
  CHECK(near(moved.position, start.position + offset));
  CHECK(near(moved.target, start.target + offset));
  // Looking straight down still has a right axis.
  const pose_axes down = axes_of({{0, 5, 0}, {0, 0, 0}});
  CHECK(glm::length(down.right) == doctest::Approx(1.0f));
}

TEST_CASE("light_arguments: the text reproduces the view's lights, the selected one first and placed") {
  const pose where{{0.5f, 2.0f, 0.25f}, {0.0f, 0.0f, 0.0f}};
  const std::string placed = "--light " + format_pose(where);
  // Every light of the file, the first selected: as with one light, --light alone.
  CHECK(light_arguments(std::nullopt, 1, 0, where) == placed);
  CHECK(light_arguments(std::nullopt, 3, 0, where) == placed);
  // Another selected: it goes first (--light places the first chosen), the rest in their order.
  CHECK(light_arguments(std::nullopt, 3, 2, where) == "--lights 2,0,1 " + placed);
  CHECK(light_arguments(std::nullopt, 3, 1, where) == "--lights 1,0,2 " + placed);
  // The view drew some of the file's lights (--lights 4,1): their file indices, even with the first selected.
  CHECK(light_arguments(std::vector<std::size_t>{4, 1}, 2, 0, where) == "--lights 4,1 " + placed);
  CHECK(light_arguments(std::vector<std::size_t>{4, 1}, 2, 1, where) == "--lights 1,4 " + placed);
  // No light: nothing placed, none drawn.
  CHECK(light_arguments(std::nullopt, 0, 0, where) == "--lights none");
  CHECK(light_arguments(std::vector<std::size_t>{}, 0, 0, where) == "--lights none");
}
