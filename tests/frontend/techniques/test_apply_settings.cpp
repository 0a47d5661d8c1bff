// pipeline::apply_settings against the settings tables, for every setting of every family: the
// table says which change needs a new pipeline (setting::defines, setting::builds; the rest feed
// uniforms), and the pipelines decide from it (rebuilding_changes). Here each setting is changed
// to another usable value on a pipeline of a technique that reads it:
// - a change the table says needs a rebuild (every change of a define) is refused in place and
//   links nothing;
// - any other change is taken in place, links no program, and the next frame is the frame a
//   fresh pipeline with the new settings draws, bit for bit (final image and indirect light), so
//   that a setting the table calls a uniform while a define or a build depends on it fails here;
// - a setting the pipeline keeps as its own state (the object's position) is neither applied nor
//   a rebuild.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>

#include <vplkit/gl/program.hpp>
#include <vplkit/parity/parity.hpp>

#include "frontend/core/setting.hpp"
#include "frontend/image/image.hpp"
#include "frontend/scene/scene.hpp"
#include "frontend/techniques/registry.hpp"
#include "tests/gl_test_helpers.hpp"

using namespace vplkit;

namespace {

using setting_values = std::vector<std::pair<std::string, std::string>>;

// Small frames, and per family the bases a setting is tried from: some settings are usable only
// beside others (vpl-max-distance with the thesis's energy).
std::vector<setting_values> bases(const technique_family& family) {
  if (family.name == "rsm") return {{{"size", "24x16"}, {"rsm-size", "32"}}};
  if (family.name == "lightwave")
    return {{{"size", "24x16"}, {"shadow-map-scale", "1"}},
            {{"size", "24x16"}, {"shadow-map-scale", "1"}, {"vpl-energy", "thesis"}, {"shadow-variant", "thesis"}, {"ray-angle", "10"}}};
  return {{{"size", "24x16"}, {"face-size", "16"}}};
}

// A one-triangle-fan .obj for the final gathering's object setting (a file other than the sphere).
std::string small_object_file() {
  static const std::string path = [] {
    const std::filesystem::path file = std::filesystem::temp_directory_path() / "vplkit_test_apply_settings_object.obj";
    std::ofstream out(file);
    out << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    return file.string();
  }();
  return path;
}

// Other values to try for a setting: its choices or allowed values, its range's closed ends, the
// value doubled, halved, plus and minus one or a tenth; another size, point, object or placement.
std::vector<std::string> other_values(const setting_info& info, const std::string& value) {
  switch (info.type) {
    case setting_type::choice: return info.choices;
    case setting_type::size: return {"20x12"};
    case setting_type::point: return {"0.2,0.8,-0.1"};
    case setting_type::text: return {small_object_file(), "0,0.6,0,0.2"};  // an object file, or a placement (object-at)
    default: break;
  }
  std::vector<std::string> candidates;
  for (int allowed : info.allowed) candidates.push_back(std::to_string(allowed));
  const std::optional<double> number = info.number(value);
  if (!number) return candidates;
  const auto text = [&](double x) { return info.type == setting_type::integer ? std::to_string(static_cast<long long>(std::llround(x))) : format_real(x); };
  for (double x : {*number * 2.0, *number * 0.5, *number + 1.0, *number - 1.0, *number + 0.1, *number - 0.1}) candidates.push_back(text(x));
  if (std::isfinite(info.range.low) && !info.range.low_open) candidates.push_back(text(info.range.low));
  if (std::isfinite(info.range.high) && !info.range.high_open) candidates.push_back(text(info.range.high));
  return candidates;
}

struct trial {
  std::unique_ptr<technique_settings> base, changed;
};

// The first technique reading `name`, base and value that make usable settings with another value.
std::optional<trial> find_change(const technique_family& family, const std::string& name) {
  for (const std::string& technique : family.make_settings(family.techniques.front().name)->readers(name))
    for (const setting_values& values : bases(family)) {
      std::unique_ptr<technique_settings> base = family.make_settings(technique);
      bool usable = true;
      for (const auto& [setting, value] : values) usable = usable && (!base->find(setting) || base->set(setting, value).empty());
      if (!usable || !base->validate().empty()) continue;
      for (const std::string& candidate : other_values(*base->find(name), base->get(name))) {
        std::unique_ptr<technique_settings> changed = base->clone();
        if (changed->set(name, candidate).empty() && changed->validate().empty() && changed->get(name) != base->get(name))
          return trial{std::move(base), std::move(changed)};
      }
    }
  return std::nullopt;
}

using vplkit::testing::different_texels;

}  // namespace

TEST_CASE("every setting of every family: a change the table calls a rebuild is refused in place, any other is the fresh pipeline's frame") {
  const shader_library& shaders = parity::test_shaders();
  int in_place = 0, refused = 0, defines = 0;
  for (const technique_family& family : technique_families()) {
    const std::optional<scene> source = family.reads_scene() ? std::optional<scene>(built_in_scene(family.default_scene)) : std::nullopt;
    const scene* scene_pointer = source ? &*source : nullptr;
    for (const setting_info* info : family.make_settings(family.techniques.front().name)->settings()) {
      CAPTURE(info->name);
      std::optional<trial> change = find_change(family, info->name);
      REQUIRE(change);  // some technique reads it, and some other value is usable
      const std::string technique = change->base->technique(), value = change->changed->get(info->name);
      CAPTURE(technique);
      CAPTURE(value);
      const std::vector<std::string> rebuilds = change->changed->rebuilding_changes(*change->base);
      // A define's change always needs new programs; a setting without a reason never rebuilds.
      if (info->rebuilds.find("the define ") != std::string::npos) {
        CHECK_FALSE(rebuilds.empty());
        ++defines;
      }
      // A setting without a reason that changes no other setting (a preset changes four) rebuilds nothing.
      bool alone = true;
      for (const setting_info* other : change->base->settings())
        alone = alone && (other == change->base->find(info->name) || !other->in_effect || change->base->get(other->name) == change->changed->get(other->name));
      if (info->rebuilds.empty() && alone) CHECK(rebuilds.empty());

      const std::unique_ptr<pipeline> drawn = family.make_pipeline(shaders, scene_pointer, *change->base);
      drawn->draw_changed();
      const image before = drawn->output().read_image();
      const glm::vec3 object = drawn->object_position();
      const std::uint64_t links = linked_program_count();
      const bool applied = drawn->apply_settings(*change->changed);
      CHECK(linked_program_count() == links);
      CHECK(applied == rebuilds.empty());
      if (!applied) {
        ++refused;
        const int draws = drawn->view_draws();
        drawn->draw_changed();
        CHECK(drawn->view_draws() == draws);  // nothing was invalidated
        CHECK(different_texels(drawn->output().read_image(), before) == 0);
        continue;
      }
      ++in_place;
      drawn->draw_changed();
      CHECK(linked_program_count() == links);
      if (info->pose) {
        // The pipeline's own: the object stays where the pipeline has it.
        CHECK(drawn->object_position() == object);
        continue;
      }
      const std::unique_ptr<pipeline> fresh = family.make_pipeline(shaders, scene_pointer, *change->changed);
      fresh->draw_changed();
      CHECK(different_texels(drawn->output().read_image(), fresh->output().read_image()) == 0);
      CHECK(different_texels(drawn->indirect_output().read_image(), fresh->indirect_output().read_image()) == 0);
    }
  }
  // Both ways are exercised, for defines as well (post-filter, slots, the Light Wave energy...).
  CHECK(in_place > 30);
  CHECK(refused > 15);
  CHECK(defines >= 5);
  std::remove(small_object_file().c_str());
}
