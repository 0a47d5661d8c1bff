// The Light Wave pipeline (frontend/techniques/lightwave/lightwave_pipeline.hpp): its vertex stage against the CPU sum
// of Eq. 4.5 through transform feedback, every mode at a small size, rebuilds only on change,
// the shadow-map memory of Eq. 5.4/5.5, and bad settings.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/parity/doctest.hpp>

#include "frontend/core/error.hpp"
#include "frontend/image/image_files.hpp"
#include "frontend/reference/reference.hpp"
#include "frontend/techniques/lightwave/lightwave_pipeline.hpp"
#include "frontend/techniques/registry.hpp"

using namespace vplkit;
using namespace vplkit::parity;

namespace {

lightwave_settings small_lightwave_settings(const char* technique) {
  lightwave_settings settings;
  settings.technique = technique;
  settings.width = 64;
  settings.height = 36;
  settings.shadow_map_scale = 2.0f;
  settings.format = texel_format::rgba32f;
  return settings;
}

}  // namespace

TEST_CASE("Light Wave vertex stage equals the CPU sum of Eq. 4.5 over all 6485 VPLs, vertex by vertex (thesis energy)") {
  const scene boxes = make_boxes_scene();
  lightwave_settings settings = small_lightwave_settings("lightwave-unshadowed");
  settings.energy = lightwave_energy::thesis;
  lightwave_pipeline pipeline(test_shaders(), boxes, settings);
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

namespace {

// The flux energy's indirect light at every receiver (lightwave_capture.frag) against the CPU sum
// over the receivers' VPLs at every receiver's sample point.
void check_receiver_sums(lightwave_pipeline& pipeline, const std::vector<glm::vec3>& gpu) {
  const mesh& receivers = pipeline.drawn_mesh();
  REQUIRE(gpu.size() == receivers.vertices.size());
  const auto& vpls = pipeline.receiver_vpls();
  kernel_inputs inputs;
  inputs.width = static_cast<int>(gpu.size());
  inputs.height = 1;
  inputs.floats.assign(1, std::vector<glm::vec4>(gpu.size()));
  std::vector<glm::vec4> gpu4(gpu.size()), cpu4(gpu.size());
  for (std::size_t i = 0; i < gpu.size(); ++i) {
    const vertex& v = receivers.vertices[i];
    inputs.floats[0][i] = glm::vec4(pipeline.receiver_samples()[i], 0.0f);
    gpu4[i] = glm::vec4(gpu[i], 0.0f);
    cpu4[i] = glm::vec4(lightwave_vertex_bounce(pipeline.receiver_samples()[i], glm::normalize(v.normal), v.albedo,
                                                [&](int index) { return vpls[static_cast<std::size_t>(index)]; }, static_cast<int>(vpls.size()),
                                                pipeline.settings().irradiance),
                        0.0f);
  }
  // Hundreds of terms (two divides each) summed in the same order: 2e-5 relative, 1e-7 absolute.
  require_parity(compare("Light Wave receiver sums (lightwave_capture.frag)", gpu4, cpu4, inputs, {1e-7f, 2e-5f, 128, 0.0, "flux VPLs of Eq. 3.2"}, 3));
}

}  // namespace

TEST_CASE("Light Wave flux energy: the indirect light summed at the receivers equals the CPU sum over the receivers' VPLs at every receiver's sample point") {
  const scene boxes = make_boxes_scene();
  lightwave_pipeline pipeline(test_shaders(), boxes, small_lightwave_settings("lightwave-unshadowed"));
  const std::vector<glm::vec3> gpu = pipeline.capture_vertex_indirect();
  REQUIRE(pipeline.drawn_mesh().triangle_count() > boxes.geometry.triangle_count());  // subdivided
  // Bands of lightwave_sum_receivers and a part of one, then empty texels: receiver i's sum read
  // from band i / cells, texel i % cells (each band's rows and a part of one).
  const std::size_t bands = lightwave_sum_receivers;
  const glm::ivec2 grid = lightwave_sum_grid(gpu.size(), 16384);
  const auto cells = static_cast<std::size_t>(grid.x) * static_cast<std::size_t>(grid.y);
  REQUIRE(gpu.size() > (bands - 1) * cells);
  REQUIRE(gpu.size() % cells != 0);
  REQUIRE(gpu.size() % static_cast<std::size_t>(grid.x) != 0);
  const auto& vpls = pipeline.receiver_vpls();
  REQUIRE(vpls.size() > 500u);
  REQUIRE(vpls.size() < pipeline.flux_vpls().size());  // a ray's samples on one plane merged
  check_receiver_sums(pipeline, gpu);

  SUBCASE("the VPLs in passes of 97: each pass continues the last one's sum, the same result to the bit") {
    lightwave_settings settings = small_lightwave_settings("lightwave-unshadowed");
    settings.vpls_per_pass = 97;
    lightwave_pipeline in_passes(test_shaders(), boxes, settings);
    const std::vector<glm::vec3> passes = in_passes.capture_vertex_indirect();
    REQUIRE(in_passes.receiver_vpls().size() > 5u * 97u);
    REQUIRE(passes.size() == gpu.size());
    std::size_t different = 0, first_different = gpu.size();
    for (std::size_t i = 0; i < gpu.size(); ++i)
      if (passes[i] != gpu[i]) {
        ++different;
        first_different = std::min(first_different, i);
      }
    CAPTURE(first_different);
    CHECK(different == 0);
    // A light move: each pass starts again from zero (not from the last light's sums), the
    // passes still equal to one pass, and both the CPU sum for the new light.
    scene_light moved = boxes.lights[0];
    moved.spot.position.x += 0.4f;
    moved.spot.direction = glm::normalize(moved.spot.direction + glm::vec3(0.1f, 0.0f, 0.0f));
    pipeline.set_light(0, moved);
    in_passes.set_light(0, moved);
    const std::vector<glm::vec3> moved_one = pipeline.capture_vertex_indirect(), moved_passes = in_passes.capture_vertex_indirect();
    REQUIRE(moved_one != gpu);
    CHECK(moved_passes == moved_one);
    check_receiver_sums(in_passes, moved_passes);
  }
  SUBCASE("the scene's own vertices as receivers: another grid") {
    lightwave_settings settings = small_lightwave_settings("lightwave-unshadowed");
    settings.receiver_spacing = 4.0f;  // the scene as it is
    lightwave_pipeline coarse(test_shaders(), boxes, settings);
    const std::vector<glm::vec3> sums = coarse.capture_vertex_indirect();
    REQUIRE(sums.size() < gpu.size() / 2);
    check_receiver_sums(coarse, sums);
  }
}

TEST_CASE("Light Wave flux energy: more VPLs per pass than a uniform block holds is refused, naming the limit") {
  // One more than this GL's block holds (test_shaders() makes the context current).
  test_shaders();
  GLint block_bytes = 0;
  glGetIntegerv(GL_MAX_UNIFORM_BLOCK_SIZE, &block_bytes);
  const int too_many = block_bytes / 48 + 1;
  lightwave_settings settings = small_lightwave_settings("lightwave-unshadowed");
  settings.vpls_per_pass = too_many;
  if (too_many <= 65535) {
    try {
      lightwave_pipeline pipeline(test_shaders(), make_boxes_scene(), settings);
      FAIL("no error");
    } catch (const error& e) {
      CHECK(std::string(e.what()).find(std::to_string(too_many) + " VPLs per pass need a uniform block of " + std::to_string(48 * too_many) + " bytes") !=
            std::string::npos);
      CHECK(std::string(e.what()).find("at most " + std::to_string(too_many - 1) + " VPLs per pass") != std::string::npos);
    }
  }
  settings.vpls_per_pass = -1;
  CHECK(validate(settings).find("VPLs per pass") != std::string::npos);
  settings.vpls_per_pass = 65536;
  CHECK(validate(settings).find("VPLs per pass") != std::string::npos);
}

TEST_CASE("Light Wave modes, both energies: finite images; shadows only remove indirect light; direct <= everything") {
  const scene boxes = make_boxes_scene();
  for (lightwave_energy energy : {lightwave_energy::flux, lightwave_energy::thesis}) {
    CAPTURE(static_cast<int>(energy));
    std::map<std::string, image> images;
    for (const lightwave_technique& technique : lightwave_techniques()) {
      lightwave_settings settings = small_lightwave_settings(technique.name);
      settings.energy = energy;
      lightwave_pipeline pipeline(test_shaders(), boxes, settings);
      const lightwave_frame frame = pipeline.render();
      for (const glm::vec4& texel : frame.radiance.texels)
        for (int c = 0; c < 4; ++c) REQUIRE(std::isfinite(texel[c]));
      images[technique.name] = frame.radiance;
    }
    const auto& unshadowed = images["lightwave-unshadowed"];
    std::size_t darker_accurate = 0, darker_integrated = 0;
    for (std::size_t i = 0; i < unshadowed.texels.size(); ++i) {
      for (int c = 0; c < 3; ++c) {
        // (The flux energy draws the receivers without shadows and the scene's own triangles with
        // them: the direct light may differ in the last bit.)
        REQUIRE(images["lightwave-accurate"].texels[i][c] <= unshadowed.texels[i][c] * (1.0f + 1e-5f) + 1e-7f);
        REQUIRE(images["lightwave-integrated"].texels[i][c] <= unshadowed.texels[i][c] * (1.0f + 1e-5f) + 1e-7f);
        // The flux energy draws the receivers, the direct light the scene's own triangles: their
        // fragments' positions, and so the direct light, may differ in the last bit.
        REQUIRE(images["lightwave-direct"].texels[i][c] <= images["lightwave-accurate"].texels[i][c] * (1.0f + 1e-5f) + 1e-7f);
      }
      darker_accurate += images["lightwave-accurate"].texels[i].r < unshadowed.texels[i].r * 0.999f;
      darker_integrated += images["lightwave-integrated"].texels[i].r < unshadowed.texels[i].r * 0.999f;
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
}

TEST_CASE("Light Wave redraws what a move invalidated: VPLs and shadow maps after a light move, the main pass after any; draw() redraws both") {
  lightwave_settings settings = small_lightwave_settings("lightwave-accurate");
  settings.shadow_variant = lightwave_shadow_variant::thesis;  // casters that do not follow the camera
  lightwave_pipeline pipeline(test_shaders(), make_boxes_scene(), settings);
  const auto passes = [&] {
    std::vector<std::string> names;
    for (const pass_time& pass : pipeline.collect_pass_times()) names.push_back(pass.pass);
    return names;
  };
  pipeline.draw_changed();
  CHECK(pipeline.rebuilds() == 1);
  // The flux energy sums the VPLs at the receivers and draws their light into the indirect buffer
  // the main pass reads.
  CHECK(passes() == std::vector<std::string>{"VPLs", "shadow maps", "indirect buffer", "main pass"});
  pipeline.draw_changed();  // nothing moved
  CHECK(passes().empty());
  pipeline.set_camera(pipeline.current_camera());
  pipeline.draw_changed();
  CHECK(pipeline.rebuilds() == 1);
  CHECK(passes() == std::vector<std::string>{"indirect buffer", "main pass"});
  scene_light moved = make_boxes_scene().lights.at(0);
  moved.spot.position.x += 0.3f;
  pipeline.set_light(0, moved);
  pipeline.draw_changed();
  CHECK(pipeline.rebuilds() == 2);
  CHECK(pipeline.layout().light_position.x == doctest::Approx(moved.spot.position.x));
  CHECK(passes().size() == 4);
  const lightwave_frame every = pipeline.render();  // draw(): every pass
  CHECK(pipeline.rebuilds() == 3);
  CHECK(every.pass_times.size() == 4);
  CHECK(pipeline.view_draws() == 4);
  // The default accurate shadows (importance, flux energy) choose their casters for the whole
  // scene: a camera move redraws the main pass alone; with the thesis energy they follow the camera.
  for (const lightwave_energy energy : {lightwave_energy::flux, lightwave_energy::thesis}) {
    lightwave_settings importance = small_lightwave_settings("lightwave-accurate");
    importance.energy = energy;
    lightwave_pipeline grouped(test_shaders(), make_boxes_scene(), importance);
    grouped.draw_changed();
    camera moved_camera = grouped.current_camera();
    moved_camera.position.x += 0.5f;
    grouped.set_camera(moved_camera);
    grouped.draw_changed();
    CAPTURE(static_cast<int>(energy));
    CHECK(grouped.rebuilds() == (energy == lightwave_energy::flux ? 1 : 2));
  }
  // A spot cannot become a sun in place (its programs and maps are a spot's): refused, and the light stays.
  scene_light sun;
  sun.kind = light_kind::directional;
  CHECK_THROWS_WITH_AS(pipeline.set_light(0, sun), doctest::Contains("is a spot light and cannot become a directional one"), vplkit::error);
  CHECK(pipeline.current_lights().at(0).spot.position.x == doctest::Approx(moved.spot.position.x));
}

TEST_CASE("shadow-map memory: the pipeline reports what it allocated") {
  // The pipeline reports what it allocated: 1 + 20 maps of 2x the 64 x 36 screen.
  lightwave_pipeline pipeline(test_shaders(), make_boxes_scene(), small_lightwave_settings("lightwave-accurate"));
  CHECK(pipeline.shadow_map_bytes() == lightwave_shadow_map_bytes(128, 72, 21));
  lightwave_pipeline integrated(test_shaders(), make_boxes_scene(), small_lightwave_settings("lightwave-integrated"));
  CHECK(integrated.shadow_map_bytes() == lightwave_shadow_map_bytes(128, 72, 6));
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
  lightwave_settings s = small_lightwave_settings("lightwave-accurate");
  s.angle_deg = 7;
  CHECK(message(s).find("ray-angle must be 1, 2, 3, 5, 6, 9, 10, 15, 18, 30, 45 or 90, got '7'") != std::string::npos);
  s = small_lightwave_settings("lightwave-accurate");
  s.per_ray = 0;
  CHECK(message(s).find("vpls-per-ray must be a whole number in [1, 32]") != std::string::npos);
  s = small_lightwave_settings("lightwave-accurate");
  s.angle_deg = 90;
  s.per_ray = 1;  // 5 VPLs
  CHECK(message(s).find("more accurate shadow maps (20) than VPLs (5)") != std::string::npos);
  s = small_lightwave_settings("lightwave-integrated");
  s.integrated_steps = -1;
  CHECK(message(s).find("integrated-steps must be a whole number in [0, 64]") != std::string::npos);
  s = small_lightwave_settings("lightwave-accurate");
  s.shadow_map_scale = 17.0f;
  CHECK(message(s).find("shadow-map-scale must be a number in (0, 16]") != std::string::npos);
  s.width = 1280;
  s.height = 720;
  s.shadow_map_scale = 14.0f;  // 17920 x 10080: refused by validate(), naming the settings, before a texture is made
  CHECK(message(s).find("shadow-map-scale 14 with a 1280x720 image (size) makes shadow maps of 17920 texels per side, more than 16384") !=
        std::string::npos);
  s = small_lightwave_settings("lightwave-accurate");
  s.accurate_maps = 65;
  CHECK(message(s).find("shadow-maps must be a whole number in [0, 64]") != std::string::npos);
  s = small_lightwave_settings("lightwave-faked");
  for (float bad : {std::nanf(""), -1.0f, 0.0f, 100.0f}) {
    s.faked_multiplier = bad;
    CHECK(message(s).find("faked-multiplier must be a number in [0.5, 4]") != std::string::npos);
  }
}

TEST_CASE("Light Wave shadow maps beyond the GL implementation's memory: GL_OUT_OF_MEMORY, named" * doctest::test_suite("slow")) {
  lightwave_settings s = small_lightwave_settings("lightwave-accurate");
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
  s.lights.emplace_back().kind = light_kind::spot;
  s.lights[0].spot.position = {-1.0f, 2.0f, 0.0f};
  s.lights[0].spot.direction = {0.0f, -1.0f, 0.0f};
  s.lights[0].spot.intensity = glm::vec3(4.0f);
  s.lights[0].spot.cos_inner = std::cos(glm::radians(50.0f));
  s.lights[0].spot.cos_outer = std::cos(glm::radians(65.0f));
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
  lightwave_settings settings = small_lightwave_settings(technique);
  settings.width = settings.height = 128;
  return settings;
}

lightwave_settings thesis_energy(lightwave_settings settings) {
  settings.energy = lightwave_energy::thesis;
  return settings;
}

}  // namespace

TEST_CASE("accurate indirect shadows, thesis energy: a wall hides the floor behind it from the brightest VPLs, open floor stays unshadowed") {
  // The thesis's VPLs float in space and light the floor from above; flux VPLs on the floor would
  // not light the floor (the panel test below is the flux energy's).
  const scene s = wall_scene(true);
  lightwave_pipeline pipeline(test_shaders(), s, thesis_energy(square("lightwave-accurate")));
  const lightwave_frame frame = pipeline.render();
  REQUIRE(pipeline.shadow_casters().size() == 20u);
  const double behind = mean_factor(frame, s, 2.1f, 2.7f, -0.8f, 0.8f);    // behind the wall
  const double open = mean_factor(frame, s, -2.6f, -1.6f, -0.8f, 0.8f);    // far on the light's side
  MESSAGE("accurate: mean indirect shadow factor behind the wall " << behind << ", on open floor " << open);
  CHECK(behind < 0.9);
  CHECK(open >= 0.99);
  // The thesis's variant (uniform VPLs, maps along the normals, the plain mean) barely sees it.
  lightwave_settings thesis = thesis_energy(square("lightwave-accurate"));
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

TEST_CASE("the number of indirect shadow maps matters: 0, 1, 5, 10 and 20 maps give five different images (thesis energy, Table 5.8)") {
  const scene boxes = make_boxes_scene();
  std::map<int, std::vector<std::uint8_t>> images;
  for (int maps : {0, 1, 5, 10, 20}) {
    lightwave_settings settings = small_lightwave_settings("lightwave-accurate");
    settings.energy = lightwave_energy::thesis;  // the thesis's table; the boxes barely occlude a flux bounce
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

TEST_CASE("flux energy: accurate shadows with no map give the unshadowed image") {
  const scene boxes = make_boxes_scene();
  lightwave_settings settings = small_lightwave_settings("lightwave-accurate");
  settings.width = 256;
  settings.height = 144;
  settings.accurate_maps = 0;
  lightwave_pipeline accurate(test_shaders(), boxes, settings);
  const lightwave_frame buffered = accurate.render();
  settings.technique = "lightwave-unshadowed";
  lightwave_pipeline unshadowed(test_shaders(), boxes, settings);
  const lightwave_frame direct = unshadowed.render();
  REQUIRE(buffered.radiance.texels.size() == direct.radiance.texels.size());
  double largest = 0.0, total = 0.0;
  for (std::size_t i = 0; i < direct.radiance.texels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      largest = std::max(largest, std::fabs(static_cast<double>(buffered.radiance.texels[i][c]) - static_cast<double>(direct.radiance.texels[i][c])));
      total += static_cast<double>(direct.radiance.texels[i][c]);
    }
  MESSAGE("largest difference " << largest << ", mean radiance " << total / (3.0 * static_cast<double>(direct.radiance.texels.size())));
  // The same indirect light from the receivers' buffer; the two programs' fragments may differ in the last bits.
  CHECK(largest <= 1e-3 * total / (3.0 * static_cast<double>(direct.radiance.texels.size())));
  CHECK(total > 0.0);
}

// ---- The flux energy: light that follows the spot and the albedos, wherever the spot points ----

namespace {

// A closed room [-2, 2] x [0, 2.5] x [-3, 3] (inner faces), optionally with a panel standing on the
// floor at x = -1 (z in [-1, 1], 1 high) between the lit floor and the wall at x = -2.
scene room_scene(bool with_panel, float albedo_scale = 1.0f) {
  scene s;
  s.name = with_panel ? "room with a panel" : "empty room";
  mesh& m = s.geometry;
  const glm::vec3 white(0.7f * albedo_scale), red(0.7f * albedo_scale, 0.2f * albedo_scale, 0.1f * albedo_scale);
  add_quad(m, {-2, 0, 3}, {2, 0, 3}, {2, 0, -3}, {-2, 0, -3}, {0, 1, 0}, white);            // floor
  add_quad(m, {-2, 2.5f, -3}, {2, 2.5f, -3}, {2, 2.5f, 3}, {-2, 2.5f, 3}, {0, -1, 0}, white);  // ceiling
  add_quad(m, {-2, 0, -3}, {2, 0, -3}, {2, 2.5f, -3}, {-2, 2.5f, -3}, {0, 0, 1}, white);    // back
  add_quad(m, {2, 0, 3}, {-2, 0, 3}, {-2, 2.5f, 3}, {2, 2.5f, 3}, {0, 0, -1}, white);       // front
  add_quad(m, {-2, 0, 3}, {-2, 0, -3}, {-2, 2.5f, -3}, {-2, 2.5f, 3}, {1, 0, 0}, red);      // left
  add_quad(m, {2, 0, -3}, {2, 0, 3}, {2, 2.5f, 3}, {2, 2.5f, -3}, {-1, 0, 0}, white);       // right
  if (with_panel) add_box(m, {-1.0f, 0.5f, 0.0f}, {0.05f, 1.0f, 2.0f}, 0.0f, white);
  s.view.position = {1.8f, 1.4f, 2.8f};
  s.view.target = {-1.5f, 0.6f, 0.0f};
  s.view.vertical_fov_degrees = 60.0f;
  s.lights.emplace_back().kind = light_kind::spot;
  s.lights[0].spot.position = {1.0f, 2.4f, 0.0f};
  s.lights[0].spot.direction = {0.0f, -1.0f, 0.0f};
  s.lights[0].spot.intensity = glm::vec3(6.0f);
  s.lights[0].spot.cos_inner = std::cos(glm::radians(30.0f));
  s.lights[0].spot.cos_outer = std::cos(glm::radians(45.0f));
  return s;
}

double luminance_sum(const image& a) {
  double sum = 0.0;
  for (const glm::vec4& texel : a.texels) sum += luminance(glm::dvec3(texel));
  return sum;
}

}  // namespace

TEST_CASE("flux energy: the indirect light follows the light's intensity and the albedos (one albedo at the VPL, one at the receiver)") {
  const scene base = room_scene(false);
  lightwave_settings settings = small_lightwave_settings("lightwave-unshadowed");
  lightwave_pipeline reference(test_shaders(), base, settings);
  const double indirect = luminance_sum(reference.render().indirect);
  REQUIRE(indirect > 0.0);
  scene brighter = base;
  brighter.lights[0].spot.intensity *= 2.0f;
  lightwave_pipeline doubled(test_shaders(), brighter, settings);
  CHECK(luminance_sum(doubled.render().indirect) == doctest::Approx(2.0 * indirect).epsilon(1e-3));
  lightwave_pipeline darker(test_shaders(), room_scene(false, 0.5f), settings);
  CHECK(luminance_sum(darker.render().indirect) == doctest::Approx(0.25 * indirect).epsilon(1e-3));
  // The thesis's energy does not follow the light (Eq. 4.5 has no flux): the same indirect light.
  settings.energy = lightwave_energy::thesis;
  lightwave_pipeline thesis(test_shaders(), base, settings), thesis_doubled(test_shaders(), brighter, settings);
  CHECK(luminance_sum(thesis_doubled.render().indirect) == doctest::Approx(luminance_sum(thesis.render().indirect)).epsilon(1e-6));
}

TEST_CASE("flux energy: a narrow spot aimed at a wall away from the room's centre lights the room at the one-bounce reference's level") {
  // The case: a user's room lit by --light, the spot aimed off-centre with a narrow cone.
  // Every ray of the layout meets the wall; the indirect light the image adds is within 25 % of
  // the Monte Carlo reference's (the thesis's energy is not: its VPLs float outside the room).
  scene s = room_scene(false);
  s.lights[0].spot.position = {1.5f, 1.5f, 2.0f};
  s.lights[0].spot.direction = glm::normalize(glm::vec3(-2.0f, 1.0f, -3.0f) - s.lights[0].spot.position);
  s.lights[0].spot.cos_inner = std::cos(glm::radians(8.0f));
  s.lights[0].spot.cos_outer = std::cos(glm::radians(12.0f));
  const int width = 64, height = 36;
  const one_bounce_images reference = reference_one_bounce(s, width, height, 256, 1u, 2);
  const one_bounce_images reference_direct = reference_one_bounce(s, width, height, 0, 1u, 2);
  double reference_indirect = 0.0;
  for (std::size_t i = 0; i < reference.radiance.texels.size(); ++i)
    reference_indirect += luminance(glm::dvec3(reference.radiance.texels[i]) - glm::dvec3(reference_direct.radiance.texels[i]));
  REQUIRE(reference_indirect > 0.0);
  lightwave_settings settings = small_lightwave_settings("lightwave-accurate");
  settings.width = width;
  settings.height = height;
  lightwave_pipeline flux(test_shaders(), s, settings);
  const double level = luminance_sum(flux.render().indirect) / reference_indirect;
  CHECK(flux.lit_vpl_count() == flux.vpl_count());  // every ray meets the wall inside the cone
  MESSAGE("flux energy: indirect level " << level << " of the reference's");
  CHECK(level > 0.75);
  CHECK(level < 1.25);
  settings.energy = lightwave_energy::thesis;
  lightwave_pipeline thesis(test_shaders(), s, settings);
  const double thesis_level = luminance_sum(thesis.render().indirect) / reference_indirect;
  MESSAGE("thesis energy: indirect level " << thesis_level << " of the reference's");
  CHECK(std::fabs(thesis_level - 1.0) > 0.25);
}

TEST_CASE("flux energy, accurate shadows: in an empty room nothing is shadowed, whatever the seed or the number of maps") {
  const scene s = room_scene(false);
  for (int maps : {1, 20})
    for (std::uint32_t seed : {0u, 1u, 2u, 3u}) {
      lightwave_settings settings = square("lightwave-accurate");
      settings.accurate_maps = maps;
      settings.seed = seed;
      lightwave_pipeline pipeline(test_shaders(), s, settings);
      const lightwave_frame frame = pipeline.render();
      float lowest = 1.0f;
      for (const glm::vec4& factor : frame.indirect_shadow.texels) lowest = std::min(lowest, factor.r);
      CAPTURE(maps);
      CAPTURE(seed);
      CHECK(pipeline.shadow_casters().size() == static_cast<std::size_t>(maps));
      CHECK(lowest >= 0.99f);
    }
}

TEST_CASE("flux energy, accurate shadows: a panel shadows the wall behind it from the lit floor, not the wall beside it") {
  scene looking = room_scene(true);  // looking at the left wall from between it and the panel
  looking.view.position = {-1.5f, 2.2f, 2.9f};
  looking.view.target = {-2.0f, 0.4f, 0.0f};
  looking.view.vertical_fov_degrees = 70.0f;
  lightwave_settings settings = square("lightwave-accurate");
  lightwave_pipeline pipeline(test_shaders(), looking, settings);
  const lightwave_frame frame = pipeline.render();
  // The wall x = -2: behind the panel (low, |z| < 0.5) and beside it (z < -2.2), at y = 0.3.
  const glm::mat4 view_projection = glm::perspective(glm::radians(looking.view.vertical_fov_degrees), 1.0f, looking.view.near_plane, looking.view.far_plane) *
                                    glm::lookAt(looking.view.position, looking.view.target, looking.view.up);
  const auto factor_at = [&](float y, float z) {
    const glm::vec4 clip = view_projection * glm::vec4(-1.999f, y, z, 1.0f);
    const int px = static_cast<int>((clip.x / clip.w * 0.5f + 0.5f) * static_cast<float>(frame.radiance.width));
    const int py = static_cast<int>((clip.y / clip.w * 0.5f + 0.5f) * static_cast<float>(frame.radiance.height));
    REQUIRE(px >= 0);
    REQUIRE(py >= 0);
    REQUIRE(px < frame.radiance.width);
    REQUIRE(py < frame.radiance.height);
    return frame.indirect_shadow.at(px, py).r;
  };
  double behind = 0.0, beside = 0.0;
  for (float z : {-0.4f, -0.2f, 0.0f, 0.2f, 0.4f}) behind += factor_at(0.3f, z) / 5.0;
  for (float z : {-2.6f, -2.5f, -2.4f, -2.3f}) beside += factor_at(0.3f, z) / 4.0;
  MESSAGE("flux energy: mean indirect shadow factor on the wall behind the panel " << behind << ", beside it " << beside);
  CHECK(behind < 0.8);
  CHECK(beside > behind + 0.15);
}

TEST_CASE("flux energy, accurate shadows: 1, 5 and 20 maps are never further from the one-bounce reference than none, the spot overhead or in a corner") {
  // The failure: one map for all the VPLs of a room lit into a corner shadowed a wall it
  // does not hide and was further from the reference than no map. Each map count against none,
  // RMSE of linear radiance over every pixel; the tolerance (1e-4 relative) only absorbs the
  // reference's noise between two nearly equal images.
  for (bool corner : {false, true}) {
    scene s = room_scene(true);
    if (corner) {
      s.lights[0].spot.position = {1.8f, 2.3f, 2.7f};
      s.lights[0].spot.direction = glm::normalize(glm::vec3(-1.8f, 0.3f, -2.7f) - s.lights[0].spot.position);
    }
    const int width = 64, height = 36;
    const one_bounce_images reference = reference_one_bounce(s, width, height, 256, 1u, 2);
    const auto rmse_of = [&](int maps) {
      lightwave_settings settings = small_lightwave_settings(maps == 0 ? "lightwave-unshadowed" : "lightwave-accurate");
      settings.width = width;
      settings.height = height;
      settings.accurate_maps = std::max(maps, 1);
      lightwave_pipeline pipeline(test_shaders(), s, settings);
      const image radiance = pipeline.render().radiance;
      double sum = 0.0;
      for (std::size_t i = 0; i < radiance.texels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
          const double d = static_cast<double>(radiance.texels[i][c]) - static_cast<double>(reference.radiance.texels[i][c]);
          sum += d * d;
        }
      return std::sqrt(sum / (3.0 * static_cast<double>(radiance.texels.size())));
    };
    const double none = rmse_of(0);
    for (int maps : {1, 5, 20}) {
      const double with_maps = rmse_of(maps);
      CAPTURE(corner);
      CAPTURE(maps);
      MESSAGE((corner ? "corner" : "overhead") << ": " << maps << " maps RMSE " << with_maps << ", none " << none);
      CHECK(with_maps <= none * (1.0 + 1e-4));
    }
  }
}

TEST_CASE("accurate shadows, importance: the image does not depend on the seed, in either energy") {
  const scene boxes = make_boxes_scene();
  for (lightwave_energy energy : {lightwave_energy::flux, lightwave_energy::thesis}) {
    std::vector<std::vector<std::uint8_t>> images;
    for (std::uint32_t seed : {0u, 1u, 2u}) {
      lightwave_settings settings = small_lightwave_settings("lightwave-accurate");
      settings.energy = energy;
      settings.seed = seed;
      lightwave_pipeline pipeline(test_shaders(), boxes, settings);
      images.push_back(to_srgb8(pipeline.render().radiance));
      REQUIRE(pipeline.shadow_casters().size() == 20u);
    }
    CHECK(images[1] == images[0]);
    CHECK(images[2] == images[0]);
  }
  // The thesis's variant draws its VPLs with the seed.
  lightwave_settings thesis = small_lightwave_settings("lightwave-accurate");
  thesis.shadow_variant = lightwave_shadow_variant::thesis;
  lightwave_pipeline first(test_shaders(), boxes, thesis);
  thesis.seed = 2;
  lightwave_pipeline second(test_shaders(), boxes, thesis);
  first.render();
  second.render();
  CHECK(first.shadow_casters().front().vpl != second.shadow_casters().front().vpl);
}

TEST_CASE("subdivide_long_edges: no edge over the bound, the area and the faces' attributes kept, no T-junction, the source's order") {
  mesh boxes;
  add_box(boxes, glm::vec3(0.0f), glm::vec3(1.0f, 2.0f, 4.0f), 20.0f, glm::vec3(0.5f, 0.4f, 0.3f));
  add_box(boxes, glm::vec3(3.0f, 0.0f, 0.0f), glm::vec3(1.0f), 0.0f, glm::vec3(0.1f, 0.8f, 0.2f));
  const std::optional<mesh> refined = subdivide_long_edges(boxes, 0.3f, 100000);
  REQUIRE(refined);
  double area = 0.0, source_area = 0.0;
  for (std::size_t t = 0; t < boxes.indices.size(); t += 3)
    source_area += 0.5 * glm::length(glm::cross(boxes.vertices[boxes.indices[t + 1]].position - boxes.vertices[boxes.indices[t]].position,
                                                boxes.vertices[boxes.indices[t + 2]].position - boxes.vertices[boxes.indices[t]].position));
  // Closed by position: every edge (as a pair of positions) is used once in each direction.
  std::map<std::pair<std::array<float, 3>, std::array<float, 3>>, int> directed;
  const auto key = [](const glm::vec3& p) { return std::array<float, 3>{p.x, p.y, p.z}; };
  for (std::size_t t = 0; t < refined->indices.size(); t += 3) {
    const vertex* v[3] = {&refined->vertices[refined->indices[t]], &refined->vertices[refined->indices[t + 1]], &refined->vertices[refined->indices[t + 2]]};
    const glm::vec3 cross = glm::cross(v[1]->position - v[0]->position, v[2]->position - v[0]->position);
    area += 0.5 * glm::length(cross);
    for (int k = 0; k < 3; ++k) {
      REQUIRE(glm::length(v[k]->position - v[(k + 1) % 3]->position) <= 0.3f);
      REQUIRE(glm::dot(cross, v[0]->normal) > 0.0f);    // winding and flat face normals kept
      REQUIRE(v[k]->normal == v[0]->normal);             // a box face stays flat: no normals welded across edges
      REQUIRE(v[k]->albedo == v[0]->albedo);
      ++directed[{key(v[k]->position), key(v[(k + 1) % 3]->position)}];
    }
  }
  for (const auto& [edge, count] : directed) {
    REQUIRE(count == 1);
    REQUIRE(directed.count({edge.second, edge.first}) == 1);  // a T-junction would leave an edge unmatched
  }
  CHECK(area == doctest::Approx(source_area).epsilon(1e-5));
  // The first box's triangles come first (a renderer's early depth test sees the source's order).
  CHECK(refined->vertices[refined->indices.front()].albedo == glm::vec3(0.5f, 0.4f, 0.3f));
  CHECK(refined->vertices[refined->indices.back()].albedo == glm::vec3(0.1f, 0.8f, 0.2f));
  // Over the budget: nothing; an already fine mesh: itself.
  CHECK(!subdivide_long_edges(boxes, 0.3f, 1000));
  const std::optional<mesh> same = subdivide_long_edges(boxes, 10.0f, 1000);
  REQUIRE(same);
  CHECK(same->triangle_count() == boxes.triangle_count());
}

TEST_CASE("Light Wave's shadowed main pass after its depth pre-pass: no pixel lost, and a cut-out is not drawn, lit or cast as a shadow") {
  // The shadowed modes draw a depth pre-pass and then shade with the depth test EQUAL and no alpha
  // test; the shadow maps of a scene without cut-outs are drawn without the alpha test. (1) Every
  // pixel of the accurate image is at least the direct-only image's (which has no pre-pass): a
  // position that differed between the two programs would leave black holes. (2) A panel under
  // the light whose MASK material cuts it out entirely changes the image by a small fraction of
  // what the same panel opaque does: it is neither drawn nor shadows the floor.
  const auto render = [](const scene& s, const char* technique) { return lightwave_pipeline(test_shaders(), s, small_lightwave_settings(technique)).render().radiance; };
  const auto with_panel = [](bool cut_out) {
    scene s = room_scene(false);
    mesh& m = s.geometry;
    const auto first = static_cast<std::uint32_t>(m.indices.size());
    add_quad(m, {0.2f, 1.2f, 0.8f}, {1.8f, 1.2f, 0.8f}, {1.8f, 1.2f, -0.8f}, {0.2f, 1.2f, -0.8f}, {0, 1, 0}, glm::vec3(0.1f, 0.8f, 0.1f));
    if (cut_out) {
      auto library = std::make_shared<material_library>();
      surface_material material;
      material.name = "cut out";
      material.alpha_mask = true;
      material.alpha_factor = 0.0f;
      library->materials.push_back(material);
      m.materials = library;
      m.material_ranges.push_back({first, 6, 0});
    }
    return s;
  };
  const scene empty = room_scene(false), cut = with_panel(true), opaque = with_panel(false);
  REQUIRE(has_alpha_cutouts(cut.geometry));
  REQUIRE_FALSE(has_alpha_cutouts(opaque.geometry));
  for (const scene* s : {&empty, &cut}) {
    const image direct = render(*s, "lightwave-direct"), accurate = render(*s, "lightwave-accurate");
    int darker = 0;
    for (std::size_t i = 0; i < direct.texels.size(); ++i)
      for (int c = 0; c < 3; ++c)
        if (accurate.texels[i][c] < direct.texels[i][c] - 1e-6f) ++darker;
    CAPTURE(s->name);
    CHECK(darker == 0);
  }
  const auto difference = [](const image& a, const image& b) {
    double sum = 0.0;
    for (std::size_t i = 0; i < a.texels.size(); ++i) sum += glm::length(glm::dvec3(a.texels[i]) - glm::dvec3(b.texels[i]));
    return sum;
  };
  for (const char* technique : {"lightwave-direct", "lightwave-unshadowed", "lightwave-accurate"}) {
    const image base = render(empty, technique);
    const double cut_change = difference(render(cut, technique), base), opaque_change = difference(render(opaque, technique), base);
    CAPTURE(technique);
    CAPTURE(cut_change);
    CAPTURE(opaque_change);
    CHECK(opaque_change > 0.0);
    CHECK(cut_change <= 0.02 * opaque_change);
  }
}

namespace {

// The boxes with a second spot: another place, another axis, another colour.
scene two_spot_boxes() {
  scene s = make_boxes_scene();
  scene_light second = s.lights.at(0);
  second.spot.position += glm::vec3(0.6f, -0.2f, 0.4f);
  second.spot.direction = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.3f));
  second.spot.intensity *= glm::vec3(0.4f, 0.9f, 1.3f);
  s.lights.push_back(second);
  return s;
}

scene only_light(const scene& s, std::size_t k) {
  scene alone = s;
  alone.lights = {s.lights.at(k)};
  return alone;
}

}  // namespace

TEST_CASE("Light Wave, two spots: every technique's image and indirect light, both energies, are the sums of the two one-light images") {
  const scene both = two_spot_boxes(), first = only_light(both, 0), second = only_light(both, 1);
  for (lightwave_energy energy : {lightwave_energy::flux, lightwave_energy::thesis})
    for (const lightwave_technique& technique : lightwave_techniques()) {
      lightwave_settings settings = small_lightwave_settings(technique.name);
      settings.energy = energy;
      CAPTURE(technique.name);
      CAPTURE(static_cast<int>(energy));
      const lightwave_frame a = lightwave_pipeline(test_shaders(), first, settings).render();
      const lightwave_frame b = lightwave_pipeline(test_shaders(), second, settings).render();
      lightwave_pipeline pipeline(test_shaders(), both, settings);
      REQUIRE(pipeline.light_count() == 2);
      const lightwave_frame sum = pipeline.render();
      double lit_a = 0.0, lit_b = 0.0, indirect_b = 0.0;
      for (std::size_t i = 0; i < sum.radiance.texels.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
          // rgba32f targets: one float addition per channel in the blend.
          const float radiance = a.radiance.texels[i][c] + b.radiance.texels[i][c];
          const float indirect = a.indirect.texels[i][c] + b.indirect.texels[i][c];
          REQUIRE(sum.radiance.texels[i][c] == doctest::Approx(radiance).epsilon(1e-5).scale(1e-6));
          REQUIRE(sum.indirect.texels[i][c] == doctest::Approx(indirect).epsilon(1e-5).scale(1e-6));
        }
        // The shadow factor is a ratio, not a light: the first light's.
        REQUIRE(sum.indirect_shadow.texels[i].r == a.indirect_shadow.texels[i].r);
        lit_a += a.radiance.texels[i].r;
        lit_b += b.radiance.texels[i].b;
        indirect_b += b.indirect.texels[i].g;
      }
      // Both lights reach the camera's view (a sum with one light dropped would fail above), and
      // the VPL techniques' second light brings indirect light of its own.
      CHECK(lit_a > 0.0);
      CHECK(lit_b > 0.0);
      if (technique.mode >= lightwave_mode::unshadowed) CHECK(indirect_b > 0.0);
    }
}

TEST_CASE("Light Wave, two spots: passes named by light; moving light 1 rebuilds light 1 alone and gives the image of a new pipeline") {
  const scene both = two_spot_boxes();
  const lightwave_settings settings = small_lightwave_settings("lightwave-accurate");
  lightwave_pipeline pipeline(test_shaders(), both, settings);
  pipeline.draw_changed();
  std::vector<std::string> names;
  for (const pass_time& pass : pipeline.collect_pass_times()) names.push_back(pass.pass);
  CHECK(names == std::vector<std::string>{"light 0: VPLs", "light 0: shadow maps", "light 0: indirect buffer", "light 0: main pass", "light 1: VPLs",
                                          "light 1: shadow maps", "light 1: indirect buffer", "light 1: main pass"});
  CHECK(pipeline.rebuilds() == 1);
  scene moved = both;
  moved.lights[1].spot.position.x -= 0.5f;
  pipeline.set_light(1, moved.lights[1]);
  pipeline.draw_changed();
  CHECK(pipeline.rebuilds() == 1);  // light 0's VPLs and shadow maps stay
  names.clear();
  for (const pass_time& pass : pipeline.collect_pass_times()) names.push_back(pass.pass);
  // Light 0's main pass is drawn again (the image starts from it), from its cached VPLs and maps.
  CHECK(names == std::vector<std::string>{"light 0: indirect buffer", "light 0: main pass", "light 1: VPLs", "light 1: shadow maps",
                                          "light 1: indirect buffer", "light 1: main pass"});
  CHECK(pipeline.current_lights().at(1).spot.position.x == doctest::Approx(moved.lights[1].spot.position.x));
  const image kept = pipeline.output().read_image();
  const image fresh = lightwave_pipeline(test_shaders(), moved, settings).render().radiance;
  REQUIRE(kept.texels.size() == fresh.texels.size());
  for (std::size_t i = 0; i < kept.texels.size(); ++i)
    for (int c = 0; c < 3; ++c) REQUIRE(kept.texels[i][c] == doctest::Approx(fresh.texels[i][c]).epsilon(1e-6).scale(1e-7));
  // Light 2 does not exist; light 1 cannot become a point light in place; no light at all is refused.
  CHECK_THROWS_WITH_AS(pipeline.set_light(2, moved.lights[1]), doctest::Contains("no light 2"), vplkit::error);
  scene_light point = moved.lights[1];
  point.kind = light_kind::point;
  CHECK_THROWS_WITH_AS(pipeline.set_light(1, point), doctest::Contains("light 1 is a spot light and cannot become a point one"), vplkit::error);
  scene dark = both;
  dark.lights.clear();
  CHECK_THROWS_WITH_AS(lightwave_pipeline(test_shaders(), dark, settings), doctest::Contains("has none"), vplkit::error);
}

TEST_CASE("Light Wave, two spots: a setting applied in place reaches both lights: the image of a fresh pipeline with it") {
  const scene both = two_spot_boxes();
  const lightwave_settings settings = small_lightwave_settings("lightwave-accurate");
  lightwave_pipeline pipeline(test_shaders(), both, settings);
  pipeline.draw();
  // The clamp distance: in place, the shadow maps redrawn and the same VPLs summed again, per light.
  std::unique_ptr<technique_settings> live = family_of("lightwave-accurate").make_settings("lightwave-accurate");
  auto& typed = dynamic_cast<described_settings<lightwave_settings, lightwave_technique>&>(*live);
  typed.value() = settings;
  typed.value().irradiance.min_distance = 0.4f;
  REQUIRE(pipeline.apply_settings(*live));
  pipeline.draw_changed();
  const image applied = pipeline.output().read_image();
  const image fresh = lightwave_pipeline(test_shaders(), both, typed.value()).render().radiance;
  const image before = lightwave_pipeline(test_shaders(), both, settings).render().radiance;
  std::size_t changed = 0;
  for (std::size_t i = 0; i < applied.texels.size(); ++i) {
    for (int c = 0; c < 3; ++c) REQUIRE(applied.texels[i][c] == doctest::Approx(fresh.texels[i][c]).epsilon(1e-6).scale(1e-7));
    changed += std::abs(fresh.texels[i].r - before.texels[i].r) > 1e-4f * (before.texels[i].r + 1e-3f);
  }
  CHECK(changed > 0);  // the setting changes the image: the comparison above sees it
}
