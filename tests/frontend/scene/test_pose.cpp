// frontend/scene/pose.hpp: the --camera/--light text reads back the floats it was written from,
// bad text is refused with the reason, a pose moves a camera and each kind of light, and a pose
// file (render --poses) reads line by line.
#include <doctest/doctest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
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

TEST_CASE("apply_pose moves a point light to the pose's position; pose_of gives it back, its target one unit below") {
  scene_light bulb;
  bulb.kind = light_kind::point;
  bulb.point.intensity = glm::vec3(5.0f, 4.0f, 3.0f);
  apply_pose({{1, 2, 3}, {4, 0, 0}}, bulb, "test");
  CHECK(bulb.point.position == glm::vec3(1, 2, 3));
  CHECK(bulb.point.intensity == glm::vec3(5.0f, 4.0f, 3.0f));  // the power is kept
  const pose back = pose_of(bulb);
  CHECK(back.position == glm::vec3(1, 2, 3));
  CHECK(back.target == glm::vec3(1, 1, 3));
  // The pose written by the viewer moves the bulb to the same place again (format, parse, apply).
  pose parsed;
  REQUIRE(parse_pose(format_pose(back), parsed).empty());
  scene_light again;
  again.kind = light_kind::point;
  apply_pose(parsed, again, "test");
  CHECK(again.point.position == bulb.point.position);
  // A pose whose two points coincide is refused for a point light too, naming the owner, and changes nothing.
  CHECK_THROWS_WITH_AS(apply_pose({{7, 7, 7}, {7, 7, 7}}, bulb, "--light"), doctest::Contains("--light"), error);
  CHECK(bulb.point.position == glm::vec3(1, 2, 3));
}

namespace {

// A pose file in a fresh temporary folder, removed afterwards.
struct pose_file {
  std::filesystem::path folder = std::filesystem::temp_directory_path() / ("vplkit-poses-" + std::to_string(std::random_device{}()));
  std::filesystem::path path = folder / "poses.txt";
  explicit pose_file(const std::string& text) {
    std::filesystem::create_directories(folder);
    std::ofstream(path) << text;
  }
  ~pose_file() { std::filesystem::remove_all(folder); }
};

}  // namespace

TEST_CASE("read_pose_file: a frame per line, comments and blank lines skipped, each pose as parse_pose reads it") {
  const pose_file file("# header\n--camera 1,2,3,0,0,0\n\n  --light 0,5,0,1,0,0   # a comment\n--light 0,4,0,0,0,0\t--camera 1,1,1,0,1,0\r\n");
  const std::vector<pose_frame> frames = read_pose_file(file.path, false);
  REQUIRE(frames.size() == 3);
  CHECK(frames[0].line == 2);
  CHECK(frames[0].camera->position == glm::vec3(1, 2, 3));
  CHECK(!frames[0].light);
  CHECK(frames[1].line == 4);
  CHECK(frames[1].light->target == glm::vec3(1, 0, 0));
  CHECK(frames[1].comment == "a comment");
  CHECK(frames[2].camera->target == glm::vec3(0, 1, 0));
  CHECK(frames[2].light->position == glm::vec3(0, 4, 0));
  const pose_file scenes("--scene cornell-box --light 0,5,0,1,0,0\n--scene a.gltf\n");
  const std::vector<pose_frame> with_scenes = read_pose_file(scenes.path, true);
  CHECK(with_scenes[0].scene == "cornell-box");
  CHECK(with_scenes[1].scene == "a.gltf");
}

TEST_CASE("read_pose_file refuses what is not a pose, naming the file and the line") {
  const auto refused = [](const std::string& text, const std::string& expected, bool with_scene = false) {
    const pose_file file(text);
    CAPTURE(text);
    const std::string message = file.path.string() + expected;
    CHECK_THROWS_WITH_AS(read_pose_file(file.path, with_scene), doctest::Contains(message.c_str()), error);
  };
  refused("--light 0,5,0,1,0,0\n--size 64\n", ":2: expected --camera or --light, got '--size'");
  refused("--scene x.gltf\n", ":1: expected --camera or --light, got '--scene'");
  refused("--scene x.gltf --size 3\n", ":1: expected --scene, --camera or --light, got '--size'", true);
  refused("--camera 1,2,3,1,2,3\n", ":1: --camera: the position and the target are the same point");
  refused("--camera 1,2,nan,0,0,0\n", ":1: --camera: expected x,y,z,tx,ty,tz");
  refused("--light 1,2,3,0,0,0 --light 0,1,0,0,0,0\n", ":1: --light is given twice");
  refused("--camera\n", ":1: --camera needs a value");
  refused("# nothing\n\n", ": no frames");
  CHECK_THROWS_WITH_AS(read_pose_file("/nonexistent/poses.txt", false), doctest::Contains("/nonexistent/poses.txt"), error);
}
