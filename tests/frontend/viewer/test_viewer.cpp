// frontend/viewer/viewer.hpp in a real GLFW window (run under xvfb-run by ctest): scripted frames
// change when the camera, the light or the object moves, and each move redraws only what it
// invalidates; the panel covers its own rectangle and nothing else; every technique and each of
// its layers can be shown; screenshots are written whole or not at all.
#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include "frontend/core/error.hpp"
#include "frontend/window/window_context.hpp"
#include "frontend/image/image.hpp"
#include "frontend/image/image_files.hpp"
#include "frontend/viewer/pose_controls.hpp"
#include "frontend/viewer/viewer.hpp"
#include "tests/gl_test_run.hpp"

using namespace vplkit;

namespace {

constexpr int side = 96;

window_context& window() {
  static window_context context(side, side, "vplkit viewer test");
  return context;
}

const shader_library& shaders() {
  static const shader_library library(default_shader_dir());
  return library;
}

viewer_options small_setup(const std::string& technique) {
  viewer_options options;
  options.technique = technique;
  for (const technique_family& family : technique_families()) {
    viewer_family& state = options.scenes.families[family.name];
    state.settings = family.make_settings(family.has(technique) ? technique : family.techniques.front().name);
    REQUIRE(state.settings->set("size", std::to_string(side)).empty());
    if (family.reads_scene()) state.source = built_in_scene(family.default_scene);
  }
  REQUIRE(options.scenes.families.at("rsm").settings->set("rsm-size", "64").empty());
  REQUIRE(options.scenes.families.at("lightwave").settings->set("shadow-map-scale", "1").empty());
  REQUIRE(options.scenes.families.at("final-gather").settings->set("face-size", "32").empty());
  options.screenshot = std::filesystem::temp_directory_path() / "vplkit-viewer-test" / "shot.png";
  return options;
}

// The share of pixels whose largest channel moved by more than `codes` 8-bit steps.
double changed_share(const window_pixels& a, const window_pixels& b, int codes = 8) {
  REQUIRE(a.rgba8.size() == b.rgba8.size());
  std::size_t changed = 0;
  for (std::size_t i = 0; i < a.rgba8.size(); i += 4) {
    int largest = 0;
    for (std::size_t c = 0; c < 3; ++c) largest = std::max(largest, std::abs(int(a.rgba8[i + c]) - int(b.rgba8[i + c])));
    changed += largest > codes;
  }
  return static_cast<double>(changed) / static_cast<double>(a.rgba8.size() / 4);
}

window_pixels shown_frame(viewer& app) {
  app.frame();
  const window_pixels pixels = app.read_window();
  window().swap_and_poll();
  return pixels;
}

// The frame that moves brought about, redrawing only what they invalidated, is bit for bit the
// frame of a new pipeline built at the final pose (no stale uniform or buffer).
void check_same_as_new_pipeline(viewer& app, viewer_scenes scenes) {
  app.view().store_pose(scenes);
  const std::unique_ptr<technique_view> fresh = make_technique_view(shaders(), scenes, app.technique());
  fresh->draw();
  for (view_layer layer : fresh->layers()) {
    if (layer == view_layer::visibility_difference) continue;  // built on demand from the same pipeline
    CAPTURE(describe(layer));
    const image moved = app.view().display(layer).image->read_image();
    const image rebuilt = fresh->display(layer).image->read_image();
    REQUIRE(moved.same_size(rebuilt));
    std::size_t different = 0;
    for (std::size_t i = 0; i < moved.texels.size(); ++i) different += moved.texels[i] != rebuilt.texels[i];
    CHECK(different == 0);
  }
}

}  // namespace

TEST_CASE("RSM: a camera move redraws the G-buffer to the post filter, a light move the RSM too, no move nothing") {
  viewer app(window(), shaders(), small_setup("rsm-alg6"));
  app.show_panel(false);
  const window_pixels first = shown_frame(app);
  CHECK(app.view().draw_counts() == "RSM 1, G-buffer to post filter 1");
  const window_pixels still = shown_frame(app);
  CHECK(app.view().draw_counts() == "RSM 1, G-buffer to post filter 1");
  CHECK(changed_share(first, still, 0) == 0.0);

  app.move_camera(orbit(app.view().camera_pose(), 0.35f, 0.1f));
  const window_pixels orbited = shown_frame(app);
  CHECK(app.message().empty());
  CHECK(app.view().draw_counts() == "RSM 1, G-buffer to post filter 2");
  CHECK(changed_share(first, orbited) > 0.2);

  // Tilt the spot light: the lit spot on the floor and its bounce move.
  app.move_light(orbit(app.view().light_pose(), 0.0f, -0.4f));
  const window_pixels tilted = shown_frame(app);
  CHECK(app.view().draw_counts() == "RSM 2, G-buffer to post filter 3");
  CHECK(changed_share(orbited, tilted) > 0.05);
  app.move_camera(dolly(app.view().camera_pose(), 0.8f));
  shown_frame(app);
  CHECK(app.view().draw_counts() == "RSM 2, G-buffer to post filter 4");
  check_same_as_new_pipeline(app, small_setup("rsm-alg6").scenes);

  // A refused move changes nothing.
  const pose camera_before = app.view().camera_pose();
  app.move_camera({camera_before.position, camera_before.position});
  CHECK(app.message().find("same point") != std::string::npos);
  CHECK(app.view().camera_pose().target == camera_before.target);
}

TEST_CASE("Light Wave: VPLs and shadow maps are rebuilt when the light moves; a camera move rebuilds only the maps of the importance variant with the thesis energy") {
  viewer_options thesis = small_setup("lightwave-accurate");
  REQUIRE(thesis.scenes.families.at("lightwave").settings->set("shadow-variant", "thesis").empty());
  thesis.panel = false;
  {
  viewer app(window(), shaders(), thesis);
  const window_pixels first = shown_frame(app);
  CHECK(app.view().draw_counts() == "VPLs and shadow maps 1, main pass 1");
  shown_frame(app);
  CHECK(app.view().draw_counts() == "VPLs and shadow maps 1, main pass 1");
  app.move_camera(orbit(app.view().camera_pose(), 0.3f, 0.0f));
  const window_pixels orbited = shown_frame(app);
  CHECK(app.view().draw_counts() == "VPLs and shadow maps 1, main pass 2");
  CHECK(changed_share(first, orbited) > 0.1);
  app.move_light(fly(app.view().light_pose(), {0.4f, 0.0f, 0.0f}));
  const window_pixels moved = shown_frame(app);
  CHECK(app.view().draw_counts() == "VPLs and shadow maps 2, main pass 3");
  CHECK(changed_share(orbited, moved) > 0.05);
  check_same_as_new_pipeline(app, thesis.scenes);
  }  // one viewer per window at a time

  // The default shadows (importance, flux energy) are chosen for the whole scene: a camera move
  // redraws the main pass alone. With the thesis energy they follow the camera: both again.
  for (const char* energy : {"flux", "thesis"}) {
    viewer_options importance = small_setup("lightwave-accurate");
    REQUIRE(importance.scenes.families.at("lightwave").settings->set("vpl-energy", energy).empty());
    importance.panel = false;
    viewer aimed(window(), shaders(), importance);
    shown_frame(aimed);
    aimed.move_camera(orbit(aimed.view().camera_pose(), 0.3f, 0.0f));
    shown_frame(aimed);
    CAPTURE(energy);
    CHECK(aimed.view().draw_counts() == (std::string(energy) == "flux" ? "VPLs and shadow maps 1, main pass 2" : "VPLs and shadow maps 2, main pass 2"));
    check_same_as_new_pipeline(aimed, importance.scenes);
  }
}

TEST_CASE("Final gathering: an object move redraws the cube map, a camera move does not; an object in a wall is refused") {
  viewer_options setup = small_setup("finalgather-polygon");
  setup.panel = false;
  viewer app(window(), shaders(), setup);
  const window_pixels first = shown_frame(app);
  CHECK(app.view().draw_counts() == "cube map 1, G-buffer and shading 1");
  app.move_object(glm::vec3(0.3f, 0.7f, 0.0f));
  const window_pixels moved = shown_frame(app);
  CHECK(app.view().draw_counts() == "cube map 2, G-buffer and shading 2");
  CHECK(changed_share(first, moved) > 0.02);
  app.move_camera(orbit(app.view().camera_pose(), -0.3f, 0.0f));
  shown_frame(app);
  CHECK(app.view().draw_counts() == "cube map 2, G-buffer and shading 3");
  check_same_as_new_pipeline(app, setup.scenes);
  const window_pixels before_wall = shown_frame(app);
  app.move_object(glm::vec3(0.95f, 0.7f, 0.0f));  // the sphere (radius 0.25) reaches into the wall at x = 1
  const window_pixels after_wall = shown_frame(app);
  CHECK(app.message().find("intersects a wall") != std::string::npos);
  CHECK(app.view().object_position() == glm::vec3(0.3f, 0.7f, 0.0f));
  CHECK(changed_share(before_wall, after_wall, 1) == 0.0);
}

TEST_CASE("the selected light: an index the scene lacks is refused; the pose text names the file's lights, the selected one first") {
  {
    viewer_options setup = small_setup("rsm-alg6");
    // As `vplkit view --lights 2` of a file whose light 2 is the Cornell box's spot.
    setup.scenes.families.at("rsm").file_lights = std::vector<std::size_t>{2};
    viewer app(window(), shaders(), setup);
    shown_frame(app);
    REQUIRE(app.view().light_count() == 1);
    app.select_light(1);
    CHECK(app.message().find("no light 1 (it has 1)") != std::string::npos);
    CHECK(app.selected_light() == 0);
    CHECK(app.pose_arguments().find("--lights 2 --light " + format_pose(app.view().light_pose())) != std::string::npos);
  }  // one viewer per window at a time
  // Every light of the file (no --lights given): the text is --light alone, as before several lights.
  viewer app(window(), shaders(), small_setup("rsm-alg6"));
  shown_frame(app);
  CHECK(app.pose_arguments().find(" --lights") == std::string::npos);
  CHECK(app.pose_arguments().find("--light " + format_pose(app.view().light_pose())) != std::string::npos);
}

namespace {

// A viewer of `lights` in the Cornell box.
std::unique_ptr<viewer> lit_viewer(const std::string& technique, const std::vector<scene_light>& lights) {
  viewer_options setup = small_setup(technique);
  for (auto& [name, family] : setup.scenes.families)
    if (family.source) family.source->lights = lights;
  return std::make_unique<viewer>(window(), shaders(), std::move(setup));
}

}  // namespace

TEST_CASE("several lights: the selected one moves, the others stay; the pose text puts it first; no light shows the image and no light controls") {
  const scene box = built_in_scene("cornell-box");
  REQUIRE(box.lights.size() == 1);
  scene_light second = box.lights[0];
  apply_pose({glm::vec3(-0.5f, 1.8f, 0.5f), glm::vec3(0.3f, 0.0f, -0.3f)}, second, "test");
  {
    const std::unique_ptr<viewer> app = lit_viewer("rsm-alg6", {box.lights[0], second});
    app->show_panel(true);
    const window_pixels first = shown_frame(*app);
    REQUIRE(app->view().light_count() == 2);
    const pose light0 = app->view().light_pose();
    app->select_light(1);
    CHECK(app->message().empty());
    CHECK(app->selected_light() == 1);
    const pose moved = orbit(app->view().light_pose(), 0.6f, -0.3f);
    app->move_light(moved);
    const window_pixels after = shown_frame(*app);
    CHECK(changed_share(first, after) > 0.02);
    CHECK(app->view().light_pose().position == moved.position);
    app->select_light(0);
    CHECK(app->view().light_pose().position == light0.position);  // light 0 did not move
    app->select_light(1);
    CHECK(app->pose_arguments().find("--lights 1,0 --light " + format_pose(app->view().light_pose())) != std::string::npos);
    // Switching technique keeps the selection where the next scene has the light.
    app->select_technique("rsm-radial");
    CHECK(app->message().empty());
    CHECK(app->selected_light() == 1);
  }
  {
    const std::unique_ptr<viewer> dark = lit_viewer("rsm-alg6", {});
    dark->show_panel(true);
    shown_frame(*dark);
    shown_frame(*dark);
    CHECK(dark->message().empty());
    CHECK(dark->view().light_count() == 0);
    CHECK(dark->light_intensity() == 0.0f);
    CHECK(dark->pose_arguments().find("--lights none") != std::string::npos);
    CHECK(dark->pose_arguments().find("--light ") == std::string::npos);
    dark->move_light({glm::vec3(0, 1, 0), glm::vec3(0, 0, 0)});
    CHECK(dark->message().find("no light") != std::string::npos);
  }
}

TEST_CASE("the panel is drawn inside its rectangle and nowhere else, and the hidden panel shows the technique's own pixels") {
  viewer app(window(), shaders(), small_setup("rsm-radial"));
  app.show_panel(false);
  const window_pixels hidden = shown_frame(app);
  // The window shows the final image as the PNG writer encodes it.
  const std::vector<std::uint8_t> expected = to_srgb8(app.view().display(view_layer::image).image->read_image());
  REQUIRE(expected.size() == hidden.rgba8.size());
  int largest = 0;
  for (std::size_t i = 0; i < expected.size(); ++i) largest = std::max(largest, std::abs(int(expected[i]) - int(hidden.rgba8[i])));
  CHECK(largest <= 1);

  app.show_panel(true);
  shown_frame(app);  // Dear ImGui sizes an auto-resizing window in its first frame and shows it from the second
  const window_pixels shown = shown_frame(app);
  const glm::vec4 panel = app.panel_rectangle();
  CHECK(panel.z > 20.0f);
  CHECK(panel.w > 20.0f);
  // Floating over the image, the panel covers at most a quarter of it.
  CHECK(panel.z * panel.w <= 0.25f * side * side);
  CHECK(panel.z <= 0.5f * side);
  CHECK(panel.w <= 0.5f * side);
  std::size_t inside = 0, inside_changed = 0, outside_changed = 0;
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const std::size_t i = 4 * (static_cast<std::size_t>(y) * side + static_cast<std::size_t>(x));
      bool changed = false;
      for (std::size_t c = 0; c < 3; ++c) changed |= hidden.rgba8[i + c] != shown.rgba8[i + c];
      // Pixel centres within a pixel of the rectangle (rows counted from the top, as ImGui does).
      const float cx = static_cast<float>(x) + 0.5f, cy = static_cast<float>(y) + 0.5f;
      const bool in_panel = cx >= panel.x - 1.0f && cx <= panel.x + panel.z + 1.0f && cy >= panel.y - 1.0f && cy <= panel.y + panel.w + 1.0f;
      inside += in_panel;
      inside_changed += in_panel && changed;
      outside_changed += !in_panel && changed;
    }
  CHECK(outside_changed == 0);
  CHECK(static_cast<double>(inside_changed) > 0.5 * static_cast<double>(inside));
}

TEST_CASE("the docked panel sits beside the image, leaves every pixel of it as the hidden panel does, and shows the full technique names") {
  viewer app(window(), shaders(), small_setup("rsm-radial"));
  app.show_panel(false);
  const window_pixels hidden = shown_frame(app);
  app.show_panel(true);
  app.dock_panel(true);
  // The window widens by the panel's column once the window system has resized it.
  for (int wait = 0; wait < 200 && window().framebuffer_size().first != side + docked_panel_width; ++wait) shown_frame(app);
  REQUIRE(window().framebuffer_size().first == side + docked_panel_width);
  shown_frame(app);
  const window_pixels docked = shown_frame(app);
  CHECK(app.image_rectangle() == glm::vec4(0.0f, 0.0f, side, side));
  const glm::vec4 panel = app.panel_rectangle();
  CHECK(panel.x == doctest::Approx(side));
  CHECK(panel.z == doctest::Approx(docked_panel_width));
  CHECK(app.technique_names_fit());
  // The image beside the panel is the hidden-panel image, pixel for pixel.
  std::size_t different = 0;
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x)
      for (std::size_t c = 0; c < 3; ++c)
        different += hidden.rgba8[4 * (static_cast<std::size_t>(y) * side + static_cast<std::size_t>(x)) + c] !=
                     docked.rgba8[4 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(docked.width) + static_cast<std::size_t>(x)) + c];
  CHECK(different == 0);
  app.dock_panel(false);
  for (int wait = 0; wait < 200 && window().framebuffer_size().first != side; ++wait) shown_frame(app);
  CHECK(window().framebuffer_size().first == side);
}

TEST_CASE("every technique and each of its layers can be shown") {
  viewer app(window(), shaders(), small_setup("direct"));
  app.show_panel(false);
  for (const char* technique : {"direct", "rsm-original", "rsm-radial", "rsm-alg2", "rsm-alg3", "rsm-alg6", "lightwave-direct", "lightwave-faked",
                                       "lightwave-unshadowed", "lightwave-accurate", "lightwave-integrated", "finalgather-polygon", "finalgather-point",
                                       "envmap"}) {
    CAPTURE(technique);
    app.select_technique(technique);
    REQUIRE(app.message().empty());
    CHECK(app.technique() == technique);
    for (view_layer layer : app.view().layers()) {
      CAPTURE(describe(layer));
      app.select_layer(layer);
      const window_pixels pixels = shown_frame(app);
      CHECK(app.message().empty());
      // Every layer shows something: light, or (shadow factor) a shadow somewhere.
      const bool lit = std::any_of(pixels.rgba8.begin(), pixels.rgba8.end(), [](std::uint8_t v) { return v > 16; });
      CHECK(lit);
    }
  }
  // A layer the technique lacks is refused.
  app.select_layer(view_layer::indirect_shadow);
  CHECK(app.message().find("has no layer") != std::string::npos);
  CHECK(app.layer() != view_layer::indirect_shadow);
}

TEST_CASE("a screenshot writes the window PNG and the indirect PFM, or nothing") {
  viewer app(window(), shaders(), small_setup("rsm-alg6"));
  app.show_panel(false);
  app.frame();
  const std::filesystem::path folder = std::filesystem::temp_directory_path() / "vplkit-viewer-test";
  std::filesystem::remove_all(folder);
  const std::vector<std::filesystem::path> written = app.save_screenshot(folder / "shot.png");
  REQUIRE(written.size() == 2);
  const image png = read_image_file(written[0]);
  CHECK(png.width == side);
  const image pfm = read_image_file(written[1]);
  const image indirect = app.view().read_indirect();
  REQUIRE(pfm.same_size(indirect));
  CHECK(std::equal(pfm.texels.begin(), pfm.texels.end(), indirect.texels.begin()));
  CHECK_THROWS_WITH_AS(app.save_screenshot(folder / "shot.jpg"), doctest::Contains("must end in .png"), error);
  CHECK_FALSE(std::filesystem::exists(folder / "shot-indirect.pfm.tmp"));
  window().swap_and_poll();
  std::filesystem::remove_all(folder);
}

// Live settings (issue 40): a slider that only feeds uniforms is applied to the running pipeline:
// no program is linked, the next frame redraws, and the window shows what a viewer built with the
// new settings shows; a setting that changes a define builds a new view. The frame times are
// printed (docs/cli.md, "Live settings", records them; nothing is asserted about them): a still
// frame, the frame after a uniform-only slider move (between `slider_value` and the default), the
// frame after a define or size change (between `rebuild_values`).
void check_live_slider(const std::string& technique, const std::string& slider, const std::string& slider_value, const std::string& rebuild,
                       const std::pair<std::string, std::string>& rebuild_values) {
  CAPTURE(technique);
  const auto timed_frame = [](viewer& app, window_pixels& pixels) {
    const auto start = std::chrono::steady_clock::now();
    app.frame();
    pixels = app.read_window();  // waits for the frame's GL work
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    window().swap_and_poll();
    return ms;
  };
  const auto settings_of = [&] { return small_setup(technique).scenes.of(technique).settings->clone(); };
  const std::string slider_default = settings_of()->get(slider);
  REQUIRE(slider_default != slider_value);
  viewer app(window(), shaders(), small_setup(technique));
  app.show_panel(false);
  window_pixels first, pixels, moved;
  timed_frame(app, first);
  const std::string counts_before = app.view().draw_counts();
  double still_ms = 0.0, slider_ms = 0.0, rebuild_ms = 0.0;
  constexpr int rounds = 6;
  for (int round = 0; round < rounds; ++round) {
    still_ms += timed_frame(app, pixels) / rounds;
    std::unique_ptr<technique_settings> edited = settings_of();
    REQUIRE(edited->set(slider, round % 2 ? slider_default : slider_value).empty());
    const std::uint64_t links = linked_program_count();
    app.set_settings(*edited);
    CHECK(app.message().empty());
    slider_ms += timed_frame(app, moved) / rounds;
    CHECK(linked_program_count() == links);
  }
  // The last move (round 5: the default) shows the first frame's pixels again; that the other
  // value changes the image is checked below.
  CHECK(changed_share(first, moved, 0) == 0.0);
  CHECK(app.view().draw_counts() != counts_before);  // the moves redrew
  {
    std::unique_ptr<technique_settings> edited = settings_of();
    REQUIRE(edited->set(slider, slider_value).empty());
    app.set_settings(*edited);
    window_pixels changed;
    timed_frame(app, changed);
    CHECK(changed_share(first, changed, 0) > 0.0);
    // The window is what a viewer built with the other value shows, bit for bit.
    viewer_options options = small_setup(technique);
    options.scenes.of(technique).settings = edited->clone();
    check_same_as_new_pipeline(app, options.scenes);
  }
  for (int round = 0; round < rounds; ++round) {
    std::unique_ptr<technique_settings> edited = settings_of();
    REQUIRE(edited->set(rebuild, round % 2 ? rebuild_values.second : rebuild_values.first).empty());
    const std::uint64_t links = linked_program_count();
    app.set_settings(*edited);
    CHECK(app.message().empty());
    rebuild_ms += timed_frame(app, moved) / rounds;
    CHECK(linked_program_count() > links);  // a new pipeline: new programs
  }
  MESSAGE(technique << " at " << side << "x" << side << ", mean of " << rounds << " frames: still " << still_ms << " ms, slider (" << slider
          << ", in place) " << slider_ms << " ms, " << rebuild << " change (new pipeline) " << rebuild_ms << " ms");
}

TEST_CASE("live settings: a uniform-only slider move redraws the next frame without linking a program") {
  SUBCASE("rsm-alg6 (RSM 64^2): radius") { check_live_slider("rsm-alg6", "radius", "0.3", "slots", {"4", "8"}); }
  // min-distance: the receivers' sums, the shadow maps (at 1 x the screen) and the main pass
  // redrawn.
  SUBCASE("lightwave-accurate: min-distance") {
    check_live_slider("lightwave-accurate", "min-distance", "0.3", "shadow-variant", {"thesis", "importance"});
  }
  // integrated-steps: the main pass only.
  SUBCASE("lightwave-integrated: integrated-steps") {
    check_live_slider("lightwave-integrated", "integrated-steps", "2", "integrated-maps", {"3", "5"});
  }
  // min-distance: the cube map (faces of 32^2) and the view redrawn (1.5: a clamp that shows, on
  // the object's top and the walls' upper parts).
  SUBCASE("finalgather-polygon: min-distance") {
    check_live_slider("finalgather-polygon", "min-distance", "1.5", "cube-resolution", {"2", "4"});
  }
}

int main(int argc, char** argv) { return vplkit::testing::run_tests_then_check_gl_errors(argc, argv); }
