// The viewer's live settings (issue 40), headless through its technique_view: a setting that only
// changes uniforms is applied in place (pipeline::apply_settings): no program is linked, and the
// next frame is the image a fresh pipeline with the new settings draws, bit for bit; a setting
// that changes a define or a buffer's size is refused in place (the viewer builds a new view).
#include <doctest/doctest.h>

#include <vplkit/gl/program.hpp>

#include "frontend/image/image.hpp"
#include "frontend/scene/scene.hpp"
#include "frontend/techniques/registry.hpp"
#include "frontend/viewer/technique_view.hpp"
#include <vplkit/parity/parity.hpp>
#include "tests/gl_test_helpers.hpp"

using namespace vplkit;

namespace {

// The test binary's headless context and shader library (made on first use).
const shader_library& shaders() { return parity::test_shaders(); }

using setting_values = std::vector<std::pair<std::string, std::string>>;

// The viewer's state for `technique` alone: its family's settings with `base` set, over the
// family's default scene (none for final gathering, which draws its own room).
viewer_scenes scenes_for(const std::string& technique, const setting_values& base) {
  const technique_family& family = family_of(technique);
  viewer_scenes scenes;
  viewer_family& state = scenes.families[family.name];
  state.settings = family.make_settings(technique);
  for (const auto& [name, value] : base) REQUIRE(state.settings->set(name, value).empty());
  REQUIRE(state.settings->validate().empty());
  if (family.reads_scene()) state.source = built_in_scene(family.default_scene);
  return scenes;
}

viewer_scenes rsm_scenes(const std::string& technique) { return scenes_for(technique, {{"size", "48"}, {"rsm-size", "64"}}); }

// What a fresh pipeline with `settings` draws first: its final image and its indirect light.
std::pair<image, image> fresh_frame(const viewer_scenes& scenes, const technique_settings& settings) {
  const viewer_family& family = scenes.of(settings.technique());
  std::unique_ptr<pipeline> fresh = family_of(settings.technique()).make_pipeline(shaders(), family.source ? &*family.source : nullptr, settings);
  fresh->draw_changed();
  return {fresh->output().read_image(), fresh->indirect_output().read_image()};
}

using vplkit::testing::different_texels;

void require_same(const image& a, const image& b, const char* what) {
  INFO(what);
  CHECK(different_texels(a, b) == 0);
}

// Each of `changes` (applied one after the other) is taken in place: no program is linked, the
// next frame redraws, and it is the fresh pipeline's, bit for bit (final image and indirect
// light); and the change shows (the final image differs from the previous frame's), so that a
// setting the pipeline ignored in place would fail here rather than match an unchanged image.
void check_applied_in_place(const std::string& technique, const setting_values& base, const setting_values& changes) {
  CAPTURE(technique);
  viewer_scenes scenes = scenes_for(technique, base);
  technique_view view(shaders(), scenes, technique);
  REQUIRE(view.draw());
  CHECK_FALSE(view.draw());  // a still frame draws nothing
  image previous = view.display(view_layer::image).image->read_image();
  for (const auto& [setting, text] : changes) {
    const std::string name = setting, value = text;  // clang 14: CAPTURE's lambda takes no structured binding
    CAPTURE(name);
    std::unique_ptr<technique_settings> edited = scenes.of(technique).settings->clone();
    REQUIRE(edited->set(name, value).empty());
    REQUIRE(edited->validate().empty());
    scenes.of(technique).settings = edited->clone();
    const std::uint64_t links = linked_program_count();
    REQUIRE(view.take_settings(scenes));
    CHECK(linked_program_count() == links);
    CHECK(view.draw());  // the next frame redraws
    CHECK(linked_program_count() == links);
    const image shown = view.display(view_layer::image).image->read_image();
    CHECK(different_texels(shown, previous) > 0);
    const std::pair<image, image> expected = fresh_frame(scenes, *edited);
    require_same(shown, expected.first, "final image");
    require_same(view.read_indirect(), expected.second, "indirect light");
    previous = shown;
  }
}

// Each of `changes` (each from `base`) is refused in place: nothing is linked, nothing is
// invalidated (the next frame draws nothing) and the image stays.
void check_refused(const std::string& technique, const setting_values& base, const setting_values& changes) {
  CAPTURE(technique);
  const viewer_scenes scenes = scenes_for(technique, base);
  technique_view view(shaders(), scenes, technique);
  REQUIRE(view.draw());
  const image before = view.display(view_layer::image).image->read_image();
  for (const auto& [setting, text] : changes) {
    const std::string name = setting, value = text;  // clang 14: CAPTURE's lambda takes no structured binding
    CAPTURE(name);
    viewer_scenes edited_scenes = scenes;
    REQUIRE(edited_scenes.of(technique).settings->set(name, value).empty());
    REQUIRE(edited_scenes.of(technique).settings->validate().empty());
    const std::uint64_t links = linked_program_count();
    CHECK_FALSE(view.take_settings(edited_scenes));
    CHECK(linked_program_count() == links);
    CHECK_FALSE(view.draw());  // nothing was invalidated
    require_same(view.display(view_layer::image).image->read_image(), before, "final image kept");
  }
}

}  // namespace

TEST_CASE("viewer: a setting that changes only uniforms is applied in place: no program linked, the fresh pipeline's image") {
  viewer_scenes scenes = rsm_scenes("rsm-alg6");
  technique_view view(shaders(), scenes, "rsm-alg6");
  view.display(view_layer::visibility_difference);  // its baseline pipeline too
  REQUIRE(view.draw());
  const image before = view.read_indirect();
  CHECK_FALSE(view.draw());  // a still frame draws nothing

  // Each of these feeds only uniforms: the radius (pattern and gather), the bilateral filter's
  // sigmas, the shadow bias, the irradiance clamp, the coverage's interleave.
  for (const auto& [setting, text] : std::vector<std::pair<std::string, std::string>>{
           {"radius", "0.25"}, {"filter-depth-sigma", "0.5"}, {"shadow-depth-bias", "0.02"}, {"min-distance", "0.05"},
           {"coverage-interleave", "1"}}) {
    const std::string name = setting, value = text;  // clang 14: CAPTURE's lambda takes no structured binding
    CAPTURE(name);
    std::unique_ptr<technique_settings> edited = scenes.of("rsm-alg6").settings->clone();
    REQUIRE(edited->set(name, value).empty());
    REQUIRE(edited->validate().empty());
    scenes.of("rsm-alg6").settings = edited->clone();
    const std::uint64_t links = linked_program_count();
    REQUIRE(view.take_settings(scenes));
    CHECK(linked_program_count() == links);
    CHECK(view.draw());  // the next frame redraws
    CHECK(linked_program_count() == links);
    const std::pair<image, image> expected = fresh_frame(scenes, *edited);
    require_same(view.display(view_layer::image).image->read_image(), expected.first, "final image");
    require_same(view.read_indirect(), expected.second, "indirect light");
  }
  // The change was visible at all (the settings are not ignored).
  const image after = view.read_indirect();
  std::size_t different = 0;
  for (std::size_t i = 0; i < after.texels.size(); ++i) different += after.texels[i] != before.texels[i];
  CHECK(different > after.texels.size() / 10);
}

TEST_CASE("viewer: a setting that changes a define or a buffer's size needs a new view, and nothing changes in place") {
  // slots: VPLKIT_SLOT_COUNT; rsm-size: the RSM's target; indirect-divisor: the indirect
  // buffer's size; post-filter: VPLKIT_SEPARABLE; coverage-blocks 0: VPLKIT_RSM_COVERAGE.
  check_refused("rsm-alg6", {{"size", "48"}, {"rsm-size", "64"}},
                {{"slots", "4"}, {"rsm-size", "32"}, {"indirect-divisor", "1"}, {"post-filter", "full"}, {"coverage-blocks", "0"}});
  // Another technique of the family: new programs, so a new view.
  viewer_scenes scenes = rsm_scenes("rsm-alg6");
  technique_view view(shaders(), scenes, "rsm-alg6");
  REQUIRE(view.draw());
  viewer_scenes other = scenes;
  other.of("rsm-alg6").settings->set_technique("rsm-alg3");
  CHECK_FALSE(view.take_settings(other));
}

TEST_CASE("viewer: rsm-voxel's march offsets apply in place; its grid's resolution and memory bound need a new view") {
  // The offsets are uniforms (voxel_march); the grid is built with the pipeline.
  check_applied_in_place("rsm-voxel", {{"size", "48"}, {"rsm-size", "64"}}, {{"voxel-start-offset", "4"}, {"voxel-end-offset", "0.5"}});
  check_refused("rsm-voxel", {{"size", "48"}, {"rsm-size", "64"}}, {{"voxel-resolution", "64"}, {"voxel-memory", "0.01"}});
}

// Light Wave (lightwave_pipeline::apply_settings says which setting is which): small maps.
const setting_values lightwave_base = {{"size", "48"}, {"shadow-map-scale", "1"}};

TEST_CASE("viewer: Light Wave's uniform-only settings apply in place: no program linked, the fresh pipeline's image") {
  // Flux energy, importance casters (the defaults): the VPL layout (ray-angle, vpls-per-ray) and
  // min-distance re-plan the VPLs and redraw the shadow maps.
  check_applied_in_place("lightwave-accurate", lightwave_base, {{"ray-angle", "10"}, {"vpls-per-ray", "3"}, {"min-distance", "0.3"}});
  // The thesis's energy and variant: the hemispheres' distance, the seed of the casters' draw, the
  // specular term of Eq. 4.5 (the vertex stage's uniforms).
  setting_values thesis = lightwave_base;
  thesis.insert(thesis.end(), {{"vpl-energy", "thesis"}, {"shadow-variant", "thesis"}, {"ray-angle", "10"}});
  check_applied_in_place("lightwave-accurate", thesis,
                         {{"vpl-max-distance", "3"}, {"seed", "7"}, {"specular-strength", "0.5"}, {"specular-exponent", "2"}, {"vpl-field-of-view", "60"}});
  check_applied_in_place("lightwave-integrated", lightwave_base, {{"integrated-steps", "2"}, {"vpl-field-of-view", "60"}});
  check_applied_in_place("lightwave-faked", lightwave_base, {{"faked-multiplier", "2.5"}});
}

TEST_CASE("viewer: Light Wave's settings that change a define or a buffer's size need a new view, and nothing changes in place") {
  // size, format: the targets; vpl-energy, shadow-variant: defines; shadow-maps: the shadow
  // maps' layers; shadow-map-scale: their size.
  check_refused("lightwave-accurate", lightwave_base,
                {{"size", "32"}, {"format", "rgba32f"}, {"vpl-energy", "thesis"}, {"shadow-variant", "thesis"}, {"shadow-maps", "10"}, {"shadow-map-scale", "2"}});
  check_refused("lightwave-integrated", lightwave_base, {{"integrated-maps", "3"}});
  check_refused("lightwave-faked", lightwave_base, {{"vpl-energy", "thesis"}});
  viewer_scenes scenes = scenes_for("lightwave-accurate", lightwave_base);
  technique_view view(shaders(), scenes, "lightwave-accurate");
  REQUIRE(view.draw());
  viewer_scenes other = scenes;
  other.of("lightwave-accurate").settings->set_technique("lightwave-integrated");
  CHECK_FALSE(view.take_settings(other));
}

// Final gathering: a small cube map.
const setting_values final_gather_base = {{"size", "48"}, {"face-size", "32"}};

TEST_CASE("viewer: final gathering's uniform-only setting applies in place: no program linked, the fresh pipeline's image") {
  // min-distance: the cube map's faces and the shading read it (the cube map is redrawn); 1.5
  // clamps the spot light's distance to the object's top and the walls' upper parts (the light
  // hangs under the ceiling of the room 2 high), so that the change shows.
  for (const char* technique : {"finalgather-polygon", "envmap"}) check_applied_in_place(technique, final_gather_base, {{"min-distance", "1.5"}});
}

TEST_CASE("viewer: final gathering's settings that change a buffer's size, a define or the object need a new view, and nothing changes in place") {
  // size, format, face-size, cube-resolution: targets; object-size: a new scene.
  check_refused("finalgather-polygon", final_gather_base,
                {{"size", "32"}, {"format", "rgba16f"}, {"face-size", "16"}, {"cube-resolution", "2"}, {"object-size", "0.3"}});
  // environment-resolution: the baseline's environment map.
  check_refused("envmap", final_gather_base, {{"environment-resolution", "8"}});
  viewer_scenes scenes = scenes_for("finalgather-polygon", final_gather_base);
  technique_view view(shaders(), scenes, "finalgather-polygon");
  REQUIRE(view.draw());
  viewer_scenes other = scenes;
  other.of("finalgather-polygon").settings->set_technique("finalgather-point");
  CHECK_FALSE(view.take_settings(other));
}
