// The one way a kernel settings struct reaches its GLSL twin, a uniform struct of the same name
// and fields: set_uniforms walks the struct's description (vplkit/settings.hpp) and sets every
// field by name, nested settings through theirs. Every program that includes a lib file fills
// its twins from here, and so do users' own shaders that take vplkit's settings as uniforms
// (installed with vplkit::parity). The same descriptions list each twin's fields with their GLSL
// types (glsl_twins), and link_program checks every uniform struct a program declares against
// them both ways: a described field the GLSL struct lacks, or a GLSL field no description sets
// (it would silently read 0), is an error when the program is built.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

#include <glm/glm.hpp>

#include <vplkit/bilateral.hpp>
#include <vplkit/direct_light.hpp>
#include <vplkit/irradiance.hpp>
#include <vplkit/lightwave.hpp>
#include <vplkit/micro_linear_buffer.hpp>
#include <vplkit/rsm_gather.hpp>
#include <vplkit/rsm_packing.hpp>
#include <vplkit/rsm_pattern.hpp>
#include <vplkit/settings.hpp>
#include <vplkit/shadow.hpp>
#include <vplkit/temporal_accumulation.hpp>

#include <vplkit/gl/program.hpp>
#include <vplkit/gl/uniform_declarations.hpp>

namespace vplkit {

/// A GLSL twin as its C++ description makes it: the struct's name, and per field its name, its
/// GLSL type ("float", "vec3", a nested twin's name) and whether it is an array.
struct glsl_twin {
  struct field {
    std::string name;
    std::string type;
    bool array = false;
  };
  std::string name;
  std::vector<field> fields;
};

/// The GLSL type name of a described field's C++ type.
template <typename Value>
std::string glsl_type_name() {
  if constexpr (std::is_array_v<Value>) return glsl_type_name<std::remove_extent_t<Value>>();
  else if constexpr (is_described_v<Value>) return settings_description<Value>::name;
  else if constexpr (std::is_same_v<Value, float>) return "float";
  else if constexpr (std::is_same_v<Value, int>) return "int";
  else if constexpr (std::is_same_v<Value, bool>) return "bool";
  else if constexpr (std::is_same_v<Value, std::uint32_t>) return "uint";
  else if constexpr (std::is_same_v<Value, glm::vec2>) return "vec2";
  else if constexpr (std::is_same_v<Value, glm::vec3>) return "vec3";
  else if constexpr (std::is_same_v<Value, glm::vec4>) return "vec4";
  else if constexpr (std::is_same_v<Value, glm::ivec2>) return "ivec2";
  else static_assert(std::is_void_v<Value>, "a field type without a GLSL twin type");
}

/// A list of settings types.
template <typename... Settings>
struct settings_list {
  static constexpr std::size_t size = sizeof...(Settings);
  template <typename S>
  static constexpr bool contains = (std::is_same_v<S, Settings> || ...);
};

/// Every kernel settings struct with a GLSL twin, in the float instantiation (the GPU's): the one
/// list glsl_twins() is made from, and the only types set_uniforms and glsl_twin_of take. The
/// static_assert below ties it to the descriptions: every type listed has a description that says
/// glsl_twin, every described struct a listed one nests (rsm_gather_settings' irradiance, radial,
/// disk, slots) is listed too, and no two share a GLSL name.
using glsl_twin_settings =
    settings_list<irradiance_settings<float>, radial_pattern_constants<float>, disk_pattern_settings<float>, elevation_slots<float>,
                  rsm_gather_settings<float>, rsm_unprojection<float>, shadow_density_settings<float>, bilateral_settings<float>,
                  spot_light<float>, directional_light<float>, lightwave_layout_settings<float>, lightwave_shading_settings<float>,
                  temporal_settings<float>>;

namespace detail {

template <typename Described>
struct described_value;
template <typename Owner, typename Value>
struct described_value<described_field<Owner, Value>> {
  using type = Value;
};

// A field of a listed twin: a nested settings struct (or an array of them) must be a listed twin.
template <typename List, typename Value>
constexpr bool nested_twin_listed() {
  using element = std::remove_all_extents_t<Value>;
  if constexpr (is_described_v<element>) return settings_description<element>::glsl_twin && List::template contains<element>;
  else return true;
}

template <typename List, typename Fields>
struct fields_listed;
template <typename List, typename... Fields>
struct fields_listed<List, std::tuple<Fields...>> {
  static constexpr bool value = (nested_twin_listed<List, typename described_value<Fields>::type>() && ...);
};

constexpr bool same_name(const char* a, const char* b) {
  for (; *a != '\0' && *a == *b; ++a, ++b) {
  }
  return *a == *b;
}

template <typename List>
struct twins_consistent;
template <typename... Settings>
struct twins_consistent<settings_list<Settings...>> {
  template <typename S>
  static constexpr int named_like() {
    return ((same_name(settings_description<S>::name, settings_description<Settings>::name) ? 1 : 0) + ...);
  }
  static constexpr bool described = (settings_description<Settings>::glsl_twin && ...);
  static constexpr bool nested_listed =
      (fields_listed<settings_list<Settings...>, decltype(settings_description<Settings>::fields())>::value && ...);
  static constexpr bool names_distinct = ((named_like<Settings>() == 1) && ...);
};

}  // namespace detail

static_assert(detail::twins_consistent<glsl_twin_settings>::described, "glsl_twin_settings lists a struct whose description has glsl_twin = false");
static_assert(detail::twins_consistent<glsl_twin_settings>::nested_listed,
              "a settings struct nested in a listed GLSL twin is not in glsl_twin_settings (or its description has glsl_twin = false)");
static_assert(detail::twins_consistent<glsl_twin_settings>::names_distinct, "two structs in glsl_twin_settings have the same GLSL name");

/// The twin of a described settings struct.
template <typename Settings>
glsl_twin glsl_twin_of() {
  static_assert(settings_description<Settings>::glsl_twin, "this settings struct has no GLSL twin");
  static_assert(glsl_twin_settings::contains<Settings>, "a GLSL twin missing from glsl_twin_settings: add it there");
  glsl_twin twin{settings_description<Settings>::name, {}};
  Settings settings{};
  for_each_field(settings, [&](const field_description& field, const auto& value) {
    using value_type = std::remove_cv_t<std::remove_reference_t<decltype(value)>>;
    twin.fields.push_back({field.name, glsl_type_name<value_type>(), std::is_array_v<value_type>});
  });
  return twin;
}

/// Every kernel settings struct with a GLSL twin (glsl_twin_settings), in that order.
const std::vector<glsl_twin>& glsl_twins();

/// Throws vplkit::error naming the program, the struct and the field when a uniform struct that
/// `declarations` holds has the name of a twin but not exactly its fields (names, types, arrays),
/// for every struct a uniform uses, nested ones included. link_program calls it.
void check_glsl_twins(const uniform_declarations& declarations, const std::string& program_name);

namespace detail {

template <typename Value>
void set_uniform_value(const program& target, const std::string& name, const Value& value) {
  if constexpr (is_described_v<Value>) {
    for_each_field(value, [&](const field_description& field, const auto& part) { set_uniform_value(target, name + "." + field.name, part); });
  } else if constexpr (std::is_array_v<Value>) {
    for (std::size_t i = 0; i < std::extent_v<Value>; ++i) set_uniform_value(target, name + "[" + std::to_string(i) + "]", value[i]);
  } else if constexpr (std::is_same_v<Value, std::uint32_t>) {
    target.set(name, static_cast<unsigned>(value));
  } else if constexpr (std::is_same_v<Value, bool>) {
    target.set(name, value ? 1 : 0);  // a GLSL bool uniform is set as an int
  } else {
    target.set(name, value);
  }
}

}  // namespace detail

/// Sets every field of `settings` into the uniform `name`, a uniform of its GLSL twin's type.
template <typename Settings>
void set_uniforms(const program& target, const std::string& name, const Settings& settings) {
  static_assert(settings_description<Settings>::glsl_twin, "this settings struct has no GLSL twin");
  static_assert(glsl_twin_settings::contains<Settings>, "a GLSL twin missing from glsl_twin_settings: add it there");
  detail::set_uniform_value(target, name, settings);
}

}  // namespace vplkit
