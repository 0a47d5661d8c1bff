// frontend/techniques/registry.hpp and the setting tables (frontend/core/setting.hpp): every
// family's settings are usable at their defaults and refuse what their ranges exclude with the
// setting's name; a value read back is the value set; one name means one range in every family;
// who reads a setting is what its predicate says; every GLSL uniform a setting claims to feed is
// declared by the shader it names; and every technique's pipeline takes cameras and lights the
// same way and redraws only what a move invalidated.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "frontend/core/error.hpp"
#include <vplkit/gl/uniform_declarations.hpp>
#include "frontend/techniques/registry.hpp"
#include "frontend/techniques/final_gather/final_gather_pipeline.hpp"
#include <vplkit/parity/parity.hpp>

using namespace vplkit;

namespace {

// A value just outside a finite end of a number's range (nullopt when the end is open to infinity).
std::optional<std::string> beyond(const setting_info& info, bool low) {
  const double end = low ? info.range.low : info.range.high;
  if (!std::isfinite(end)) return std::nullopt;
  if (info.type == setting_type::integer) return std::to_string(static_cast<long long>(low ? (info.range.low_open ? end : end - 1) : (info.range.high_open ? end : end + 1)));
  const bool open = low ? info.range.low_open : info.range.high_open;
  return format_real(open ? end : (low ? end - std::max(1e-3, std::fabs(end) * 1e-3) : end + std::max(1e-3, std::fabs(end) * 1e-3)));
}

}  // namespace

TEST_CASE("every family's settings are usable at their defaults, for every technique") {
  for (const technique_family& family : technique_families()) {
    CHECK_FALSE(family.techniques.empty());
    for (const technique_entry& technique : family.techniques) {
      CAPTURE(technique.name);
      const std::unique_ptr<technique_settings> settings = family.make_settings(technique.name);
      CHECK(settings->technique() == technique.name);
      CHECK(settings->validate() == "");
      std::set<std::string> names;
      for (const setting_info* info : settings->settings()) {
        CAPTURE(info->name);
        CHECK(names.insert(info->name).second);  // one description per setting
        CHECK_FALSE(info->help.empty());
        CHECK(info->check(settings->get(info->name)) == "");
      }
    }
  }
}

TEST_CASE("a setting refuses values out of its range with its name, and reads back what was set") {
  for (const technique_family& family : technique_families()) {
    const std::unique_ptr<technique_settings> settings = family.make_settings(family.techniques.back().name);
    for (const setting_info* info : settings->settings()) {
      CAPTURE(family.name);
      CAPTURE(info->name);
      // Round trip: what get() writes, set() reads, unchanged.
      const std::string value = settings->get(info->name);
      CHECK(settings->set(info->name, value) == "");
      CHECK(settings->get(info->name) == value);
      if (info->type != setting_type::integer && info->type != setting_type::real) continue;
      for (const bool low : {true, false}) {
        const std::optional<std::string> bad = beyond(*info, low);
        if (!bad) continue;
        CAPTURE(*bad);
        const std::string why = settings->set(info->name, *bad);
        CHECK_FALSE(why.empty());
        CHECK(settings->get(info->name) == value);  // nothing changed
        CHECK((why.find(describe_range(info->range)) != std::string::npos || why.find(info->values()) != std::string::npos));
      }
      for (const char* nonsense : {"nan", "inf", "x", ""}) CHECK_FALSE(settings->set(info->name, nonsense).empty());
      // A viewer slider offers the range's ends: a closed end is a value, an open one is refused.
      if (info->allowed.empty() && std::isfinite(info->range.low) && std::isfinite(info->range.high)) {
        const std::string low = info->type == setting_type::integer ? std::to_string(static_cast<long long>(info->range.low)) : format_real(info->range.low);
        CHECK(info->check(low).empty() == !info->range.low_open);
      }
      for (int allowed : info->allowed) CHECK(info->check(std::to_string(allowed)).empty());
    }
  }
}

TEST_CASE("a setting several families have takes the same values in each: one option describes it") {
  std::map<std::string, const setting_info*> first;
  std::vector<std::unique_ptr<technique_settings>> kept;
  for (const technique_family& family : technique_families()) {
    kept.push_back(family.make_settings(family.techniques.front().name));
    for (const setting_info* info : kept.back()->settings()) {
      const auto [found, inserted] = first.emplace(info->name, info);
      if (inserted) continue;
      CAPTURE(info->name);
      CHECK(found->second->type == info->type);
      CHECK(found->second->values() == info->values());
    }
  }
  CHECK(first.count("size") == 1);
  CHECK(first.count("min-distance") == 1);
}

TEST_CASE("who reads a setting is its predicate over the family's techniques") {
  const technique_family& rsm = family_of("rsm-alg6");
  const std::unique_ptr<technique_settings> settings = rsm.make_settings("rsm-alg6");
  CHECK(settings->readers("slots") == std::vector<std::string>{"rsm-alg2", "rsm-alg3", "rsm-alg6", "rsm-alg6-ray"});
  CHECK(settings->readers("disk-samples") == std::vector<std::string>{"rsm-original"});
  CHECK(settings->readers("paths") == std::vector<std::string>{"rsm-radial", "rsm-alg2", "rsm-alg3", "rsm-alg6", "rsm-alg6-ray", "rsm-voxel"});
  CHECK(settings->readers("rsm-size").size() == rsm.techniques.size());
  CHECK_FALSE(settings->reads("slots", "rsm-radial"));
  const std::unique_ptr<technique_settings> light_wave = family_of("lightwave-faked").make_settings("lightwave-faked");
  CHECK(settings->readers("voxel-resolution") == std::vector<std::string>{"rsm-voxel"});
  CHECK(settings->readers("voxel-start-offset") == std::vector<std::string>{"rsm-voxel"});
  CHECK(light_wave->readers("faked-multiplier") == std::vector<std::string>{"lightwave-faked"});
  CHECK(light_wave->readers("integrated-steps") == std::vector<std::string>{"lightwave-integrated"});
  CHECK(light_wave->find("radius") == nullptr);
  CHECK_THROWS_AS(light_wave->set_technique("rsm-alg6"), vplkit::error);
  CHECK(family_of("envmap").name == "final-gather");
  CHECK_THROWS_WITH_AS(family_of("rsm-alg7"), doctest::Contains("unknown technique 'rsm-alg7'"), vplkit::error);
  CHECK(technique_names().size() == 16u);
}

TEST_CASE("the settings in effect as JSON: the settings the technique reads, numbers as numbers") {
  const std::unique_ptr<technique_settings> settings = family_of("rsm-radial").make_settings("rsm-radial");
  REQUIRE(settings->set("radius", "0.5") == "");
  const std::string json = settings_json(*settings);
  CHECK(json.find("\"technique\": \"rsm-radial\"") != std::string::npos);
  CHECK(json.find("\"radius\": 0.5") != std::string::npos);
  CHECK(json.find("\"post-filter\": \"separable\"") != std::string::npos);
  CHECK(json.find("\"slots\"") == std::string::npos);   // rsm-radial reads no slots
  CHECK(json.find("\"preset\"") == std::string::npos);  // radius, paths, samples and slots are in effect instead
}

TEST_CASE("every GLSL uniform a setting feeds is declared by the shader it names") {
  const shader_library& shaders = parity::test_shaders();
  std::map<std::string, std::pair<uniform_declarations, std::string>> files;
  int checked = 0;
  for (const technique_family& family : technique_families()) {
    const std::unique_ptr<technique_settings> settings = family.make_settings(family.techniques.front().name);
    for (const setting_info* info : settings->settings()) {
      std::string rest = info->glsl;
      while (!rest.empty()) {
        const std::size_t end = rest.find("; ");
        const std::string item = rest.substr(0, end);
        rest = end == std::string::npos ? "" : rest.substr(end + 2);
        const std::size_t colon = item.find(": ");
        CAPTURE(info->name);
        CAPTURE(item);
        REQUIRE(colon != std::string::npos);
        const std::string file = item.substr(0, colon), uniform = item.substr(colon + 2);
        auto found = files.find(file);
        if (found == files.end()) {
          const std::string text = shaders.expand_file(file).text;
          uniform_declarations declarations;
          declarations.scan(text);
          found = files.emplace(file, std::make_pair(declarations, text)).first;
        }
        if (uniform.rfind("VPLKIT_", 0) == 0) CHECK(found->second.second.find(uniform) != std::string::npos);
        else CHECK(found->second.first.declares(uniform));
        ++checked;
      }
    }
  }
  CHECK(checked > 30);
}

namespace {

// Values to try for a setting other than `value`: its range's closed ends, its allowed values or
// choices, and the value doubled, halved, plus and minus one.
std::vector<std::string> other_allowed_values(const setting_info& info, const std::string& value) {
  std::vector<std::string> candidates;
  if (info.type == setting_type::choice) return info.choices;
  for (int allowed : info.allowed) candidates.push_back(std::to_string(allowed));
  const std::optional<double> number = info.number(value);
  if (!number) return candidates;
  const auto text = [&](double x) { return info.type == setting_type::integer ? std::to_string(static_cast<long long>(std::llround(x))) : format_real(x); };
  if (std::isfinite(info.range.low) && !info.range.low_open) candidates.push_back(text(info.range.low));
  if (std::isfinite(info.range.high) && !info.range.high_open) candidates.push_back(text(info.range.high));
  for (double x : {*number * 2.0, *number * 0.5, *number + 1.0, *number - 1.0, *number + 0.1, *number - 0.1}) candidates.push_back(text(x));
  return candidates;
}

}  // namespace

TEST_CASE("every kernel-struct member a setting feeds moves with the setting, as the frame derives it") {
  // The member path of setting::feeds names the uniform (checked above against the shaders);
  // here the binding is real: a technique that reads the setting, given another usable value of
  // it, derives another value of every member the setting claims to feed.
  int checked = 0;
  for (const technique_family& family : technique_families()) {
    for (const setting_info* info : family.make_settings(family.techniques.front().name)->settings()) {
      for (const std::string& technique : family.make_settings(family.techniques.front().name)->readers(info->name)) {
        const std::unique_ptr<technique_settings> settings = family.make_settings(technique);
        const std::vector<double> before = settings->fed_values(info->name);
        if (before.empty()) continue;
        CAPTURE(technique);
        CAPTURE(info->name);
        bool moved = false;
        for (const std::string& candidate : other_allowed_values(*info, settings->get(info->name))) {
          const std::unique_ptr<technique_settings> changed = settings->clone();
          if (!changed->set(info->name, candidate).empty() || !changed->validate().empty() || changed->get(info->name) == settings->get(info->name)) continue;
          CAPTURE(candidate);
          const std::vector<double> after = changed->fed_values(info->name);
          REQUIRE(after.size() == before.size());
          for (std::size_t k = 0; k < after.size(); ++k) CHECK(after[k] != before[k]);
          moved = true;
          break;
        }
        CHECK(moved);  // some other value was usable
        ++checked;
      }
    }
  }
  CHECK(checked > 40);
}

TEST_CASE("every technique's pipeline takes cameras and lights the same way and redraws only what a move invalidated") {
  const shader_library& shaders = parity::test_shaders();
  for (const technique_family& family : technique_families()) {
    const scene source = family.reads_scene() ? built_in_scene(family.default_scene) : scene{};
    for (const technique_entry& technique : family.techniques) {
      CAPTURE(technique.name);
      std::unique_ptr<technique_settings> settings = family.make_settings(technique.name);
      REQUIRE(settings->set("size", "24x16") == "");
      for (const auto& [name, value] : std::map<std::string, std::string>{{"rsm-size", "32"}, {"shadow-map-scale", "1"}, {"face-size", "16"}})
        if (settings->find(name)) REQUIRE(settings->set(name, value) == "");
      const std::unique_ptr<pipeline> drawn = family.make_pipeline(shaders, family.reads_scene() ? &source : nullptr, *settings);
      drawn->draw();
      const int after_draw = drawn->view_draws();
      CHECK_FALSE(drawn->collect_pass_times().empty());
      drawn->draw_changed();  // nothing moved
      CHECK(drawn->view_draws() == after_draw);
      CHECK(drawn->collect_pass_times().empty());
      camera moved = drawn->current_camera();
      moved.position.x += 0.1f;
      drawn->set_camera(moved);
      drawn->draw_changed();
      CHECK(drawn->view_draws() == after_draw + 1);
      CHECK(drawn->current_camera().position.x == moved.position.x);
      scene_light light = drawn->current_lights().at(0);
      drawn->set_light(0, light);
      drawn->draw_changed();
      CHECK(drawn->view_draws() == after_draw + 2);
      drawn->collect_pass_times();
      // A refused move keeps what was there.
      camera broken = moved;
      broken.target = broken.position;
      CHECK_THROWS_AS(drawn->set_camera(broken), vplkit::error);
      CHECK(drawn->current_camera().target == moved.target);
      scene_light sun;
      sun.kind = light_kind::directional;
      if (family.name == "lightwave") {
        CHECK_THROWS_WITH_AS(drawn->set_light(0, sun), doctest::Contains("spot light"), vplkit::error);
      } else if (family.name == "final-gather") {  // every kind of light, each with its own shadows
        drawn->set_light(0, sun);
        CHECK(drawn->current_lights().at(0).kind == light_kind::directional);
      }
      CHECK(drawn->has_indirect() == (technique.name != "direct" && technique.name != "lightwave-direct"));
      CHECK(drawn->describe().find(technique.name) != std::string::npos);
    }
  }
}

namespace {

double rec709_luminance_sum(const image& picture) {
  double sum = 0.0;
  for (const glm::vec4& texel : picture.texels) sum += 0.2126 * texel.r + 0.7152 * texel.g + 0.0722 * texel.b;
  return sum;
}

// The sum of pipeline::indirect_output(), what `vplkit render` writes to -indirect.pfm.
double indirect_sum(const technique_family& family, const std::string& technique, const scene& source) {
  std::unique_ptr<technique_settings> settings = family.make_settings(technique);
  REQUIRE(settings->set("size", "32x24") == "");
  REQUIRE(settings->set("format", "rgba32f") == "");
  for (const auto& [name, value] : std::map<std::string, std::string>{{"rsm-size", "64"}, {"shadow-map-scale", "1"}})
    if (settings->find(name)) REQUIRE(settings->set(name, value) == "");
  const std::unique_ptr<pipeline> drawn = family.make_pipeline(parity::test_shaders(), &source, *settings);
  drawn->draw();
  return rec709_luminance_sum(drawn->indirect_output().read_image());
}

}  // namespace

TEST_CASE("-indirect.pfm is the indirect irradiance in every family: one bounce is linear in the reflector's albedo, not in the receiver's") {
  // Halving every albedo halves the irradiance a bounce brings (the reflected flux halves) but
  // quarters the radiance the receivers reflect of it: a family that wrote radiance would give 1/4.
  // Halving is exact in floating point, so the ratio is 1/2 up to the sums' rounding.
  // A pair, not a structured binding: clang 14 cannot capture one in CAPTURE's lambda.
  for (const auto& family_and_technique : std::vector<std::pair<std::string, std::string>>{{"rsm", "rsm-radial"}, {"lightwave", "lightwave-unshadowed"}}) {
    const std::string& family_name = family_and_technique.first;
    const std::string& technique = family_and_technique.second;
    CAPTURE(technique);
    const technique_family& family = family_of(technique);
    CHECK(family.name == family_name);
    scene source = built_in_scene("cornell-box");
    const double full = indirect_sum(family, technique, source);
    REQUIRE(full > 0.0);
    for (vertex& v : source.geometry.vertices) v.albedo *= 0.5f;
    CHECK(indirect_sum(family, technique, source) / full == doctest::Approx(0.5).epsilon(1e-4));
  }
  // Final gathering: the object's own albedo changes its radiance, not the irradiance it gathers.
  final_gather_scene room = make_final_gather_scene("sphere", glm::vec3(0.0f, 0.7f, 0.0f), 0.5f);
  final_gather_settings settings;
  settings.width = settings.height = 24;
  settings.face_size = 16;
  // The irradiance over the image, and the radiance of the object's pixels (those it gathers at).
  const auto gathered = [&] {
    final_gather_pipeline drawn(parity::test_shaders(), room, settings);
    const final_gather_frame frame = drawn.render();
    double object_radiance = 0.0;
    for (std::size_t i = 0; i < frame.indirect.texels.size(); ++i)
      if (frame.indirect.texels[i].r + frame.indirect.texels[i].g + frame.indirect.texels[i].b > 0.0f)
        object_radiance += 0.2126 * frame.radiance.texels[i].r + 0.7152 * frame.radiance.texels[i].g + 0.0722 * frame.radiance.texels[i].b;
    return std::make_pair(rec709_luminance_sum(frame.indirect), object_radiance);
  };
  const auto [irradiance, radiance] = gathered();
  REQUIRE(irradiance > 0.0);
  for (mesh* part : {&room.object, &room.local_object})
    for (vertex& v : part->vertices) v.albedo *= 0.5f;
  const auto [darker_irradiance, darker_radiance] = gathered();
  CHECK(darker_irradiance == doctest::Approx(irradiance).epsilon(1e-6));
  CHECK(darker_radiance / radiance == doctest::Approx(0.5).epsilon(1e-4));  // what a radiance output would have halved
}
