#include "frontend/cli/technique_options.hpp"

#include <algorithm>

#include "frontend/core/error.hpp"

namespace vplkit::cli {

namespace {

// A setting as the families have it: its description (the same in every family that has it) and
// each family's default.
struct merged_setting {
  setting_info info;
  std::vector<std::pair<std::string, std::string>> defaults;  // family -> default
};

bool same_values(const setting_info& a, const setting_info& b) {
  return a.type == b.type && a.range.low == b.range.low && a.range.high == b.range.high && a.range.low_open == b.range.low_open &&
         a.range.high_open == b.range.high_open && a.allowed == b.allowed && a.choices == b.choices;
}

// Every setting name of every family, in the families' and tables' order.
const std::vector<merged_setting>& merged_settings() {
  static const std::vector<merged_setting> merged = [] {
    std::vector<merged_setting> all;
    for (const technique_family& family : technique_families()) {
      const std::unique_ptr<technique_settings> defaults = family.make_settings(family.techniques.front().name);
      for (const setting_info* info : defaults->settings()) {
        auto found = std::find_if(all.begin(), all.end(), [&](const merged_setting& m) { return m.info.name == info->name; });
        if (found == all.end()) {
          all.push_back({*info, {}});
          found = all.end() - 1;
        } else if (!same_values(found->info, *info)) {
          throw error("setting '" + info->name + "' takes different values in two technique families; one option cannot describe both");
        }
        found->defaults.emplace_back(family.name, defaults->get(info->name));
      }
    }
    return all;
  }();
  return merged;
}

std::string default_text(const merged_setting& setting) {
  bool one = true;
  for (const auto& entry : setting.defaults) one = one && entry.second == setting.defaults.front().second;
  if (one) return setting.defaults.front().second;
  std::string text;
  for (const auto& [family, value] : setting.defaults) text += (text.empty() ? "" : "; ") + value + " (" + family + ")";
  return text;
}

std::string listed(const std::vector<std::string>& names) {
  std::string all;
  for (std::size_t i = 0; i < names.size(); ++i) all += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + names[i];
  return all;
}

// "rsm-original, ... and rsm-alg6 (the techniques that gather indirect light) and lightwave-accurate (...)".
}  // namespace

std::string setting_readers(const std::string& name) {
  std::vector<std::string> groups;
  for (const technique_family& family : technique_families()) {
    const std::unique_ptr<technique_settings> settings = family.make_settings(family.techniques.front().name);
    const setting_info* info = settings->find(name);
    if (!info) continue;
    const std::vector<std::string> readers = settings->readers(name);
    if (readers.empty()) continue;
    groups.push_back(listed(readers) + (info->readers.empty() ? "" : " (" + info->readers + ")"));
  }
  return groups.empty() ? "no technique" : listed(groups);
}

const std::string* given_settings::find(const std::string& name) const {
  for (const auto& [key, value] : values)
    if (key == name) return &value;
  return nullptr;
}

std::vector<CLI::Option*> add_setting_options(CLI::App& command, given_settings& given, const std::vector<std::string>& only) {
  std::vector<CLI::Option*> options;
  for (const merged_setting& setting : merged_settings()) {
    const setting_info& info = setting.info;
    if (!only.empty() && std::find(only.begin(), only.end(), info.name) == only.end()) continue;
    const std::string help = info.help + ": " + info.values() + " [" + default_text(setting) + "]";
    CLI::Option* option = command.add_option_function<std::string>(
        "--" + info.name, [&given, name = info.name](const std::string& value) { given.values.emplace_back(name, value); }, help);
    option->check(CLI::Validator([info](std::string& text) { return info.check(text); }, ""));
    option->type_name(info.type == setting_type::choice ? "" : info.type == setting_type::size ? "N|WxH" : info.type == setting_type::point ? "x,y,z" : "");
    options.push_back(option);
  }
  return options;
}

void add_technique_options(CLI::App& command, technique_options& options) {
  std::string techniques;
  for (const technique_family& family : technique_families()) techniques += (techniques.empty() ? "" : "; ") + family.title + ": " + listed(family.technique_names());
  command.add_option("--technique", options.technique, "rendering technique: " + techniques)->check(CLI::IsMember(technique_names()))->capture_default_str();
  std::vector<std::string> scene_readers, scene_defaults;
  for (const technique_family& family : technique_families())
    if (family.takes_scene()) {
      for (const std::string& name : family.technique_names()) scene_readers.push_back(name);
      scene_defaults.push_back((family.reads_scene() ? family.default_scene : "its own room") + " (" + family.name + ")");
    }
  options.scope.add(add_scene_option(command, options.common, listed(scene_defaults)), listed(scene_readers),
                    [](const std::string& technique) { return family_of(technique).takes_scene(); });
  add_pose_options(command, options.common);
  add_exposure_option(command, options.common);
  add_common_options(command, options.common);
  add_setting_options(command, options.given);
}

std::string unread_setting(const given_settings& given, const std::string& technique) {
  const std::unique_ptr<technique_settings> settings = family_of(technique).make_settings(technique);
  for (const auto& [name, value] : given.values)
    if (!settings->reads(name)) return "--" + name + " is read by " + setting_readers(name) + ", not by technique " + technique;
  return {};
}

std::unique_ptr<technique_settings> make_technique_settings(const given_settings& given, const std::string& technique) {
  std::unique_ptr<technique_settings> settings = family_of(technique).make_settings(technique);
  if (const std::string unread = unread_setting(given, technique); !unread.empty()) throw usage_error(unread);
  for (const auto& [name, value] : given.values) {
    const setting_info* info = settings->find(name);
    if (!info->excludes.empty() && given.find(info->excludes))
      throw usage_error("--" + name + " and --" + info->excludes + " set the same setting: give one of them");
  }
  // Presets first, then the table's order (a setting in other units needs what it is relative to).
  for (const bool first : {true, false})
    for (const setting_info* info : settings->settings())
      if (info->applies_first == first)
        for (const auto& [name, value] : given.values)
          if (name == info->name)
            if (const std::string why = settings->set(name, value); !why.empty()) throw usage_error("--" + name + " " + why);
  if (const std::string problem = settings->validate(); !problem.empty()) throw usage_error(problem);
  return settings;
}

void add_reference_options(CLI::App& command, reference_options& options, option_scope& scope, const std::string& chooser) {
  const auto named = [](const char* name) { return [name](const std::string& reference) { return reference == name; }; };
  scope.add(command
                .add_option("--receiver-stride", options.receiver_stride,
                            "rsm-brute-force: every N-th receiver of the indirect buffer per axis (the others are not computed or counted)")
                ->check(CLI::Range(1, 64))->capture_default_str(),
            chooser + " rsm-brute-force", named("rsm-brute-force"));
  scope.add(command.add_option("--samples,--reference-samples", options.samples, "monte-carlo: bounce rays per pixel")->check(CLI::Range(1, 1 << 20))->capture_default_str(),
            chooser + " monte-carlo", named("monte-carlo"));
  scope.add(command.add_option("--reference-seed", options.seed, "monte-carlo: seed of the estimate")->capture_default_str(), chooser + " monte-carlo",
            named("monte-carlo"));
}

std::string drawn_scene_name(const common_options& common, const technique_settings& settings) {
  const technique_family& family = family_of(settings.technique());
  if (!family.draws_scene(common.scene_given)) return settings.get("object");
  return common.scene_given ? common.scene : family.default_scene;
}

std::unique_ptr<pipeline> make_posed_pipeline(const shader_library& shaders, const common_options& common, const technique_settings& settings,
                                              std::unique_ptr<scene>& source) {
  const technique_family& family = family_of(settings.technique());
  if (!family.draws_scene(common.scene_given)) {
    std::unique_ptr<pipeline> drawn = family.make_pipeline(shaders, nullptr, settings);
    apply_poses(common, *drawn);
    return drawn;
  }
  source = std::make_unique<scene>(load_scene(common, drawn_scene_name(common, settings)));
  return family.make_pipeline(shaders, source.get(), settings);
}

}  // namespace vplkit::cli
