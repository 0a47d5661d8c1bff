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

using namespace vplkit;

namespace {

// The test binary's headless context and shader library (made on first use).
const shader_library& shaders() { return parity::test_shaders(); }

viewer_scenes rsm_scenes(const std::string& technique) {
  viewer_scenes scenes;
  viewer_family& rsm = scenes.families["rsm"];
  rsm.settings = family_of(technique).make_settings(technique);
  REQUIRE(rsm.settings->set("size", "48").empty());
  REQUIRE(rsm.settings->set("rsm-size", "64").empty());
  rsm.source = built_in_scene("cornell-box");
  return scenes;
}

// What a fresh pipeline with `settings` draws first: its final image and its indirect light.
std::pair<image, image> fresh_frame(const viewer_scenes& scenes, const technique_settings& settings) {
  std::unique_ptr<pipeline> fresh = family_of(settings.technique()).make_pipeline(shaders(), &*scenes.families.at("rsm").source, settings);
  fresh->draw_changed();
  return {fresh->output().read_image(), fresh->indirect_output().read_image()};
}

void require_same(const image& a, const image& b, const char* what) {
  INFO(what);
  REQUIRE(a.width == b.width);
  REQUIRE(a.height == b.height);
  std::size_t different = 0;
  for (std::size_t i = 0; i < a.texels.size(); ++i) different += a.texels[i] != b.texels[i];
  CHECK(different == 0);
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
  viewer_scenes scenes = rsm_scenes("rsm-alg6");
  technique_view view(shaders(), scenes, "rsm-alg6");
  REQUIRE(view.draw());
  const image before = view.read_indirect();
  // slots: VPLKIT_SLOT_COUNT; rsm-size: the RSM's target; indirect-divisor: the indirect
  // buffer's size; post-filter: VPLKIT_SEPARABLE; coverage-blocks 0: VPLKIT_RSM_COVERAGE.
  for (const auto& [setting, text] : std::vector<std::pair<std::string, std::string>>{
           {"slots", "4"}, {"rsm-size", "32"}, {"indirect-divisor", "1"}, {"post-filter", "full"}, {"coverage-blocks", "0"}}) {
    const std::string name = setting, value = text;  // clang 14: CAPTURE's lambda takes no structured binding
    CAPTURE(name);
    viewer_scenes edited_scenes = scenes;
    REQUIRE(edited_scenes.of("rsm-alg6").settings->set(name, value).empty());
    REQUIRE(edited_scenes.of("rsm-alg6").settings->validate().empty());
    const std::uint64_t links = linked_program_count();
    CHECK_FALSE(view.take_settings(edited_scenes));
    CHECK(linked_program_count() == links);
    CHECK_FALSE(view.draw());  // nothing was invalidated
    require_same(view.read_indirect(), before, "indirect light kept");
  }
  // Another technique of the family: new programs, so a new view.
  viewer_scenes other = scenes;
  other.of("rsm-alg6").settings->set_technique("rsm-alg3");
  CHECK_FALSE(view.take_settings(other));
}
