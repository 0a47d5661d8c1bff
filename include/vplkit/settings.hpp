// Descriptions of the kernels' settings structs: for every field its name (the same in the C++
// struct and in its GLSL twin), the values it may take, its unit and one line on what it does,
// written once, next to the struct. From a description come
// - validate(settings): every field in its range (non-finite numbers refused), nested settings
//   validated through their own descriptions, then the rules that join several fields;
// - the frontend's upload into the GLSL twin and its check, when a program is built, that the
//   GLSL struct declares exactly the described fields (vplkit/gl/settings_uniforms.hpp);
// - the frontend's options, viewer controls and sweep axes for the fields a user sets, which
//   take the range, unit and help from here (frontend/core/setting.hpp).
//
// A description is a specialisation, next to the struct, of settings_description<S> with
//   static constexpr const char* name;        the struct's name, and its GLSL twin's
//   static constexpr bool glsl_twin;          whether shaders/lib declares a struct of that name
//   static constexpr auto fields();           std::make_tuple(schema::field(&S::member, "member", range, unit, help), ...)
//   static setting_problem rules(const S&);   what no single range says (schema::no_rules() when nothing)
// GLM and the standard library only, like every kernel header.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <tuple>
#include <type_traits>

#include <glm/glm.hpp>

namespace vplkit {

/// The values a number may take: from low to high, either end open; an infinite end is no bound.
/// Every number must be finite as well.
struct setting_range {
  double low = -std::numeric_limits<double>::infinity();
  double high = std::numeric_limits<double>::infinity();
  bool low_open = false;
  bool high_open = false;

  constexpr bool contains(double value) const {
    return value - value == 0.0 && (low_open ? value > low : value >= low) && (high_open ? value < high : value <= high);
  }
};

/// One field of a settings struct.
struct field_description {
  const char* name = "";   ///< the C++ field and the GLSL twin's field
  setting_range range{};   ///< of the number, or of each component or element
  const char* unit = "";   ///< "scene units", "RSM texels", "" for a count
  const char* help = "";   ///< one line
};

template <typename Owner, typename Value>
struct described_field {
  Value Owner::*member;
  field_description description;
};

/// The first problem validate() found, as a sentence naming the struct and the field; empty
/// (false) when the settings are usable. A value, so that several can be held at once.
class setting_problem {
 public:
  setting_problem() = default;
  explicit setting_problem(const char* text) { append(text); }
  explicit operator bool() const { return text_[0] != '\0'; }
  /// "" when there is no problem.
  const char* message() const { return text_; }

  setting_problem& append(const char* text) {
    for (; text && *text && length_ + 1 < capacity; ++text) text_[length_++] = *text;
    text_[length_] = '\0';
    return *this;
  }
  setting_problem& append(double value) {
    char number[32];
    std::snprintf(number, sizeof number, "%g", value);
    return append(number);
  }

 private:
  static constexpr std::size_t capacity = 256;
  char text_[capacity] = {};
  std::size_t length_ = 0;
};

/// Appends "in [0, 1]", "> 0", "in (0, 2]" to `problem`.
inline setting_problem& append_range(setting_problem& problem, const setting_range& range) {
  const bool has_low = range.low > -std::numeric_limits<double>::infinity();
  const bool has_high = range.high < std::numeric_limits<double>::infinity();
  if (has_low && has_high) {
    problem.append("in ").append(range.low_open ? "(" : "[").append(range.low).append(", ").append(range.high).append(range.high_open ? ")" : "]");
  } else if (has_low) {
    problem.append(range.low_open ? "> " : ">= ").append(range.low);
  } else if (has_high) {
    problem.append(range.high_open ? "< " : "<= ").append(range.high);
  } else {
    problem.append("finite");
  }
  return problem;
}

/// The helpers a description is written with, in their own namespace: names as common as `field`
/// or `above` would otherwise collide with a user's own under `using namespace vplkit` (a user's
/// `struct field` became ambiguous). Descriptions call them qualified: schema::field(...). (Not
/// `describe`: vplkit and its users have functions of that name, which a namespace would hide.)
namespace schema {

constexpr setting_range closed_range(double low, double high) { return {low, high, false, false}; }
/// (low, high]
constexpr setting_range open_closed_range(double low, double high) { return {low, high, true, false}; }
/// [low, high)
constexpr setting_range closed_open_range(double low, double high) { return {low, high, false, true}; }
/// > low
constexpr setting_range above(double low) { return {low, std::numeric_limits<double>::infinity(), true, false}; }
/// >= low
constexpr setting_range at_least(double low) { return {low, std::numeric_limits<double>::infinity(), false, false}; }
/// Any finite number.
constexpr setting_range any_finite() { return {}; }

template <typename Owner, typename Value>
constexpr described_field<Owner, Value> field(Value Owner::*member, const char* name, setting_range range, const char* unit, const char* help) {
  return {member, {name, range, unit, help}};
}

/// A field described elsewhere (a derived struct's field that is a setting's value as it is).
template <typename Owner, typename Value>
constexpr described_field<Owner, Value> field(Value Owner::*member, const field_description& description) {
  return {member, description};
}

/// For a description without rules.
template <typename Settings>
setting_problem no_rules(const Settings&) {
  return {};
}

}  // namespace schema

/// Specialised next to each settings struct (see the top of this file).
template <typename Settings>
struct settings_description;

template <typename Settings, typename = void>
struct is_described : std::false_type {};
template <typename Settings>
struct is_described<Settings, std::void_t<decltype(settings_description<Settings>::fields())>> : std::true_type {};
template <typename Settings>
inline constexpr bool is_described_v = is_described<std::remove_cv_t<Settings>>::value;

/// Calls visit(const field_description&, value&) for every field of `settings`, in the
/// description's order (const or not, as `settings` is).
template <typename Settings, typename Visitor>
void for_each_field(Settings& settings, Visitor&& visit) {
  using plain = std::remove_cv_t<Settings>;
  std::apply([&](const auto&... described) { (visit(described.description, settings.*(described.member)), ...); },
             settings_description<plain>::fields());
}

/// The description of one field, found by its member pointer.
template <typename Owner, typename Value>
constexpr field_description describe_field(Value Owner::*member) {
  field_description found{};
  std::apply(
      [&](const auto&... described) {
        const auto match = [&](const auto& one) {
          if constexpr (std::is_same_v<std::decay_t<decltype(one.member)>, Value Owner::*>)
            if (one.member == member) found = one.description;
        };
        (match(described), ...);
      },
      settings_description<Owner>::fields());
  return found;
}

template <typename Settings, std::enable_if_t<is_described_v<Settings>, int> = 0>
setting_problem validate(const Settings& settings);

namespace detail {

template <typename T>
inline constexpr bool is_glm_vector = false;
template <glm::length_t N, typename T, glm::qualifier Q>
inline constexpr bool is_glm_vector<glm::vec<N, T, Q>> = true;

inline setting_problem out_of_range(const char* owner, const field_description& field, double value) {
  setting_problem problem;
  problem.append(owner).append("::").append(field.name).append(" must be ");
  append_range(problem, field.range);
  if (field.unit[0] != '\0') problem.append(" (").append(field.unit).append(")");
  return problem.append(", got ").append(value);
}

template <typename Value>
setting_problem check_value(const char* owner, const field_description& field, const Value& value) {
  if constexpr (is_described_v<Value>) {
    return validate(value);
  } else if constexpr (std::is_array_v<Value>) {
    for (const auto& element : value)
      if (setting_problem problem = check_value(owner, field, element)) return problem;
    return {};
  } else if constexpr (is_glm_vector<Value>) {
    for (glm::length_t i = 0; i < Value::length(); ++i)
      if (setting_problem problem = check_value(owner, field, value[i])) return problem;
    return {};
  } else {
    static_assert(std::is_arithmetic_v<Value>, "a described field is a number, a GLM vector, an array of them or a described struct");
    const double number = static_cast<double>(value);
    if (!field.range.contains(number)) return out_of_range(owner, field, number);
    return {};
  }
}

}  // namespace detail

/// Every field in its range (nested settings by their own descriptions), then the description's
/// rules. The first problem, or an empty one.
template <typename Settings, std::enable_if_t<is_described_v<Settings>, int>>
setting_problem validate(const Settings& settings) {
  using description = settings_description<Settings>;
  setting_problem problem;
  for_each_field(settings, [&](const field_description& field, const auto& value) {
    if (!problem) problem = detail::check_value(description::name, field, value);
  });
  if (!problem) problem = description::rules(settings);
  return problem;
}

/// The problem of one value of a field alone (its range), e.g. for a value a user typed.
template <typename Owner, typename Value>
setting_problem validate_field(Value Owner::*member, const Value& value) {
  return detail::check_value(settings_description<Owner>::name, describe_field(member), value);
}

}  // namespace vplkit
