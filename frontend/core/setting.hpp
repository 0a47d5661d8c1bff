// One description per setting of a technique family: its name (the command-line option's,
// without the dashes), the field it reads and writes (a member path: path_of(&S::radial,
// &radial_pattern_settings<float>::paths); its default is the struct's initialiser), type, range,
// unit, one line of help, which techniques read it, the GLSL uniforms and defines it feeds, and
// whether a change needs a new pipeline (defines, builds). A family's settings struct has one
// table of these, next to the struct (rsm_settings_table() in rsm_settings.hpp, ...), and from
// that table come
// - the command-line options and their scoping (frontend/cli/technique_options),
// - validation and its messages (check_settings, each family's validate()),
// - the viewer's controls, with the same ranges and refusals (frontend/viewer),
// - which change a pipeline applies in place and which needs a new one (rebuilding_changes,
//   each family's pipeline::apply_settings),
// - the sweep's axes (frontend/sweep),
// - the JSON dump of the settings in effect (settings_json).
// A setting that is a kernel struct's field takes its range, unit and help from the kernel's
// description (vplkit/settings.hpp): nothing is written twice. Adding a setting is one entry in
// its family's table (docs/architecture.md says how).
#pragma once

#include <algorithm>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include <vplkit/settings.hpp>

namespace vplkit {

enum class setting_type {
  integer,  ///< a whole number in a range, or one of `allowed`
  real,     ///< a finite number in a range
  choice,   ///< one of `choices`
  size,     ///< N or WxH, each side in the range
  point,    ///< x,y,z, each coordinate in the range
  text,     ///< any non-empty text (a name or a file)
};

/// A setting without its struct: what the command line, the viewer and the sweep read.
struct setting_info {
  std::string name;                  ///< "radius": the option --radius, the sweep axis radius
  setting_type type = setting_type::real;
  setting_range range{};             ///< integer, real, size (each side), point (each coordinate)
  std::vector<int> allowed;          ///< integer: only these values; empty: the whole range
  std::vector<std::string> choices;  ///< choice
  std::string unit;                  ///< "of the RSM side", "texels", "" for a count
  std::string help;                  ///< one line
  std::string glsl;                  ///< the uniforms it feeds, "file: name; ...", "" when none directly (setting::feeds)
  std::string readers;               ///< who reads it, said next to their names: "the radial pattern"
  bool live = true;                  ///< the viewer offers a control (not for the frame size)
  bool in_effect = true;             ///< among the settings in effect (false for another unit of one)
  bool applies_first = false;        ///< a preset: applied before the other settings, which override it
  std::string excludes;              ///< a setting that cannot be given together with this one
  /// Why a change of it needs a new pipeline, "" for a setting that feeds only uniforms (applied
  /// in place: pipeline::apply_settings): the defines it sets (setting::defines) and what a
  /// pipeline builds from it (setting::builds: a target's size, a grid, a mesh), "; "-separated.
  std::string rebuilds;
  /// The pipeline's own state once made, moved by the pipeline's interface rather than its
  /// settings (final gathering's object position: pipeline::set_object_position), so that
  /// apply_settings keeps the pipeline's: neither applied nor a reason to rebuild.
  bool pose = false;

  /// "" when `text` is a value of this setting, else why not, e.g. "must be a whole number in
  /// [1, 256], got '0'".
  std::string check(const std::string& text) const;
  /// The values it takes, for help texts: "[1, 256]", "(0, 2] of the RSM side", "1, 2, 4 or 8".
  std::string values() const;
  /// The value as a number for a slider or a plot's axis; nullopt for the other types.
  std::optional<double> number(const std::string& text) const;
};

/// "in [1, 256]", "> 0", "in (0, 2]": numbers as ostream writes them (1e+07).
std::string describe_range(const setting_range& range);
/// A float or double as the shortest text that reads back to the same value.
std::string format_real(double value);
std::string format_real(float value);
/// The whole text as a number; nullopt for anything else (trailing characters included).
std::optional<double> parse_real(std::string_view text);
std::optional<long long> parse_integer(std::string_view text);
/// "N" or "WxH" into (width, height); nullopt when it is neither.
std::optional<std::pair<int, int>> parse_extent(std::string_view text);
/// "x,y,z" (spaces allowed around the numbers).
std::optional<std::vector<double>> parse_point(std::string_view text);
/// A value as a message shows it: quoted, and cut after 60 characters.
std::string quote_for_message(std::string_view text);

namespace detail {

/// "radial.paths": the described names of a member path, each member of the previous one's type.
template <typename Owner, typename Value>
std::string member_path_name(Value Owner::*member) {
  return describe_field(member).name;
}
template <typename Owner, typename Value, typename Next, typename... Rest>
std::string member_path_name(Value Owner::*member, Next next, Rest... rest) {
  static_assert(std::is_member_object_pointer_v<Next>, "a member path is member object pointers");
  return std::string(describe_field(member).name) + "." + member_path_name(next, rest...);
}

/// The member at the end of a path, each step checked by the compiler (`value.*member` of the
/// previous step's type); const or not, as `value` is.
template <typename Value>
Value& member_at(Value& value) {
  return value;
}
template <typename Value, typename Member, typename... Rest>
decltype(auto) member_at(Value& value, Member member, Rest... rest) {
  return member_at(value.*member, rest...);
}

/// A value as a setting's text, and back (text that setting_info::check accepted).
template <typename Value>
std::string value_text(const Value& value) {
  if constexpr (std::is_integral_v<Value>) return std::to_string(value);
  else return format_real(value);
}
template <typename Value>
Value text_value(const std::string& text) {
  if constexpr (std::is_integral_v<Value>) return static_cast<Value>(*parse_integer(text));
  else return static_cast<Value>(*parse_real(text));
}

/// A fed member as a number: itself, or a GLM vector's first component.
template <typename Value>
double as_number(const Value& value) {
  if constexpr (std::is_arithmetic_v<Value>) return static_cast<double>(value);
  else return static_cast<double>(value[0]);
}

}  // namespace detail

/// A field of a settings struct as a chain of member pointers, each a member of the previous
/// one's type: path_of(&rsm_pipeline_settings::radial, &radial_pattern_settings<float>::paths).
/// A table entry reads and writes its field through it (the compiler checks every step), its
/// default is the struct's initialiser, and a kernel struct's field gives its description.
template <typename... Members>
struct member_path {
  static_assert(sizeof...(Members) > 0 && (std::is_member_object_pointer_v<Members> && ...), "a member path is member object pointers");
  std::tuple<Members...> members;

  template <typename Value>
  decltype(auto) operator()(Value& value) const {
    return std::apply([&value](auto... member) -> decltype(auto) { return detail::member_at(value, member...); }, members);
  }
  /// The last member's description, from its struct's settings_description (vplkit/settings.hpp).
  field_description description() const { return describe_field(std::get<sizeof...(Members) - 1>(members)); }
};
template <typename... Members>
member_path<Members...> path_of(Members... members) {
  return {{members...}};
}
/// The type of the field at the end of `Path` from a `Settings`.
template <typename Settings, typename Path>
using path_value_t = std::decay_t<decltype(std::declval<const Path&>()(std::declval<Settings&>()))>;

/// A setting of `Settings` for the techniques `Technique` names (the family's technique table).
template <typename Settings, typename Technique>
struct setting : setting_info {
  std::function<bool(const Technique&)> reads;            ///< null: every technique of the family
  std::function<std::string(const Settings&)> get;        ///< the value, in a form check() accepts
  std::function<void(Settings&, const std::string&)> set;  ///< a value check() accepted
  std::function<std::string(const Settings&)> build_key;  ///< what a build reads of it (builds); null: get()

  setting& read_by(std::function<bool(const Technique&)> predicate, std::string who) {
    reads = std::move(predicate);
    readers = std::move(who);
    return *this;
  }
  /// The value of each kernel-struct member the setting feeds (feeds(file, root, derive, path...)),
  /// as the family derives it from `Settings` for the frame: a test sets the setting and checks
  /// that every one moves (tests/frontend/techniques/test_registry.cpp).
  std::vector<std::function<double(const Settings&)>> fed_members;

  /// A uniform or define the setting feeds that is no member of a kernel struct: "file: name"
  /// (a plain uniform such as "rsm.frag: rsm_size", or a define "post.frag: VPLKIT_SEPARABLE"),
  /// checked against the shipped shaders by the registry's test.
  setting& feeds(std::string uniform) {
    glsl += (glsl.empty() ? "" : "; ") + uniform;
    return *this;
  }
  /// The member `path` of the kernel struct that `derive` (the family's derivation: settings ->
  /// the struct the frame uploads as uniform `root` of `file`) returns: a chain of member
  /// pointers, `&rsm_gather_settings<float>::radial, &radial_pattern_constants<float>::paths`.
  /// The compiler checks the chain; the GLSL name ("gather.frag: settings.radial.paths") comes
  /// from the structs' descriptions, the names the link-time check holds to the shader's.
  template <typename Derive, typename... Members>
  setting& feeds(const char* file, const char* root, Derive derive, Members... path) {
    static_assert(sizeof...(Members) > 0, "feeds: a member path of at least one member");
    feeds(std::string(file) + ": " + root + "." + detail::member_path_name(path...));
    fed_members.push_back([derive, path...](const Settings& settings) {
      const auto derived = derive(settings);
      return detail::as_number(detail::member_at(derived, path...));
    });
    return *this;
  }
  setting& allowing(std::vector<int> values) {
    allowed = std::move(values);
    return *this;
  }
  setting& within(setting_range values) {
    range = values;
    return *this;
  }
  setting& not_live() {
    live = false;
    return *this;
  }

  /// A define of a shader the setting sets, "file: NAME" (post.frag: VPLKIT_SEPARABLE): checked
  /// against the shader like a uniform, and a change needs a new pipeline (another program).
  setting& defines(const std::string& define) {
    feeds(define);
    rebuilds += (rebuilds.empty() ? "" : "; ") + ("the define " + define);
    return *this;
  }
  /// Something a pipeline builds from the setting when it is made ("the RSM's target", "the
  /// voxel grid"): a change needs a new pipeline. `key`, when given, is what of the settings the
  /// build reads (a size rounded from the setting, or the setting only where the technique reads
  /// it): a change that keeps the key is applied in place.
  setting& builds(const std::string& what, std::function<std::string(const Settings&)> key = nullptr) {
    rebuilds += (rebuilds.empty() ? "" : "; ") + what;
    if (key) build_key = std::move(key);
    return *this;
  }
  setting& kept_by_pipeline() {
    pose = true;
    return *this;
  }
  /// Whether going from `from` to `to` changes what a pipeline builds from this setting.
  bool needs_rebuild(const Settings& from, const Settings& to) const {
    if (rebuilds.empty()) return false;
    return build_key ? build_key(from) != build_key(to) : get(from) != get(to);
  }
  /// Also writes its value to `path` (a value two kernel structs share: the patterns' seed).
  template <typename... Members>
  setting& sets_also(member_path<Members...> path) {
    set = [first = std::move(set), path](Settings& s, const std::string& text) {
      first(s, text);
      path(s) = detail::text_value<path_value_t<Settings, member_path<Members...>>>(text);
    };
    return *this;
  }

  /// A number field; integral fields are integers, floating ones reals.
  template <typename... Members>
  static setting number(std::string name, member_path<Members...> path, setting_range range, std::string unit, std::string help) {
    using value_type = path_value_t<Settings, member_path<Members...>>;
    static_assert(std::is_arithmetic_v<value_type>, "setting::number needs a number field");
    return described(std::move(name), std::is_integral_v<value_type> ? setting_type::integer : setting_type::real, range, std::move(unit), std::move(help),
                     [path](const Settings& s) { return detail::value_text(path(s)); },
                     [path](Settings& s, const std::string& text) { path(s) = detail::text_value<value_type>(text); });
  }
  /// A number field with a kernel struct's description (range, unit and help).
  template <typename... Members>
  static setting number(std::string name, member_path<Members...> path, const field_description& kernel_field) {
    return number(std::move(name), path, kernel_field.range, kernel_field.unit, kernel_field.help);
  }
  /// A number field that is a kernel struct's field: its description is the field's own.
  template <typename... Members>
  static setting number(std::string name, member_path<Members...> path) {
    return number(std::move(name), path, path.description());
  }

  /// A field of one of `options` (an enum or a string), shown by their names.
  template <typename... Members>
  static setting choice(std::string name, member_path<Members...> path,
                        std::vector<std::pair<std::string, path_value_t<Settings, member_path<Members...>>>> options, std::string help) {
    setting entry = described(
        std::move(name), setting_type::choice, setting_range{}, "", std::move(help),
        [path, options](const Settings& s) {
          for (const auto& option : options)
            if (option.second == path(s)) return option.first;
          return std::string("?");
        },
        [path, options](Settings& s, const std::string& text) {
          for (const auto& option : options)
            if (option.first == text) path(s) = option.second;
        });
    for (const auto& option : options) entry.choices.push_back(option.first);
    return entry;
  }

  /// Two whole-number fields given as N (both) or WxH: an image's size.
  template <typename Width, typename Height>
  static setting extent(std::string name, Width width, Height height, setting_range range, std::string unit, std::string help) {
    return described(
        std::move(name), setting_type::size, range, std::move(unit), std::move(help),
        [width, height](const Settings& s) {
          return width(s) == height(s) ? std::to_string(width(s)) : std::to_string(width(s)) + "x" + std::to_string(height(s));
        },
        [width, height](Settings& s, const std::string& text) { std::tie(width(s), height(s)) = *parse_extent(text); });
  }

  /// A GLM vector field given as x,y,z.
  template <typename... Members>
  static setting point(std::string name, member_path<Members...> path, setting_range range, std::string unit, std::string help) {
    using value_type = path_value_t<Settings, member_path<Members...>>;
    return described(
        std::move(name), setting_type::point, range, std::move(unit), std::move(help),
        [path](const Settings& s) {
          std::string text;
          for (glm::length_t i = 0; i < value_type::length(); ++i) {
            if (i > 0) text += ',';
            text += format_real(path(s)[i]);
          }
          return text;
        },
        [path](Settings& s, const std::string& text) {
          const std::vector<double> point = *parse_point(text);
          for (glm::length_t i = 0; i < value_type::length(); ++i) path(s)[i] = static_cast<typename value_type::value_type>(point[static_cast<std::size_t>(i)]);
        });
  }

  /// A text field (a name or a file).
  template <typename... Members>
  static setting text(std::string name, member_path<Members...> path, std::string help) {
    return described(
        std::move(name), setting_type::text, setting_range{}, "", std::move(help), [path](const Settings& s) { return std::string(path(s)); },
        [path](Settings& s, const std::string& text) { path(s) = text; });
  }

  /// A value derived from fields that other settings hold (a preset, a radius in other units):
  /// its own get and set.
  static setting custom(std::string name, setting_type type, std::string unit, std::string help, std::function<std::string(const Settings&)> get,
                        std::function<void(Settings&, const std::string&)> set) {
    return described(std::move(name), type, setting_range{}, std::move(unit), std::move(help), std::move(get), std::move(set));
  }

 private:
  /// What every factory above fills: the description and how to read and write the value.
  static setting described(std::string name, setting_type type, setting_range range, std::string unit, std::string help,
                           std::function<std::string(const Settings&)> get, std::function<void(Settings&, const std::string&)> set) {
    setting entry;
    entry.name = std::move(name);
    entry.type = type;
    entry.range = range;
    entry.unit = std::move(unit);
    entry.help = std::move(help);
    entry.get = std::move(get);
    entry.set = std::move(set);
    return entry;
  }
};

/// "" when every setting in effect of `table` holds a value its description accepts (the
/// struct may have been filled by code, not by set()), else "<name> <why>".
template <typename Settings, typename Technique>
std::string check_settings(const std::vector<setting<Settings, Technique>>& table, const Settings& settings) {
  for (const setting<Settings, Technique>& entry : table)
    if (entry.in_effect)
      if (const std::string why = entry.check(entry.get(settings)); !why.empty()) return entry.name + " " + why;
  return {};
}

/// The settings of `table` whose change from `from` to `to` needs a new pipeline (a define or
/// something built from them; setting::defines, setting::builds), in the table's order: what
/// each family's apply_settings refuses to apply in place.
template <typename Settings, typename Technique>
std::vector<std::string> rebuilding_changes(const std::vector<setting<Settings, Technique>>& table, const Settings& from, const Settings& to) {
  std::vector<std::string> names;
  for (const setting<Settings, Technique>& entry : table)
    if (entry.needs_rebuild(from, to)) names.push_back(entry.name);
  return names;
}

/// Any family's settings, by name and text: what the command line, the viewer and the sweep hold
/// and change without knowing the family's struct.
class technique_settings {
 public:
  virtual ~technique_settings() = default;
  virtual std::unique_ptr<technique_settings> clone() const = 0;
  virtual std::string technique() const = 0;
  /// Another technique of the same family (the settings are kept). Throws vplkit::error for a
  /// technique of another family.
  virtual void set_technique(const std::string& technique) = 0;
  /// Every setting of the family, in the table's order.
  virtual std::vector<const setting_info*> settings() const = 0;
  /// The setting called `name`, or null.
  virtual const setting_info* find(const std::string& name) const = 0;
  /// Whether `technique` (default: the current one) reads the setting.
  virtual bool reads(const std::string& name, const std::string& technique) const = 0;
  bool reads(const std::string& name) const { return reads(name, technique()); }
  /// The techniques of the family that read the setting, in the family's order.
  virtual std::vector<std::string> readers(const std::string& name) const = 0;
  virtual std::string get(const std::string& name) const = 0;
  /// Checks `value` against the setting's type and range and sets it: "" on success, else why
  /// not (and nothing changed). Cross-setting rules are validate()'s.
  virtual std::string set(const std::string& name, const std::string& value) = 0;
  /// "" when the settings are usable (every range and every rule of the family), else the first problem.
  virtual std::string validate() const = 0;
  /// The kernel-struct members the setting feeds, as the frame would upload them (setting::feeds
  /// with a member path); empty for a setting that feeds none.
  virtual std::vector<double> fed_values(const std::string& name) const = 0;
  /// The settings whose change from `from` to these needs a new pipeline (rebuilding_changes),
  /// with "technique" first for another technique; {"family"} for another family's settings.
  virtual std::vector<std::string> rebuilding_changes(const technique_settings& from) const = 0;
};

/// The name and value of every setting in effect that the current technique reads.
std::vector<std::pair<std::string, std::string>> settings_in_effect(const technique_settings& settings);

/// The settings in effect as a JSON object, numbers as numbers: {"technique": ..., "radius": 0.75, ...}.
std::string settings_json(const technique_settings& settings, int indent = 2);

namespace detail {
/// Throws vplkit::error: "unknown technique '<name>' for these settings (known: ...)".
[[noreturn]] void throw_unknown_technique(const std::string& technique, const std::vector<std::string>& known);
}  // namespace detail

/// technique_settings over one family's struct and table.
template <typename Settings, typename Technique>
class described_settings final : public technique_settings {
 public:
  /// What the family supplies: its table, its techniques, its validation and where the struct
  /// keeps the technique's name.
  struct family {
    const std::vector<setting<Settings, Technique>>* table;
    const std::vector<Technique>* techniques;
    std::function<std::string(const Settings&)> validate;
    std::function<std::string(const Settings&)> technique_of;
    std::function<void(Settings&, const std::string&)> set_technique;
  };

  described_settings(const family& description, Settings value) : family_(&description), value_(std::move(value)) {}

  Settings& value() { return value_; }
  const Settings& value() const { return value_; }

  std::unique_ptr<technique_settings> clone() const override { return std::make_unique<described_settings>(*this); }
  std::string technique() const override { return family_->technique_of(value_); }
  void set_technique(const std::string& technique) override {
    if (!find_technique(technique)) detail::throw_unknown_technique(technique, technique_names());
    family_->set_technique(value_, technique);
  }
  std::vector<const setting_info*> settings() const override {
    std::vector<const setting_info*> all;
    for (const auto& entry : *family_->table) all.push_back(&entry);
    return all;
  }
  const setting_info* find(const std::string& name) const override { return entry(name); }
  bool reads(const std::string& name, const std::string& technique) const override {
    const auto* found = entry(name);
    const Technique* chosen = find_technique(technique);
    return found && chosen && (!found->reads || found->reads(*chosen));
  }
  std::vector<std::string> readers(const std::string& name) const override {
    std::vector<std::string> names;
    for (const Technique& t : *family_->techniques)
      if (reads(name, t.name)) names.emplace_back(t.name);
    return names;
  }
  std::string get(const std::string& name) const override {
    const auto* found = entry(name);
    return found ? found->get(value_) : std::string();
  }
  std::string set(const std::string& name, const std::string& text) override {
    const auto* found = entry(name);
    if (!found) return "is not a setting of technique " + technique();
    if (std::string why = found->check(text); !why.empty()) return why;
    found->set(value_, text);
    return {};
  }
  std::string validate() const override { return family_->validate(value_); }
  std::vector<double> fed_values(const std::string& name) const override {
    std::vector<double> values;
    if (const auto* found = entry(name))
      for (const auto& fed : found->fed_members) values.push_back(fed(value_));
    return values;
  }
  std::vector<std::string> rebuilding_changes(const technique_settings& from) const override {
    const auto* same_family = dynamic_cast<const described_settings*>(&from);
    if (!same_family) return {"family"};
    std::vector<std::string> names;
    if (same_family->technique() != technique()) names.push_back("technique");
    for (std::string& name : vplkit::rebuilding_changes(*family_->table, same_family->value(), value_)) names.push_back(std::move(name));
    return names;
  }

 private:
  const setting<Settings, Technique>* entry(const std::string& name) const {
    for (const auto& candidate : *family_->table)
      if (candidate.name == name) return &candidate;
    return nullptr;
  }
  const Technique* find_technique(const std::string& name) const {
    for (const Technique& t : *family_->techniques)
      if (name == t.name) return &t;
    return nullptr;
  }
  std::vector<std::string> technique_names() const {
    std::vector<std::string> names;
    for (const Technique& t : *family_->techniques) names.emplace_back(t.name);
    return names;
  }
  const family* family_;
  Settings value_;
};

}  // namespace vplkit
