// vplkit/settings.hpp: the descriptions of the kernels' settings structs and the validate() that
// comes from them. Every described struct is usable at its defaults (where its default is a
// usable value) and refuses each field pushed just out of its range, naming the struct, the field
// and the range; composites validate their parts; a description names each field once.
#include <doctest/doctest.h>

#include <cstring>
#include <limits>
#include <set>
#include <string>

#include <vplkit/vplkit.hpp>

using namespace vplkit;

namespace {

std::string message(const setting_problem& problem) { return problem.message(); }

// Every field's name once, and every member once (two fields of one member would be two
// descriptions of one setting).
template <typename Settings>
void check_names_unique() {
  std::set<std::string> names;
  Settings settings{};
  int count = 0;
  for_each_field(settings, [&](const field_description& field, const auto&) {
    CHECK(std::strlen(field.name) > 0);
    CHECK(std::strlen(field.help) > 0);
    names.insert(field.name);
    ++count;
  });
  CHECK(names.size() == static_cast<std::size_t>(count));
}

// Sets the first number of a field (of whatever shape) to `value`; false when the field is a
// described struct (validated by its own description).
template <typename Value>
bool set_first_number(Value& field, double value) {
  if constexpr (is_described_v<Value>) {
    return false;
  } else if constexpr (std::is_array_v<Value>) {
    return set_first_number(field[0], value);
  } else if constexpr (detail::is_glm_vector<Value>) {
    return set_first_number(field[0], value);
  } else {
    // A value the type cannot hold (a negative unsigned) would be undefined, not out of range.
    if constexpr (std::is_integral_v<Value>)
      if (value < static_cast<double>(std::numeric_limits<Value>::lowest()) || value > static_cast<double>(std::numeric_limits<Value>::max())) return false;
    field = static_cast<Value>(value);
    return true;
  }
}

// Each numeric field just outside each finite end of its range (and NaN for a float) is refused
// with a message naming the struct and the field.
template <typename Settings>
void check_ranges_refused(const Settings& usable) {
  REQUIRE_MESSAGE(!validate(usable), message(validate(usable)));
  Settings probe = usable;
  int index = 0;
  for_each_field(probe, [&](const field_description& field, auto&) {
    const int target = index++;
    const auto refuse = [&](double bad) {
      Settings broken = usable;
      int at = 0;
      bool set = false;
      for_each_field(broken, [&](const field_description&, auto& value) {
        if (at++ == target) set = set_first_number(value, bad);
      });
      if (!set) return;
      const setting_problem problem = validate(broken);
      CAPTURE(field.name);
      CAPTURE(bad);
      CHECK(static_cast<bool>(problem));
      CHECK(message(problem).find(settings_description<Settings>::name) != std::string::npos);
      CHECK(message(problem).find(field.name) != std::string::npos);
    };
    const setting_range& range = field.range;
    // Integers cannot go below a bound by less than 1; floats by a relative step.
    if (range.low > -std::numeric_limits<double>::infinity()) refuse(range.low_open ? range.low : range.low - 1.0);
    if (range.high < std::numeric_limits<double>::infinity() && range.high < 4294967295.0) refuse(range.high_open ? range.high : range.high + 1.0);
  });
}

}  // namespace

TEST_CASE("setting_range: open and closed ends, infinite ends, NaN and infinities refused") {
  CHECK(schema::closed_range(1, 3).contains(1));
  CHECK(schema::closed_range(1, 3).contains(3));
  CHECK_FALSE(schema::closed_range(1, 3).contains(3.0001));
  CHECK_FALSE(schema::open_closed_range(0, 2).contains(0));
  CHECK(schema::open_closed_range(0, 2).contains(2));
  CHECK_FALSE(schema::closed_open_range(0, 1).contains(1));
  CHECK(schema::above(0).contains(1e300));
  CHECK_FALSE(schema::above(0).contains(std::numeric_limits<double>::infinity()));
  CHECK_FALSE(schema::any_finite().contains(std::numeric_limits<double>::quiet_NaN()));
  CHECK(schema::any_finite().contains(-1e300));
}

TEST_CASE("a problem names the struct, the field, the range, the unit and the value") {
  const setting_problem problem = validate(irradiance_settings<float>{-1.0f});
  CHECK(message(problem) == "irradiance_settings::min_distance must be > 0 (scene units), got -1");
  radial_pattern_settings<float> radial;
  radial.paths = 300;
  CHECK(message(validate(radial)) == "radial_pattern_settings::paths must be in [1, 256], got 300");
  radial.paths = 15;
  radial.scale_jitter = 1.0f;
  CHECK(message(validate(radial)) == "radial_pattern_settings::scale_jitter must be in [0, 1), got 1");
  CHECK(message(validate(radial_pattern_settings<float>{})).empty());
  CHECK_FALSE(static_cast<bool>(setting_problem()));
}

TEST_CASE("rules join fields: radii in order, odd kernels, unit directions, cones in order, ray angles that close up") {
  radial_pattern_settings<double> radial;
  radial.max_radius = radial.min_radius;
  CHECK(message(validate(radial)) == "radial_pattern_settings::max_radius must be finite and > min_radius");
  bilateral_settings<float> bilateral;
  bilateral.kernel_size = 16;
  CHECK(message(validate(bilateral)).find("odd") != std::string::npos);
  spot_light<float> spot;
  spot.direction = glm::vec3(0.5f, 0.0f, 0.0f);
  CHECK(message(validate(spot)) == "spot_light::direction must be a unit vector");
  spot.direction = glm::vec3(0, -1, 0);
  spot.cos_inner = spot.cos_outer;
  CHECK(message(validate(spot)).find("cos_inner must be greater than cos_outer") != std::string::npos);
  for (int angle = 1; angle <= 90; ++angle)
    CHECK(static_cast<bool>(validate_lightwave_layout(angle, 5)) == (90 % angle != 0 || 360 % angle != 0));
  elevation_slots<float> slots = make_elevation_slots<float>(6);
  std::swap(slots.boundary_tangent[1], slots.boundary_tangent[2]);
  CHECK(message(validate(slots)).find("ascend") != std::string::npos);
}

TEST_CASE("every described struct is usable at its defaults and refuses each field out of its range") {
  check_ranges_refused(irradiance_settings<float>{});
  check_ranges_refused(radial_pattern_settings<float>{});
  check_ranges_refused(make_radial_pattern_constants(radial_pattern_settings<float>{}));
  check_ranges_refused(disk_pattern_settings<float>{});
  check_ranges_refused(make_elevation_slots<float>(5));
  check_ranges_refused(shadow_density_settings<float>{});
  check_ranges_refused(bilateral_settings<float>{});
  check_ranges_refused(spot_light<float>{});
  check_ranges_refused(directional_light<float>{});
  check_ranges_refused(lightwave_layout_settings<float>{});
  check_ranges_refused(lightwave_cone_settings<float>{});
  check_ranges_refused(lightwave_shading_settings<float>{});
  check_ranges_refused(make_rsm_unprojection(0.5f, true, glm::ivec2(64)));
  check_ranges_refused(default_rsm_gather_preset<float>());
  check_ranges_refused(default_rsm_gather_settings<float>(glm::ivec2(512)));
  check_ranges_refused(irradiance_settings<double>{});
  check_ranges_refused(default_rsm_gather_settings<double>(glm::ivec2(64)));
}

TEST_CASE("each field is described once, with a name and a line of help") {
  check_names_unique<irradiance_settings<float>>();
  check_names_unique<radial_pattern_settings<float>>();
  check_names_unique<radial_pattern_constants<float>>();
  check_names_unique<disk_pattern_settings<float>>();
  check_names_unique<elevation_slots<float>>();
  check_names_unique<rsm_gather_settings<float>>();
  check_names_unique<rsm_gather_preset<float>>();
  check_names_unique<shadow_density_settings<float>>();
  check_names_unique<bilateral_settings<float>>();
  check_names_unique<spot_light<float>>();
  check_names_unique<directional_light<float>>();
  check_names_unique<lightwave_layout_settings<float>>();
  check_names_unique<lightwave_cone_settings<float>>();
  check_names_unique<lightwave_shading_settings<float>>();
  check_names_unique<rsm_unprojection<float>>();
}

TEST_CASE("a composite validates its parts: rsm_gather_settings names the nested struct at fault") {
  rsm_gather_settings<float> settings = default_rsm_gather_settings<float>(glm::ivec2(512));
  CHECK_FALSE(static_cast<bool>(validate(settings)));
  settings.irradiance.min_distance = 0.0f;
  CHECK(message(validate(settings)).find("irradiance_settings::min_distance") == 0);
  settings = default_rsm_gather_settings<float>(glm::ivec2(512));
  settings.slots.count = 0;
  CHECK(message(validate(settings)).find("elevation_slots::count must be in [1, 16]") == 0);
  settings = default_rsm_gather_settings<float>(glm::ivec2(512));
  settings.disk.samples = 0;
  CHECK(message(validate(settings)).find("disk_pattern_settings::samples") == 0);
  settings = default_rsm_gather_settings<float>(glm::ivec2(512));
  settings.rsm_size.y = 0;
  CHECK(message(validate(settings)).find("rsm_gather_settings::rsm_size") == 0);
}

TEST_CASE("a field described once is found by its member, also where a derived struct reuses it") {
  const field_description paths = describe_field(&radial_pattern_settings<float>::paths);
  CHECK(std::string(paths.name) == "paths");
  CHECK(paths.range.low == 1.0);
  CHECK(paths.range.high == 256.0);
  const field_description preset_paths = describe_field(&rsm_gather_preset<float>::paths);
  CHECK(std::string(preset_paths.help) == paths.help);
  const field_description preset_slots = describe_field(&rsm_gather_preset<float>::slots);
  CHECK(preset_slots.range.high == static_cast<double>(micro_linear_buffer_max_slots));
  CHECK(message(validate_field(&radial_pattern_settings<float>::paths, 0)) == "radial_pattern_settings::paths must be in [1, 256], got 0");
  CHECK(static_cast<bool>(validate_slot_count(0)));
  CHECK_FALSE(static_cast<bool>(validate_slot_count(micro_linear_buffer_max_slots)));
}
