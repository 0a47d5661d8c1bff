// The light options of the command line (frontend/cli/options.hpp): --lights' text, the lights it
// chooses from a scene and the errors for indices the scene does not have, --light-intensity over
// several lights; and render --stats' time per light (frontend/cli/output.hpp).
#include <doctest/doctest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "frontend/cli/options.hpp"
#include "frontend/cli/output.hpp"
#include "frontend/scene/scene.hpp"

using namespace vplkit;
using namespace vplkit::cli;

namespace {

std::vector<scene_light> three_lights() {
  std::vector<scene_light> lights(3);
  lights[0].spot.position = {0, 2, 0};
  lights[0].spot.intensity = {4.0f, 2.0f, 1.0f};
  lights[1].kind = light_kind::point;
  lights[1].point.position = {1, 1, 1};
  lights[1].point.intensity = {0.5f, 0.5f, 8.0f};
  lights[2].kind = light_kind::directional;
  lights[2].directional.irradiance = {0.25f, 1.0f, 0.0f};
  return lights;
}

}  // namespace

TEST_CASE("parse_light_choice: all, none, indices in the order given; bad texts say what is wrong") {
  std::string problem = "left from before";
  CHECK(!parse_light_choice("all", problem));
  CHECK(problem.empty());
  const auto none = parse_light_choice("none", problem);
  REQUIRE(none);
  CHECK(none->empty());
  const auto two = parse_light_choice("0,2", problem);
  REQUIRE(two);
  CHECK(*two == std::vector<std::size_t>{0, 2});
  const auto reordered = parse_light_choice("2,0", problem);
  REQUIRE(reordered);
  CHECK(*reordered == std::vector<std::size_t>{2, 0});
  for (const std::string bad : {"", "0,,1", "a", "-1", "9999", "0,", ",0", " 1", "1.5", "All"}) {
    CAPTURE(bad);
    CHECK(!parse_light_choice(bad, problem));
    CHECK(problem.find("expected all, none or light indices separated by commas") != std::string::npos);
  }
  CHECK(!parse_light_choice("1,1", problem));
  CHECK(problem == "light 1 is chosen twice");
}

TEST_CASE("apply_poses: --lights chooses the scene's lights in the order given; an index it does not have is a usage error naming --lights") {
  camera view;
  common_options options;
  std::string problem;
  options.light_choice = parse_light_choice("2,0", problem);
  std::vector<scene_light> lights = three_lights();
  apply_poses(options, view, lights);
  REQUIRE(lights.size() == 2);
  CHECK(lights[0].kind == light_kind::directional);
  CHECK(lights[1].kind == light_kind::spot);
  // --light places the first chosen one.
  options.light_pose = pose{{0, 5, 0}, {1, 5, 0}};
  lights = three_lights();
  apply_poses(options, view, lights);
  CHECK(lights[0].directional.direction == glm::vec3(1, 0, 0));
  CHECK(lights[1].spot.position == glm::vec3(0, 2, 0));

  options.light_pose.reset();
  options.light_choice = parse_light_choice("0,3", problem);
  lights = three_lights();
  CHECK_THROWS_WITH_AS(apply_poses(options, view, lights), doctest::Contains("--lights: the scene has no light 3 (it has 3, 0 to 2)"), usage_error);
  CHECK(lights.size() == 3);  // untouched by the refusal
  // A scene with 9 lights: check_scene refuses it (above), --lights 0,2 then gives two.
  std::vector<scene_light> nine(9, three_lights()[0]);
  options.light_choice = parse_light_choice("0,2", problem);
  apply_poses(options, view, nine);
  CHECK(nine.size() == 2);
  CHECK_NOTHROW(check_lights(nine, "test"));
  // No lights: --light has nothing to place.
  options.light_choice = parse_light_choice("none", problem);
  options.light_pose = pose{{0, 5, 0}, {1, 5, 0}};
  lights = three_lights();
  CHECK_THROWS_WITH_AS(apply_poses(options, view, lights), doctest::Contains("--light: the scene has no light to place"), usage_error);
}

TEST_CASE("scale_light_intensities: one light is set_light_intensity bit for bit; several keep their ratios, the brightest channel becomes the intensity") {
  for (const scene_light& light : three_lights()) {
    for (const float intensity : {0.0f, 0.3f, 7.0f, 1.0e6f}) {
      scene_light alone = light;
      set_light_intensity(alone, intensity);
      std::vector<scene_light> one{light};
      scale_light_intensities(one, intensity);
      CHECK(light_power(one[0]) == light_power(alone));  // exactly
    }
  }
  std::vector<scene_light> lights = three_lights();
  scale_light_intensities(lights, 2.0f);
  // The brightest channel of all is the point light's blue, 8: everything is scaled by 2 / 8.
  CHECK(light_power(lights[1]).b == 2.0f);
  const std::vector<scene_light> before = three_lights();
  for (std::size_t k = 0; k < lights.size(); ++k)
    for (int c = 0; c < 3; ++c) CHECK(light_power(lights[k])[c] == doctest::Approx(light_power(before[k])[c] * 0.25f).epsilon(1e-6));
  CHECK_THROWS(scale_light_intensities(lights, -1.0f));
}

TEST_CASE("render --stats' time per light: passes naming \"light K\" summed per light, the rest shared") {
  const std::vector<pass_time> passes{{"G-buffer", 2.0},         {"RSM light 0", 3.0},       {"RSM light 1 face 0", 1.0}, {"RSM light 1 face 1", 1.5},
                                      {"gather light 1", 4.0},   {"gather light 0", 5.0},    {"spotlight 7", 0.25},       {"light 2b", 0.5},
                                      {"lighting 3", 0.125},     {"post filter", 1.0},       {"shadow light 12", 0.75}};
  const light_times times = group_by_light(passes);
  REQUIRE(times.lights.size() == 3);
  CHECK(times.lights[0].light == 0);
  CHECK(times.lights[0].passes == 2);
  CHECK(times.lights[0].milliseconds == 8.0);
  CHECK(times.lights[1].light == 1);
  CHECK(times.lights[1].passes == 3);
  CHECK(times.lights[1].milliseconds == 6.5);
  CHECK(times.lights[2].light == 12);
  CHECK(times.lights[2].milliseconds == 0.75);
  // "spotlight 7", "light 2b" and "lighting 3" name no light: shared with the G-buffer and the filter.
  CHECK(times.shared_passes == 5);
  CHECK(times.shared_milliseconds == 3.875);
  const std::string table = format_light_table(times);
  CHECK(table.find("| 0 | 2 | 8.00 | 41.8 |") != std::string::npos);  // 8 of 19.125 ms
  CHECK(table.find("| 1 | 3 | 6.50 | 34.0 |") != std::string::npos);
  CHECK(table.find("| shared | 5 | 3.88 | 20.3 |") != std::string::npos);
  CHECK(light_times_json(times) ==
        "[{\"light\": 0, \"passes\": 2, \"ms\": 8}, {\"light\": 1, \"passes\": 3, \"ms\": 6.5}, {\"light\": 12, \"passes\": 1, \"ms\": 0.75}], \"shared_ms\": 3.875");
  // A pipeline whose passes name no light (one light): no table, an empty list.
  CHECK(format_light_table(group_by_light({{"G-buffer", 1.0}, {"RSM", 2.0}})).empty());
  CHECK(light_times_json(group_by_light({})) == "[], \"shared_ms\": 0");
}
