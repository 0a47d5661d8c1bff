// std140 layouts of the settings structs, for engines that hand vplkit's settings to the GLSL
// twins in a uniform buffer (GL 3.1+ UBOs, Vulkan uniform buffers, WebGL2) instead of setting
// default-block uniforms by name (set_uniforms, vplkit/gl/settings_uniforms.hpp, GL 3.3).
//
// Everything comes from the structs' descriptions (vplkit/settings.hpp), computed at compile
// time: for a described struct S (the float instantiation, the GPU's)
//   std140_size<S>, std140_alignment<S>   its size and base alignment as a block member
//   std140_offsets<S>                     the offset of each described field, in the
//                                         description's order
//   std140_offset(&S::member)             the same, by member pointer (constexpr)
//   std140_bytes(settings)                the bytes of a buffer holding it, padding zeroed
//   write_std140(settings, destination)   the same, written at destination (e.g. into a larger
//                                         buffer at the struct's offset there)
//   std140_fields<S>()                    every basic value with its path, GLSL type and offset
//   std140_block<S>(block, member)        the GLSL text of a std140 uniform block holding it
//
// The GLSL side lays a struct out in the order of its declaration in shaders/lib, which is the
// order of the description's fields: the GL test (tests/frontend/gl/test_std140_gl.cpp) checks
// every offset here against GL_UNIFORM_OFFSET for every struct in glsl_twin_settings, the one
// list of the twins, which is here (a kernel header) so that std140 needs no GL header; the
// GLSL checks of vplkit/gl/settings_uniforms.hpp take it from here.
//
// The std140 rules applied (GL 4.6 core, section 7.6.2.2): a scalar (float, int, uint; a bool is
// a 4-byte int, 0 or 1) has size and alignment 4; vec2 / ivec2 size and alignment 8; vec3 size
// 12 and alignment 16 (a scalar may follow in its last 4 bytes); vec4 16; an array's elements
// have a stride of their size rounded up to 16, which is also the array's alignment (so
// elevation_slots::boundary_tangent, a float[15], takes 240 bytes, not 60); a struct's alignment
// is its largest member's rounded up to 16, and its size is rounded up to that alignment.
//
// GLM and the standard library only, like every kernel header.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
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
#include <vplkit/voxel_visibility.hpp>

namespace vplkit {

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
  else if constexpr (std::is_same_v<Value, glm::ivec3>) return "ivec3";
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
                  spot_light<float>, directional_light<float>, point_light<float>, lightwave_layout_settings<float>,
                  lightwave_cone_settings<float>, lightwave_shading_settings<float>,
                  temporal_settings<float>, voxel_march_settings<float>, voxel_grid_shape<float>>;

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

/// Calls visit(S{}) (a value-initialised settings struct, for its type) for every struct of a
/// settings_list, in its order; for_each_glsl_twin_type for glsl_twin_settings.
template <typename... Settings, typename Visitor>
void for_each_settings(settings_list<Settings...>, Visitor&& visit) {
  (visit(Settings{}), ...);
}
template <typename Visitor>
void for_each_glsl_twin_type(Visitor&& visit) {
  for_each_settings(glsl_twin_settings{}, visit);
}

namespace std140_detail {

constexpr std::size_t round_up(std::size_t value, std::size_t multiple) { return (value + multiple - 1) / multiple * multiple; }
constexpr std::size_t larger(std::size_t a, std::size_t b) { return a > b ? a : b; }

/// The value type a described_field points at.
template <typename Described>
struct field_value;
template <typename Owner, typename Value>
struct field_value<described_field<Owner, Value>> {
  using owner = Owner;
  using type = Value;
};

template <typename Settings>
using fields_tuple = std::remove_cv_t<decltype(settings_description<Settings>::fields())>;
template <typename Settings, std::size_t I>
using field_type = typename field_value<std::tuple_element_t<I, fields_tuple<Settings>>>::type;

template <typename Value, typename = void>
struct layout;

template <typename Settings>
struct struct_layout;

// Scalars: 4 bytes, 4-aligned. Only the 32-bit types GLSL has; a double instantiation of a
// settings struct has no std140 form here (the GPU side is float).
template <typename Value>
struct layout<Value, std::enable_if_t<std::is_same_v<Value, float> || std::is_same_v<Value, int> || std::is_same_v<Value, std::uint32_t> ||
                                      std::is_same_v<Value, bool>>> {
  static constexpr std::size_t alignment = 4;
  static constexpr std::size_t size = 4;
};

template <glm::length_t N, typename T, glm::qualifier Q>
struct layout<glm::vec<N, T, Q>> {
  static_assert(N >= 2 && N <= 4, "a GLSL vector has 2, 3 or 4 components");
  static constexpr std::size_t alignment = N == 2 ? 2 * layout<T>::size : 4 * layout<T>::size;
  static constexpr std::size_t size = static_cast<std::size_t>(N) * layout<T>::size;
};

template <typename Element, std::size_t N>
struct layout<Element[N]> {
  // Rule 4 (and 10 for arrays of structs): the element's alignment rounded up to a vec4's is the
  // array's alignment and its stride; the stride also covers the element's size.
  static constexpr std::size_t alignment = round_up(layout<Element>::alignment, 16);
  static constexpr std::size_t stride = round_up(layout<Element>::size, alignment);
  static constexpr std::size_t size = stride * N;
};

template <typename Settings>
struct layout<Settings, std::enable_if_t<is_described_v<Settings>>> {
  static constexpr std::size_t alignment = struct_layout<Settings>::alignment;
  static constexpr std::size_t size = struct_layout<Settings>::size;
};

template <typename Settings>
struct struct_layout {
  static constexpr std::size_t count = std::tuple_size_v<fields_tuple<Settings>>;
  static_assert(count > 0, "a described struct has fields");

  template <std::size_t... I>
  static constexpr std::array<std::size_t, count> compute_offsets(std::index_sequence<I...>) {
    static_assert((std::is_same_v<typename field_value<std::tuple_element_t<I, fields_tuple<Settings>>>::owner, Settings> && ...),
                  "every field of a description is a member of the described struct");
    std::array<std::size_t, count> placed{};
    std::size_t at = 0;
    ((at = round_up(at, layout<field_type<Settings, I>>::alignment), placed[I] = at, at += layout<field_type<Settings, I>>::size), ...);
    return placed;
  }
  template <std::size_t... I>
  static constexpr std::size_t compute_alignment(std::index_sequence<I...>) {
    std::size_t largest = 0;
    ((largest = larger(largest, layout<field_type<Settings, I>>::alignment)), ...);
    return round_up(largest, 16);  // rule 9
  }

  static constexpr std::array<std::size_t, count> offsets = compute_offsets(std::make_index_sequence<count>{});
  static constexpr std::size_t alignment = compute_alignment(std::make_index_sequence<count>{});
  static constexpr std::size_t size = round_up(offsets[count - 1] + layout<field_type<Settings, count - 1>>::size, alignment);
};

template <typename Value>
void write_value(const Value& value, unsigned char* at) {
  if constexpr (is_described_v<Value>) {
    std::size_t i = 0;
    for_each_field(value, [&](const field_description&, const auto& part) { write_value(part, at + struct_layout<Value>::offsets[i++]); });
  } else if constexpr (std::is_array_v<Value>) {
    for (std::size_t i = 0; i < std::extent_v<Value>; ++i) write_value(value[i], at + i * layout<Value>::stride);
  } else if constexpr (std::is_same_v<Value, bool>) {
    const std::uint32_t word = value ? 1u : 0u;  // a GLSL bool in a block is a 4-byte word, true when not 0
    std::memcpy(at, &word, sizeof word);
  } else if constexpr (std::is_arithmetic_v<Value>) {
    static_assert(sizeof(Value) == 4, "std140 scalars are 4 bytes");
    std::memcpy(at, &value, sizeof value);
  } else {
    for (glm::length_t c = 0; c < Value::length(); ++c) write_value(value[c], at + static_cast<std::size_t>(c) * 4);
  }
}

}  // namespace std140_detail

/// The size in bytes of a settings struct as a std140 block member (and of std140_bytes).
template <typename Settings>
inline constexpr std::size_t std140_size = std140_detail::struct_layout<Settings>::size;

/// Its base alignment: where it may start in a block (a multiple of 16).
template <typename Settings>
inline constexpr std::size_t std140_alignment = std140_detail::struct_layout<Settings>::alignment;

/// The offset of each described field from the struct's start, in the description's order.
template <typename Settings>
inline constexpr std::array<std::size_t, std140_detail::struct_layout<Settings>::count> std140_offsets =
    std140_detail::struct_layout<Settings>::offsets;

/// The offset of one field of a described struct, by member pointer: std140_offset(&S::member).
/// Throws std::invalid_argument (a compile error in a constant expression) for a member the
/// description does not list.
template <typename Owner, typename Value>
constexpr std::size_t std140_offset(Value Owner::*member) {
  std::size_t found = 0;
  bool matched = false;
  std::size_t i = 0;
  std::apply(
      [&](const auto&... described) {
        const auto match = [&](const auto& one) {
          if constexpr (std::is_same_v<std::decay_t<decltype(one.member)>, Value Owner::*>) {
            if (!matched && one.member == member) {
              found = std140_offsets<Owner>[i];
              matched = true;
            }
          }
          ++i;
        };
        (match(described), ...);
      },
      settings_description<Owner>::fields());
  if (!matched) throw std::invalid_argument("std140_offset: the member is not a described field of the struct");
  return found;
}

/// Writes `settings` in std140 at `destination`, which holds std140_size<Settings> bytes from
/// there; the padding between fields is left as it is.
template <typename Settings>
void write_std140(const Settings& settings, void* destination) {
  static_assert(is_described_v<Settings>, "write_std140 takes a described settings struct");
  std140_detail::write_value(settings, static_cast<unsigned char*>(destination));
}

/// `settings` in std140, padding zeroed: the contents of a uniform buffer that holds it alone
/// (glBufferData(GL_UNIFORM_BUFFER, bytes.size(), bytes.data(), ...)).
template <typename Settings>
std::array<std::byte, std140_size<Settings>> std140_bytes(const Settings& settings) {
  std::array<std::byte, std140_size<Settings>> bytes{};
  write_std140(settings, bytes.data());
  return bytes;
}

/// One basic value of a struct in std140: a float, vector, int, uint or bool, or an array of
/// them (arrays of structs are listed element by element, "a[2].b").
struct std140_field {
  std::string path;            ///< from the struct: "min_distance", "slots.boundary_tangent"
  std::string glsl_type;       ///< "float", "ivec2", ...
  std::size_t offset = 0;      ///< from the struct's start
  std::size_t array_size = 0;  ///< elements; 0: not an array
  std::size_t array_stride = 0;
};

namespace std140_detail {

template <typename Value>
void list_fields(const std::string& path, std::size_t offset, std::vector<std140_field>& fields) {
  if constexpr (is_described_v<Value>) {
    Value settings{};
    std::size_t i = 0;
    for_each_field(settings, [&](const field_description& field, const auto& part) {
      using part_type = std::remove_cv_t<std::remove_reference_t<decltype(part)>>;
      list_fields<part_type>(path.empty() ? field.name : path + "." + field.name, offset + struct_layout<Value>::offsets[i++], fields);
    });
  } else if constexpr (std::is_array_v<Value> && is_described_v<std::remove_extent_t<Value>>) {
    for (std::size_t i = 0; i < std::extent_v<Value>; ++i)
      list_fields<std::remove_extent_t<Value>>(path + "[" + std::to_string(i) + "]", offset + i * layout<Value>::stride, fields);
  } else if constexpr (std::is_array_v<Value>) {
    fields.push_back({path, glsl_type_name<Value>(), offset, std::extent_v<Value>, layout<Value>::stride});
  } else {
    fields.push_back({path, glsl_type_name<Value>(), offset, 0, 0});
  }
}

}  // namespace std140_detail

/// Every basic value of a settings struct with its std140 offset, nested structs flattened
/// ("radial.seed"), in the order of the layout.
template <typename Settings>
std::vector<std140_field> std140_fields() {
  std::vector<std140_field> fields;
  std140_detail::list_fields<Settings>("", 0, fields);
  return fields;
}

/// The GLSL declaration of a std140 uniform block that holds one `member` of the settings
/// struct's GLSL twin, with its size and every field's offset as comments:
///   layout(std140) uniform <block> {
///     <twin> <member>;
///   };
/// The struct itself comes from the lib file that declares it (docs/glsl-twins.md); a block
/// without an instance name makes `member` a global name, as a default-block uniform would be.
/// Bind the buffer with glUniformBlockBinding (GL 3.3) or add `binding = N` to the layout (GLSL
/// 4.20+, Vulkan with its set as well).
template <typename Settings>
std::string std140_block(const std::string& block, const std::string& member) {
  static_assert(settings_description<Settings>::glsl_twin, "this settings struct has no GLSL twin");
  const std::string name = settings_description<Settings>::name;
  // Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive) on a literal + std::string chain here.
  std::string text = "// ";
  text.append(name).append(" in std140: ").append(std::to_string(std140_size<Settings>)).append(" bytes (vplkit/std140.hpp: std140_bytes)\n");
  for (const std140_field& field : std140_fields<Settings>()) {
    text.append("//   offset ").append(std::to_string(field.offset)).append(": ").append(field.glsl_type).append(" ");
    text.append(member).append(".").append(field.path);
    if (field.array_size) text.append("[").append(std::to_string(field.array_size)).append("], stride ").append(std::to_string(field.array_stride));
    text.append("\n");
  }
  text.append("layout(std140) uniform ").append(block).append(" {\n  ").append(name).append(" ").append(member).append(";\n};\n");
  return text;
}

}  // namespace vplkit
