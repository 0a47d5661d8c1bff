#include "frontend/techniques/registry.hpp"

#include "frontend/core/error.hpp"
#include "frontend/techniques/final_gather/final_gather_pipeline.hpp"
#include "frontend/techniques/lightwave/lightwave_pipeline.hpp"
#include "frontend/techniques/rsm/rsm_pipeline.hpp"

#include <vplkit/lightwave.hpp>

namespace vplkit {

namespace {

template <typename Technique>
std::vector<technique_entry> entries(const std::vector<Technique>& techniques) {
  std::vector<technique_entry> all;
  for (const Technique& technique : techniques) all.push_back({technique.name, technique.description});
  return all;
}

const scene& required(const scene* source, const std::string& family) {
  if (!source) throw error("the " + family + " techniques draw a scene, and none was given");
  return *source;
}

technique_family rsm_family() {
  using settings_type = described_settings<rsm_pipeline_settings, rsm_technique>;
  static const settings_type::family description{&rsm_settings_table(), &rsm_techniques(), [](const rsm_pipeline_settings& s) { return validate(s); },
                                                 [](const rsm_pipeline_settings& s) { return s.technique; },
                                                 [](rsm_pipeline_settings& s, const std::string& name) { s.technique = name; }};
  technique_family family;
  family.name = "rsm";
  family.title = "reflective shadow maps with a visibility approximation ([RSMV])";
  family.techniques = entries(rsm_techniques());
  family.default_scene = "cornell-box";
  family.make_settings = [](const std::string& technique) {
    rsm_pipeline_settings settings;
    settings.technique = find_rsm_technique(technique).name;
    return std::make_unique<settings_type>(description, settings);
  };
  family.make_pipeline = [](const shader_library& shaders, const scene* source, const technique_settings& settings) -> std::unique_ptr<pipeline> {
    return std::make_unique<rsm_pipeline>(shaders, required(source, "RSM"), settings_struct<rsm_pipeline_settings, rsm_technique>(settings));
  };
  family.visibility_baseline = [](const std::string& technique) {
    return find_rsm_technique(technique).visibility != rsm_visibility::none ? std::string("rsm-radial") : std::string();
  };
  family.sequence_readers = "the RSM techniques (direct, rsm-*)";
  return family;
}

technique_family lightwave_family() {
  using settings_type = described_settings<lightwave_settings, lightwave_technique>;
  static const settings_type::family description{&lightwave_settings_table(), &lightwave_techniques(), [](const lightwave_settings& s) { return validate(s); },
                                                 [](const lightwave_settings& s) { return s.technique; },
                                                 [](lightwave_settings& s, const std::string& name) { s.technique = name; }};
  technique_family family;
  family.name = "lightwave";
  family.title = "Light Wave ([LW])";
  family.techniques = entries(lightwave_techniques());
  family.default_scene = "boxes";
  family.make_settings = [](const std::string& technique) {
    lightwave_settings settings;
    settings.technique = find_lightwave_technique(technique).name;
    return std::make_unique<settings_type>(description, settings);
  };
  family.make_pipeline = [](const shader_library& shaders, const scene* source, const technique_settings& settings) -> std::unique_ptr<pipeline> {
    return std::make_unique<lightwave_pipeline>(shaders, required(source, "Light Wave"), settings_struct<lightwave_settings, lightwave_technique>(settings));
  };
  family.visibility_baseline = [](const std::string&) { return std::string(); };
  family.base_rank = [](double fps_gain, double similarity_percent) { return lightwave_rank(fps_gain, similarity_percent); };
  family.base_rank_title = "[LW]'s Eq. 5.3 (Table 5.10)";
  return family;
}

technique_family final_gather_family() {
  using settings_type = described_settings<final_gather_setup, final_gather_technique>;
  static const settings_type::family description{&final_gather_settings_table(), &final_gather_techniques(),
                                                 [](const final_gather_setup& s) { return validate(s); },
                                                 [](const final_gather_setup& s) { return s.pipeline.technique; },
                                                 [](final_gather_setup& s, const std::string& name) { s.pipeline.technique = name; }};
  technique_family family;
  family.name = "final-gather";
  family.title = "robust diffuse final gathering ([FG])";
  family.techniques = entries(final_gather_techniques());
  family.make_settings = [](const std::string& technique) {
    final_gather_setup setup;
    setup.pipeline.technique = find_final_gather_technique(technique).name;
    return std::make_unique<settings_type>(description, setup);
  };
  family.scene_optional = true;
  family.make_pipeline = [](const shader_library& shaders, const scene* source, const technique_settings& settings) -> std::unique_ptr<pipeline> {
    const final_gather_setup& setup = settings_struct<final_gather_setup, final_gather_technique>(settings);
    return std::make_unique<final_gather_pipeline>(shaders, make_final_gather_scene(source, setup), setup.pipeline);
  };
  family.visibility_baseline = [](const std::string&) { return std::string(); };
  return family;
}

}  // namespace

bool technique_family::has(const std::string& technique) const {
  for (const technique_entry& entry : techniques)
    if (entry.name == technique) return true;
  return false;
}

std::vector<std::string> technique_family::technique_names() const {
  std::vector<std::string> names;
  for (const technique_entry& entry : techniques) names.push_back(entry.name);
  return names;
}

const std::vector<technique_family>& technique_families() {
  static const std::vector<technique_family> families = {rsm_family(), lightwave_family(), final_gather_family()};
  return families;
}

const technique_family& family_of(const std::string& technique) {
  for (const technique_family& family : technique_families())
    if (family.has(technique)) return family;
  std::string known;
  for (const std::string& name : technique_names()) known += (known.empty() ? "" : ", ") + name;
  throw error("unknown technique '" + technique + "' (known: " + known + ")");
}

std::vector<std::string> technique_names() {
  std::vector<std::string> names;
  for (const technique_family& family : technique_families())
    for (const technique_entry& entry : family.techniques) names.push_back(entry.name);
  return names;
}

bool is_technique(const std::string& technique) {
  for (const technique_family& family : technique_families())
    if (family.has(technique)) return true;
  return false;
}

}  // namespace vplkit
