// The Light Wave pipeline (frontend/techniques/lightwave/lightwave_pipeline.hpp): its vertex stage against the CPU sum
// of Eq. 4.5 through transform feedback, every mode at a small size, rebuilds only on change,
// the shadow-map memory of Eq. 5.4/5.5, and bad settings.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/parity/doctest.hpp>

#include "frontend/core/error.hpp"
#include "frontend/image/image_files.hpp"
#include "frontend/techniques/lightwave/lightwave_pipeline.hpp"

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
  std::map<std::string, image> images;
  for (const lightwave_technique& technique : lightwave_techniques()) {
    lightwave_pipeline pipeline(test_shaders(), boxes, small(technique.name));
    const lightwave_frame frame = pipeline.render();
    for (const glm::vec4& texel : frame.radiance.texels)
      for (int c = 0; c < 4; ++c) REQUIRE(std::isfinite(texel[c]));
    images[technique.name] = frame.radiance;
  }
  const auto& unshadowed = images["lightwave-unshadowed"];
  std::size_t darker_accurate = 0, darker_integrated = 0;
  for (std::size_t i = 0; i < unshadowed.texels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      REQUIRE(images["lightwave-accurate"].texels[i][c] <= unshadowed.texels[i][c]);
      REQUIRE(images["lightwave-integrated"].texels[i][c] <= unshadowed.texels[i][c]);
      REQUIRE(images["lightwave-direct"].texels[i][c] <= images["lightwave-accurate"].texels[i][c]);
    }
    darker_accurate += images["lightwave-accurate"].texels[i].r < unshadowed.texels[i].r;
    darker_integrated += images["lightwave-integrated"].texels[i].r < unshadowed.texels[i].r;
  }
  CHECK(darker_accurate > 0);  // indirect shadows exist
  CHECK(darker_integrated > 0);
  // Faked indirect (Eq. 5.2, m = 1.3) is brighter than direct light wherever direct light
  // reaches: direct * (0.5 shadow + 0.8) >= direct * shadow.
  std::size_t lit = 0, brighter = 0;
  for (std::size_t i = 0; i < unshadowed.texels.size(); ++i) {
    lit += images["lightwave-direct"].texels[i].r > 0.0f;
    brighter += images["lightwave-faked"].texels[i].r > images["lightwave-direct"].texels[i].r;
    REQUIRE(images["lightwave-faked"].texels[i].r >= images["lightwave-direct"].texels[i].r);
  }
  CHECK(brighter >= lit);  // and in direct shadow too, where it is 0.8 direct
  CHECK(lit > 0);
}

TEST_CASE("Light Wave redraws what a move invalidated: VPLs and shadow maps after a light move, the main pass after any; draw() redraws both") {
  lightwave_settings settings = small("lightwave-accurate");
  settings.shadow_variant = lightwave_shadow_variant::thesis;  // casters that do not follow the camera
  lightwave_pipeline pipeline(test_shaders(), make_boxes_scene(), settings);
  const auto passes = [&] {
    std::vector<std::string> names;
    for (const pass_time& pass : pipeline.collect_pass_times()) names.push_back(pass.pass);
    return names;
  };
  pipeline.draw_changed();
  CHECK(pipeline.rebuilds() == 1);
  CHECK(passes() == std::vector<std::string>{"VPLs and shadow maps", "main pass"});
  pipeline.draw_changed();  // nothing moved
  CHECK(passes().empty());
  pipeline.set_camera(pipeline.current_camera());
  pipeline.draw_changed();
  CHECK(pipeline.rebuilds() == 1);
  CHECK(passes() == std::vector<std::string>{"main pass"});
  scene_light moved = make_boxes_scene().light;
  moved.spot.position.x += 0.3f;
  pipeline.set_light(moved);
  pipeline.draw_changed();
  CHECK(pipeline.rebuilds() == 2);
  CHECK(pipeline.layout().light_position.x == doctest::Approx(moved.spot.position.x));
  CHECK(passes().size() == 2);
  const lightwave_frame every = pipeline.render();  // draw(): every pass
  CHECK(pipeline.rebuilds() == 3);
  CHECK(every.pass_times.size() == 2);
  CHECK(pipeline.view_draws() == 4);
  // A directional light is refused, and the light stays.
  scene_light sun;
  sun.kind = light_kind::directional;
  CHECK_THROWS_WITH_AS(pipeline.set_light(sun), doctest::Contains("needs a spot light"), vplkit::error);
  CHECK(pipeline.current_light().spot.position.x == doctest::Approx(moved.spot.position.x));
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

namespace {

// The message a pipeline built with `settings` on the boxes throws, or "(no error)".
std::string settings_error(const lightwave_settings& settings) {
  try {
    lightwave_pipeline(test_shaders(), make_boxes_scene(), settings);
  } catch (const vplkit::error& failure) {
    return std::string(failure.what());
  }
  return std::string("(no error)");
}

}  // namespace

TEST_CASE("Light Wave settings errors name the setting") {
  const auto message = settings_error;
  lightwave_settings s = small("lightwave-accurate");
  s.angle_deg = 7;
  CHECK(message(s).find("ray-angle must be 1, 2, 3, 5, 6, 9, 10, 15, 18, 30, 45 or 90, got '7'") != std::string::npos);
  s = small("lightwave-accurate");
  s.per_ray = 0;
  CHECK(message(s).find("vpls-per-ray must be a whole number in [1, 32]") != std::string::npos);
  s = small("lightwave-accurate");
  s.angle_deg = 90;
  s.per_ray = 1;  // 5 VPLs
  CHECK(message(s).find("more accurate shadow maps (20) than VPLs (5)") != std::string::npos);
  s = small("lightwave-integrated");
  s.integrated_steps = -1;
  CHECK(message(s).find("integrated-steps must be a whole number in [0, 64]") != std::string::npos);
  s = small("lightwave-accurate");
  s.shadow_map_scale = 17.0f;
  CHECK(message(s).find("shadow-map-scale must be a number in (0, 16]") != std::string::npos);
  s.width = 1280;
  s.height = 720;
  s.shadow_map_scale = 14.0f;  // 17920 x 10080
  CHECK(message(s).find("GL_MAX_TEXTURE_SIZE") != std::string::npos);
  s = small("lightwave-accurate");
  s.accurate_maps = 65;
  CHECK(message(s).find("shadow-maps must be a whole number in [0, 64]") != std::string::npos);
  s = small("lightwave-faked");
  for (float bad : {std::nanf(""), -1.0f, 0.0f, 100.0f}) {
    s.faked_multiplier = bad;
    CHECK(message(s).find("faked-multiplier must be a number in [0.5, 4]") != std::string::npos);
  }
}

TEST_CASE("Light Wave shadow maps beyond the GL implementation's memory: GL_OUT_OF_MEMORY, named" * doctest::test_suite("slow")) {
  lightwave_settings s = small("lightwave-accurate");
  s.width = 1280;
  s.height = 720;
  s.shadow_map_scale = 12.0f;  // 15360 x 8640 x 21 layers: 10.4 GiB
  CHECK(settings_error(s).find("GL_OUT_OF_MEMORY") != std::string::npos);
}

namespace {

// A floor seen from straight above, a spot light over its left part, and optionally a wall
// standing across the floor at x = 2 (2.5 high, above the light): the floor beyond it (x > 2) is
// hidden from the VPLs on the light's side, among them the whole innermost hemisphere (2.7 from
// the light), the brightest.
scene wall_scene(bool with_wall) {
  scene s;
  s.name = with_wall ? "wall" : "plane";
  add_quad(s.geometry, {-3, 0, 3}, {3, 0, 3}, {3, 0, -3}, {-3, 0, -3}, {0, 1, 0}, glm::vec3(0.7f));
  if (with_wall) add_box(s.geometry, {2.0f, 1.25f, 0.0f}, {0.1f, 2.5f, 4.0f}, 0.0f, glm::vec3(0.7f));
  s.view.position = {0.0f, 7.0f, 0.001f};
  s.view.target = {0.0f, 0.0f, 0.0f};
  s.view.vertical_fov_degrees = 50.0f;
  s.light.kind = light_kind::spot;
  s.light.spot.position = {-1.0f, 2.0f, 0.0f};
  s.light.spot.direction = {0.0f, -1.0f, 0.0f};
  s.light.spot.intensity = glm::vec3(4.0f);
  s.light.spot.cos_inner = std::cos(glm::radians(50.0f));
  s.light.spot.cos_outer = std::cos(glm::radians(65.0f));
  return s;
}

// The mean indirect shadow factor over the floor pixels whose world point lies in [x0, x1] x [z0, z1].
double mean_factor(const lightwave_frame& frame, const scene& s, float x0, float x1, float z0, float z1) {
  const glm::mat4 view_projection = glm::perspective(glm::radians(s.view.vertical_fov_degrees), static_cast<float>(frame.radiance.width) / static_cast<float>(frame.radiance.height),
                                                     s.view.near_plane, s.view.far_plane) *
                                    glm::lookAt(s.view.position, s.view.target, s.view.up);
  double sum = 0.0;
  int count = 0;
  for (float x = x0; x <= x1; x += 0.05f)
    for (float z = z0; z <= z1; z += 0.05f) {
      const glm::vec4 clip = view_projection * glm::vec4(x, 0.0f, z, 1.0f);
      const int px = static_cast<int>((clip.x / clip.w * 0.5f + 0.5f) * static_cast<float>(frame.radiance.width));
      const int py = static_cast<int>((clip.y / clip.w * 0.5f + 0.5f) * static_cast<float>(frame.radiance.height));
      REQUIRE(px >= 0);
      REQUIRE(py >= 0);
      REQUIRE(px < frame.radiance.width);
      REQUIRE(py < frame.radiance.height);
      sum += frame.indirect_shadow.at(px, py).r;
      ++count;
    }
  return sum / count;
}

lightwave_settings square(const char* technique) {
  lightwave_settings settings = small(technique);
  settings.width = settings.height = 128;
  return settings;
}

}  // namespace

TEST_CASE("accurate indirect shadows shadow: a wall hides the floor behind it from the brightest VPLs, open floor stays unshadowed") {
  const scene s = wall_scene(true);
  lightwave_pipeline pipeline(test_shaders(), s, square("lightwave-accurate"));
  const lightwave_frame frame = pipeline.render();
  REQUIRE(pipeline.shadow_casters().size() == 20u);
  const double behind = mean_factor(frame, s, 2.1f, 2.7f, -0.8f, 0.8f);    // behind the wall
  const double open = mean_factor(frame, s, -2.6f, -1.6f, -0.8f, 0.8f);    // far on the light's side
  MESSAGE("accurate: mean indirect shadow factor behind the wall " << behind << ", on open floor " << open);
  CHECK(behind < 0.9);
  CHECK(open >= 0.99);
  // The thesis's variant (uniform VPLs, maps along the normals, the plain mean) barely sees it.
  lightwave_settings thesis = square("lightwave-accurate");
  thesis.shadow_variant = lightwave_shadow_variant::thesis;
  lightwave_pipeline thesis_pipeline(test_shaders(), s, thesis);
  const double thesis_behind = mean_factor(thesis_pipeline.render(), s, 2.1f, 2.7f, -0.8f, 0.8f);
  MESSAGE("thesis variant: mean factor behind the wall " << thesis_behind);
  CHECK(thesis_behind > behind);
}

TEST_CASE("integrated indirect shadows over an empty plane: no darkening anywhere") {
  const scene s = wall_scene(false);
  lightwave_pipeline pipeline(test_shaders(), s, square("lightwave-integrated"));
  const lightwave_frame frame = pipeline.render();
  float lowest = 1.0f;
  for (const glm::vec4& factor : frame.indirect_shadow.texels) lowest = std::min(lowest, factor.r);
  MESSAGE("integrated over an empty plane: lowest factor " << lowest);
  CHECK(lowest >= 0.99f);
  lightwave_pipeline accurate(test_shaders(), s, square("lightwave-accurate"));
  const lightwave_frame accurate_frame = accurate.render();
  lowest = 1.0f;
  for (const glm::vec4& factor : accurate_frame.indirect_shadow.texels) lowest = std::min(lowest, factor.r);
  CHECK(lowest >= 0.99f);
}

TEST_CASE("the number of indirect shadow maps matters: 0, 1, 5, 10 and 20 maps give five different images") {
  const scene boxes = make_boxes_scene();
  std::map<int, std::vector<std::uint8_t>> images;
  for (int maps : {0, 1, 5, 10, 20}) {
    lightwave_settings settings = small("lightwave-accurate");
    settings.width = 256;
    settings.height = 144;
    settings.accurate_maps = maps;
    lightwave_pipeline pipeline(test_shaders(), boxes, settings);
    const lightwave_frame frame = pipeline.render();
    images[maps] = to_srgb8(frame.radiance);
    if (maps == 0) {
      // No maps: exactly the image without indirect shadows.
      lightwave_settings unshadowed = settings;
      unshadowed.technique = "lightwave-unshadowed";
      lightwave_pipeline reference(test_shaders(), boxes, unshadowed);
      const lightwave_frame plain = reference.render();
      CHECK(to_srgb8(plain.radiance) == images[0]);
    }
  }
  const auto rmse = [](const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
    double sum = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      const double d = (static_cast<double>(a[i]) - static_cast<double>(b[i])) / 255.0;
      sum += d * d;
    }
    return std::sqrt(sum / static_cast<double>(a.size()));
  };
  for (int a : {0, 1, 5, 10, 20})
    for (int b : {0, 1, 5, 10, 20}) {
      if (a >= b) continue;
      CAPTURE(a);
      CAPTURE(b);
      MESSAGE(a << " against " << b << " maps: RMSE on 8-bit images " << rmse(images[a], images[b]));
      CHECK(rmse(images[a], images[b]) > 1e-3);
    }
}
