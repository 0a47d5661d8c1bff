#include "frontend/viewer/technique_view.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "frontend/core/error.hpp"
#include "frontend/scene/pose.hpp"

namespace vplkit {

const char* describe(view_layer layer) {
  switch (layer) {
    case view_layer::image: return "final image";
    case view_layer::indirect: return "indirect light";
    case view_layer::visibility_difference: return "visibility difference (8x)";
    case view_layer::indirect_shadow: return "indirect shadow factor";
  }
  return "";
}

viewer_family::viewer_family(const viewer_family& other)
    : settings(other.settings ? other.settings->clone() : nullptr), source(other.source), view(other.view), lights(other.lights), file_lights(other.file_lights),
      object(other.object) {}

viewer_family& viewer_family::operator=(const viewer_family& other) {
  if (this != &other) *this = viewer_family(other);
  return *this;
}

viewer_family& viewer_scenes::of(const std::string& technique) {
  const auto found = families.find(family_of(technique).name);
  if (found == families.end() || !found->second.settings) throw error("the viewer has no settings of the " + family_of(technique).name + " techniques");
  return found->second;
}

const viewer_family& viewer_scenes::of(const std::string& technique) const { return const_cast<viewer_scenes&>(*this).of(technique); }

namespace {

// The pipeline of `settings` over the family's scene, at the stored poses.
std::unique_ptr<pipeline> make_posed(const shader_library& shaders, const viewer_family& family, const technique_settings& settings) {
  std::unique_ptr<pipeline> made = family_of(settings.technique()).make_pipeline(shaders, family.source ? &*family.source : nullptr, settings);
  if (family.view) made->set_camera(*family.view);
  if (family.lights)
    for (std::size_t k = 0; k < family.lights->size(); ++k) made->set_light(k, (*family.lights)[k]);
  if (family.object) made->set_object_position(*family.object);
  return made;
}

// A control for one setting, made from its description; `value` holds the setting's text. True
// when the user finished an edit (a slider or field is let go: a setting that needs a new
// pipeline would otherwise recompile the programs per mouse pixel). The range is the description's: what the command
// line refuses, the control does not offer, or refuses the same way.
bool edit_control(const setting_info& info, std::string& value) {
  const char* label = info.name.c_str();
  bool done = false;
  const auto finite = [](double v) { return std::isfinite(v); };
  if (info.type == setting_type::choice || (info.type == setting_type::integer && !info.allowed.empty())) {
    std::vector<std::string> options = info.choices;
    for (int allowed : info.allowed) options.push_back(std::to_string(allowed));
    if (ImGui::BeginCombo(label, value.c_str())) {
      for (const std::string& option : options)
        if (ImGui::Selectable(option.c_str(), option == value) && option != value) {
          value = option;
          done = true;
        }
      ImGui::EndCombo();
    }
  } else if (info.type == setting_type::integer) {
    int number = static_cast<int>(info.number(value).value_or(0.0));
    const double low = info.range.low_open ? info.range.low + 1.0 : info.range.low, high = info.range.high_open ? info.range.high - 1.0 : info.range.high;
    if (finite(low) && finite(high) && high - low <= 256.0) ImGui::SliderInt(label, &number, static_cast<int>(low), static_cast<int>(high));
    else ImGui::InputInt(label, &number, 1, 16);
    done = ImGui::IsItemDeactivatedAfterEdit();
    if (done) value = std::to_string(number);
  } else if (info.type == setting_type::real) {
    float number = static_cast<float>(info.number(value).value_or(0.0));
    if (finite(info.range.low) && finite(info.range.high))
      ImGui::SliderFloat(label, &number, static_cast<float>(info.range.low), static_cast<float>(info.range.high), "%.4g");
    else
      ImGui::InputFloat(label, &number, 0.0f, 0.0f, "%.4g");
    done = ImGui::IsItemDeactivatedAfterEdit();
    if (done) value = format_real(number);
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s: %s", info.help.c_str(), info.values().c_str());
  return done;
}

}  // namespace

technique_view::technique_view(const shader_library& shaders, const viewer_scenes& scenes, const std::string& technique)
    : shaders_(shaders), settings_(scenes.of(technique).settings->clone()) {
  settings_->set_technique(technique);
  const viewer_family& family = scenes.of(technique);
  source_ = family.source ? &*family.source : nullptr;
  pipeline_ = make_posed(shaders, family, *settings_);
}

bool technique_view::draw() {
  const int before = pipeline_->view_draws();
  pipeline_->draw_changed();
  if (difference_) difference_->draw_changed();
  return pipeline_->view_draws() != before;
}

std::vector<view_layer> technique_view::layers() const {
  std::vector<view_layer> result{view_layer::image};
  if (pipeline_->has_indirect()) result.push_back(view_layer::indirect);
  if (!family_of(technique()).visibility_baseline(technique()).empty()) result.push_back(view_layer::visibility_difference);
  if (pipeline_->indirect_shadow_output()) result.push_back(view_layer::indirect_shadow);
  return result;
}

layer_display technique_view::display(view_layer layer) {
  if (layer == view_layer::indirect) return {&pipeline_->indirect_output(), nullptr, 0, true, 1.0f};
  if (layer == view_layer::indirect_shadow && pipeline_->indirect_shadow_output()) return {pipeline_->indirect_shadow_output(), nullptr, 2, false, 1.0f};
  if (layer == view_layer::visibility_difference) {
    if (!difference_) {
      // The same frame without visibility: what the approximation removes (as `vplkit render`
      // writes -visibility-difference.png), built when first shown.
      std::unique_ptr<technique_settings> without = settings_->clone();
      without->set_technique(family_of(technique()).visibility_baseline(technique()));
      difference_ = family_of(technique()).make_pipeline(shaders_, source_, *without);
      difference_->set_camera(pipeline_->current_camera());
      const std::vector<scene_light> lights = pipeline_->current_lights();
      for (std::size_t k = 0; k < lights.size(); ++k) difference_->set_light(k, lights[k]);
      difference_->draw_changed();
    }
    return {&difference_->indirect_output(), &pipeline_->indirect_output(), 1, true, 8.0f};
  }
  return {&pipeline_->output(), nullptr, 0, false, 1.0f};
}

std::vector<pass_time> technique_view::collect_pass_times() {
  if (difference_) difference_->collect_pass_times();  // the overlay times the technique itself
  return pipeline_->collect_pass_times();
}

pose technique_view::camera_pose() const { return pose_of(pipeline_->current_camera()); }
std::size_t technique_view::light_count() const { return pipeline_->current_lights().size(); }

light_kind technique_view::light_kind_of(std::size_t index) const {
  const std::vector<scene_light> lights = pipeline_->current_lights();
  if (index >= lights.size()) throw error("the scene has no light " + std::to_string(index) + " (it has " + std::to_string(lights.size()) + ")");
  return lights[index].kind;
}

void technique_view::select_light(std::size_t index) {
  const std::size_t count = light_count();
  if (index >= count) throw error("the scene has no light " + std::to_string(index) + " (it has " + std::to_string(count) + ")");
  selected_light_ = index;
}

scene_light technique_view::selected_light() const {
  const std::vector<scene_light> lights = pipeline_->current_lights();
  if (selected_light_ >= lights.size()) throw error("the scene has no light to move");
  return lights[selected_light_];
}

void technique_view::set_selected_light(const scene_light& light) {
  pipeline_->set_light(selected_light_, light);
  if (difference_) difference_->set_light(selected_light_, light);
}

pose technique_view::light_pose() const { return pose_of(selected_light()); }

void technique_view::set_camera_pose(const pose& where) {
  camera view = pipeline_->current_camera();
  apply_pose(where, view, "camera");
  pipeline_->set_camera(view);
  if (difference_) difference_->set_camera(view);
}

void technique_view::set_light_pose(const pose& where) {
  scene_light light = selected_light();
  apply_pose(where, light, "light " + std::to_string(selected_light_));
  set_selected_light(light);
}

float technique_view::light_intensity() const {
  const glm::vec3 power = light_power(selected_light());
  return std::max({power.r, power.g, power.b});
}

void technique_view::set_light_intensity(float intensity) {
  scene_light light = selected_light();
  vplkit::set_light_intensity(light, intensity);
  set_selected_light(light);
}

void technique_view::store_pose(viewer_scenes& scenes) const {
  viewer_family& family = scenes.of(technique());
  family.view = pipeline_->current_camera();
  family.lights = pipeline_->current_lights();
  if (pipeline_->has_object()) family.object = pipeline_->object_position();
}

bool technique_view::edit_settings(viewer_scenes& scenes, std::string& problem) {
  viewer_family& family = scenes.of(technique());
  std::unique_ptr<technique_settings> edited = settings_->clone();
  bool changed = false;
  for (const setting_info* info : edited->settings()) {
    if (!info->live || !info->in_effect || !edited->reads(info->name)) continue;
    std::string value = edited->get(info->name);
    if (!edit_control(*info, value)) continue;
    if (const std::string why = edited->set(info->name, value); !why.empty()) {
      problem = info->name + " " + why;
      return false;
    }
    changed = true;
  }
  if (!changed) return false;
  if (const std::string why = edited->validate(); !why.empty()) {
    problem = why;
    return false;
  }
  family.settings = std::move(edited);
  return true;
}

bool technique_view::take_settings(const viewer_scenes& scenes) {
  const technique_settings& stored = *scenes.of(technique()).settings;
  if (stored.technique() != technique() || !pipeline_->apply_settings(stored)) return false;
  settings_ = stored.clone();
  if (difference_) {
    std::unique_ptr<technique_settings> without = settings_->clone();
    without->set_technique(family_of(technique()).visibility_baseline(technique()));
    if (!difference_->apply_settings(*without)) difference_.reset();
  }
  return true;
}

std::unique_ptr<technique_view> make_technique_view(const shader_library& shaders, const viewer_scenes& scenes, const std::string& technique) {
  return std::make_unique<technique_view>(shaders, scenes, technique);
}

}  // namespace vplkit
