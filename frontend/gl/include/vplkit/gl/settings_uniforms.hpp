// How a kernel settings struct reaches its GLSL twin as a default-block uniform struct of the
// same name and fields (the GL 3.3 convenience; a uniform buffer takes the bytes of
// vplkit/std140.hpp instead, through program::set_uniform_block): set_uniforms walks the
// struct's description (vplkit/settings.hpp) and sets every field by name, nested settings
// through theirs. Every program that includes a lib file fills its twins from here, and so do
// users' own shaders that take vplkit's settings as uniforms (installed with vplkit::parity).
// The same descriptions list each twin's fields with their GLSL types (glsl_twins, made from
// glsl_twin_settings in vplkit/std140.hpp), and link_program checks every uniform struct a
// program declares against them both ways, members of uniform blocks included: a described
// field the GLSL struct lacks, or a GLSL field no description sets (it would silently read 0),
// is an error when the program is built.
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
#include <vplkit/std140.hpp>
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
/// for every struct a uniform or a uniform block member uses, nested ones included. link_program
/// calls it.
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
