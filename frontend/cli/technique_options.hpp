// What `render`, `view` and `sweep` share: --technique over every family of the registry
// (frontend/techniques/registry.hpp), --scene, --camera/--light, the context options, and one
// option per setting of the families' tables (frontend/core/setting.hpp), each scoped to the
// techniques that read it: an option the chosen technique does not read is an error that names
// who reads it. A setting several families have (--size, --min-distance) is one option.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "frontend/cli/options.hpp"
#include "frontend/core/setting.hpp"
#include "frontend/reference/quality.hpp"
#include "frontend/techniques/registry.hpp"

namespace vplkit::cli {

/// Setting values as given on the command line, by setting name, in the order given.
struct given_settings {
  std::vector<std::pair<std::string, std::string>> values;
  const std::string* find(const std::string& name) const;
};

struct technique_options {
  std::string technique = "rsm-alg6";
  given_settings given;
  common_options common;
  option_scope scope;  ///< options that are not settings (--scene, --raw-indirect)
};

/// One option per setting name of every family (or of `only` when not empty), storing what was
/// given into `given`, checked as parsed against the setting's description. Returns the options.
std::vector<CLI::Option*> add_setting_options(CLI::App& command, given_settings& given, const std::vector<std::string>& only = {});

/// --technique, --scene, --camera/--light, --shader-dir/--context/--device and every setting option.
void add_technique_options(CLI::App& command, technique_options& options);

/// Who reads the setting `name`: "rsm-original, ... and rsm-alg6 (the techniques that gather
/// indirect light)", over every family that has it.
std::string setting_readers(const std::string& name);

/// "--radius is read by rsm-original, rsm-radial, ... (the techniques that gather indirect light),
/// not by technique direct" for the first given setting `technique` does not read, or "".
std::string unread_setting(const given_settings& given, const std::string& technique);

/// `technique`'s settings: its family's defaults, then the given values that it reads (presets
/// first, then in the table's order), validated. Throws usage_error for a given setting it does
/// not read, two settings that exclude each other, or settings the family refuses.
std::unique_ptr<technique_settings> make_technique_settings(const given_settings& given, const std::string& technique);

/// --receiver-stride (rsm-brute-force), --samples and --reference-seed (monte-carlo), scoped in
/// `scope` to the reference that reads them (the choice is the reference's name, which the
/// option `chooser` gives: --reference, or --method for `vplkit reference`).
void add_reference_options(CLI::App& command, reference_options& options, option_scope& scope, const std::string& chooser = "--reference");

/// The scene a technique draws: --scene, else its family's default; for a family that draws its
/// own (final gathering), its object.
std::string drawn_scene_name(const common_options& common, const technique_settings& settings);

/// The pipeline of `settings` over its scene (loaded by name, posed; null source for a family
/// without one, posed after it is built). `source` keeps the loaded scene alive.
std::unique_ptr<pipeline> make_posed_pipeline(const shader_library& shaders, const common_options& common, const technique_settings& settings,
                                              std::unique_ptr<scene>& source);

}  // namespace vplkit::cli
