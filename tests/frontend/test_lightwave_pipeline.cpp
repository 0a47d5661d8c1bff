// The Light Wave pipeline (frontend/lightwave_pipeline.hpp): its vertex stage against the CPU sum
// of Eq. 4.5 through transform feedback, every mode at a small size, rebuilds only on change,
// the shadow-map memory of Eq. 5.4/5.5, and bad settings.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "frontend/error.hpp"
#include "frontend/lightwave_pipeline.hpp"
#include "tests/parity/parity_harness.hpp"

using namespace vplkit;
using namespace vplkit::parity;

namespace {

lightwave_settings small(const char* technique) {
  lightwave_settings settings;
  settings.technique = technique;
  settings.width = 64;
  settings.height = 36;
  settings.shadow_map_scale = 2.0f;
  settings.format = texel_format::rgba32f;
  return settings;
}

}  // namespace

TEST_CASE("Light Wave vertex stage equals the CPU sum of Eq. 4.5 over all 6485 VPLs, vertex by vertex") {
  const scene boxes = make_boxes_scene();
  lightwave_pipeline pipeline(test_shaders(), boxes, small("lightwave-unshadowed"));
  const std::vector<glm::vec3> gpu = pipeline.capture_vertex_indirect();
  REQUIRE(gpu.size() == boxes.geometry.vertices.size());
  const auto& vpls = pipeline.vpls();
  REQUIRE(vpls.size() == 6485u);
  kernel_inputs inputs;
  inputs.width = static_cast<int>(gpu.size());
  inputs.height = 1;
  inputs.floats.assign(1, std::vector<glm::vec4>(gpu.size()));
  std::vector<glm::vec4> gpu4(gpu.size()), cpu4(gpu.size());
  for (std::size_t i = 0; i < gpu.size(); ++i) {
    const vertex& v = boxes.geometry.vertices[i];
    inputs.floats[0][i] = glm::vec4(v.position, 0.0f);
    gpu4[i] = glm::vec4(gpu[i], 0.0f);
    cpu4[i] = glm::vec4(lightwave_vertex_indirect(v.position, glm::normalize(v.normal), v.albedo, boxes.view.position,
                                                  [&](int index) { return vpls[static_cast<std::size_t>(index)]; }, static_cast<int>(vpls.size()),
                                                  pipeline.settings().shading),
                        0.0f);
  }
  // 6485 terms per vertex (two normalisations and a divide each) summed in the same order:
  // 2e-5 relative, or 1e-7 absolute near 0.
  require_parity(compare("Light Wave vertex stage (transform feedback)", gpu4, cpu4, inputs, {1e-7f, 2e-5f, 128, 0.0, "6485 terms of Eq. 4.5"}, 3));
}

TEST_CASE("Light Wave modes: finite images; shadows only remove indirect light; direct <= everything") {
  const scene boxes = make_boxes_scene();
  std::map<std::string, std::vector<float>> images;
  for (const lightwave_technique& technique : lightwave_techniques()) {
    lightwave_pipeline pipeline(test_shaders(), boxes, small(technique.name));
    const lightwave_frame frame = pipeline.render();
    for (float value : frame.radiance) REQUIRE(std::isfinite(value));
    images[technique.name] = frame.radiance;
  }
  const auto& unshadowed = images["lightwave-unshadowed"];
  std::size_t darker_accurate = 0, darker_integrated = 0;
  for (std::size_t i = 0; i < unshadowed.size(); i += 4) {
    for (int c = 0; c < 3; ++c) {
      const std::size_t k = i + static_cast<std::size_t>(c);
      REQUIRE(images["lightwave-accurate"][k] <= unshadowed[k]);
      REQUIRE(images["lightwave-integrated"][k] <= unshadowed[k]);
      REQUIRE(images["lightwave-direct"][k] <= images["lightwave-accurate"][k]);
    }
    darker_accurate += images["lightwave-accurate"][i] < unshadowed[i];
    darker_integrated += images["lightwave-integrated"][i] < unshadowed[i];
  }
  CHECK(darker_accurate > 0);  // indirect shadows exist
  CHECK(darker_integrated > 0);
  // Faked indirect (Eq. 5.2, m = 1.3) is brighter than direct light wherever direct light
  // reaches: direct * (0.5 shadow + 0.8) >= direct * shadow.
  std::size_t lit = 0, brighter = 0;
  for (std::size_t i = 0; i < unshadowed.size(); i += 4) {
    lit += images["lightwave-direct"][i] > 0.0f;
    brighter += images["lightwave-faked"][i] > images["lightwave-direct"][i];
    REQUIRE(images["lightwave-faked"][i] >= images["lightwave-direct"][i]);
  }
  CHECK(brighter >= lit);  // and in direct shadow too, where it is 0.8 direct
  CHECK(lit > 0);
}

TEST_CASE("Light Wave rebuilds VPLs and shadow maps only when the light moves") {
  lightwave_pipeline pipeline(test_shaders(), make_boxes_scene(), small("lightwave-accurate"));
  const lightwave_frame first = pipeline.render();
  CHECK(pipeline.rebuilds() == 1);
  CHECK(first.pass_times.size() == 2);
  const lightwave_frame second = pipeline.render();
  CHECK(pipeline.rebuilds() == 1);
  REQUIRE(second.pass_times.size() == 1);
  CHECK(second.pass_times[0].pass == "main pass");
  spot_light<float> moved = make_boxes_scene().light.spot;
  moved.position.x += 0.3f;
  pipeline.set_light(moved);
  pipeline.render();
  CHECK(pipeline.rebuilds() == 2);
  CHECK(pipeline.layout().light_position.x == doctest::Approx(moved.position.x));
}

TEST_CASE("shadow-map memory: Eq. 5.4 and 5.5 for the thesis's configuration") {
  const double mib = 1024.0 * 1024.0;
  CHECK(static_cast<double>(lightwave_shadow_map_bytes(3840, 2160, 1)) / mib == doctest::Approx(31.640625));
  CHECK(static_cast<double>(lightwave_shadow_map_bytes(3840, 2160, 21)) / mib == doctest::Approx(664.453125));
  // The pipeline reports what it allocated: 1 + 20 maps of 2x the 64 x 36 screen.
  lightwave_pipeline pipeline(test_shaders(), make_boxes_scene(), small("lightwave-accurate"));
  CHECK(pipeline.shadow_map_bytes() == lightwave_shadow_map_bytes(128, 72, 21));
  lightwave_pipeline integrated(test_shaders(), make_boxes_scene(), small("lightwave-integrated"));
  CHECK(integrated.shadow_map_bytes() == lightwave_shadow_map_bytes(128, 72, 6));
}

TEST_CASE("the VPLs that get shadow maps: reproducible random draws, and the innermost axis and ring") {
  lightwave_settings settings;
  const std::vector<int> drawn = lightwave_shadow_vpls(lightwave_mode::accurate, settings);
  CHECK(drawn.size() == 20u);
  CHECK(drawn == lightwave_shadow_vpls(lightwave_mode::accurate, settings));
  std::vector<int> sorted = drawn;
  std::sort(sorted.begin(), sorted.end());
  CHECK(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end());
  settings.seed = 2;
  CHECK(lightwave_shadow_vpls(lightwave_mode::accurate, settings) != drawn);
  // Integrated: the axis and four VPLs 45 degrees off it, a quarter turn apart, all innermost.
  settings = {};
  const std::vector<int> ring = lightwave_shadow_vpls(lightwave_mode::integrated, settings);
  REQUIRE(ring.size() == 5u);
  lightwave_layout_settings<double> layout;
  for (std::size_t k = 1; k < ring.size(); ++k) {
    const lightwave_vpl<double> vpl = lightwave_layout_vpl(ring[k], layout);
    CHECK(ring[k] < lightwave_ray_count(5));  // innermost hemisphere
    CHECK(glm::dot(vpl.normal, layout.light_direction) == doctest::Approx(std::cos(3.14159265358979 / 4)));
    const lightwave_vpl<double> next = lightwave_layout_vpl(ring[k % 4 + 1], layout);
    CHECK(glm::dot(vpl.normal - layout.light_direction * glm::dot(vpl.normal, layout.light_direction),
                   next.normal - layout.light_direction * glm::dot(next.normal, layout.light_direction)) == doctest::Approx(0.0).scale(1.0));
  }
}

TEST_CASE("longest-edge refinement reaches the count, keeps the surface closed, splits the longest edges first") {
  mesh cube;
  add_box(cube, glm::vec3(0.0f), glm::vec3(1.0f, 2.0f, 4.0f), 0.0f, glm::vec3(0.5f));
  const mesh refined = refine_longest_edges(cube, 500);
  CHECK(refined.triangle_count() >= 500);
  CHECK(refined.triangle_count() <= 501);  // each split adds 2 triangles on a closed surface
  // Closed: every edge is shared by exactly two triangles, in opposite directions (no cracks).
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (std::size_t t = 0; t < refined.indices.size(); t += 3)
    for (int k = 0; k < 3; ++k) ++directed[{refined.indices[t + static_cast<std::size_t>(k)], refined.indices[t + static_cast<std::size_t>((k + 1) % 3)]}];
  for (const auto& [edge, count] : directed) {
    REQUIRE(count == 1);
    REQUIRE(directed.count({edge.second, edge.first}) == 1);
  }
  // The area is unchanged and every triangle keeps its orientation (normals outward).
  double area = 0.0;
  for (std::size_t t = 0; t < refined.indices.size(); t += 3) {
    const glm::vec3 a = refined.vertices[refined.indices[t]].position, b = refined.vertices[refined.indices[t + 1]].position,
                    c = refined.vertices[refined.indices[t + 2]].position;
    const glm::vec3 cross = glm::cross(b - a, c - a);
    area += 0.5 * glm::length(cross);
    REQUIRE(glm::dot(cross, (a + b + c) / 3.0f) > 0.0f);  // outward for a box centred at 0
  }
  CHECK(area == doctest::Approx(2.0 * (1 * 2 + 1 * 4 + 2 * 4)).epsilon(1e-5));
}

TEST_CASE("Light Wave settings errors name the setting") {
  const auto message = [](lightwave_settings settings) {
    try {
      lightwave_pipeline(test_shaders(), make_boxes_scene(), settings);
    } catch (const vplkit::error& failure) {
      return std::string(failure.what());
    }
    return std::string("(no error)");
  };
  lightwave_settings s = small("lightwave-accurate");
  s.angle_deg = 7;
  CHECK(message(s).find("must divide 90 and 360") != std::string::npos);
  s = small("lightwave-accurate");
  s.per_ray = 0;
  CHECK(message(s).find("VPLs per ray") != std::string::npos);
  s = small("lightwave-accurate");
  s.angle_deg = 90;
  s.per_ray = 1;  // 5 VPLs
  CHECK(message(s).find("more accurate shadow maps (20) than VPLs (5)") != std::string::npos);
  s = small("lightwave-integrated");
  s.integrated_steps = -1;
  CHECK(message(s).find("integrated steps must be >= 0") != std::string::npos);
  s = small("lightwave-accurate");
  s.shadow_map_scale = 400.0f;  // 25600 x 14400
  CHECK(message(s).find("GL_MAX_TEXTURE_SIZE") != std::string::npos);
  s = small("lightwave-accurate");
  s.width = 1280;
  s.height = 720;
  s.shadow_map_scale = 12.0f;  // 15360 x 8640 x 21 layers: 10.4 GiB
  CHECK(message(s).find("GL_OUT_OF_MEMORY") != std::string::npos);
  s = small("lightwave-accurate");
  s.accurate_maps = 0;
  CHECK(message(s).find("accurate shadow maps must be in [1, 64]") != std::string::npos);
}
