#include "frontend/viewer/technique_view.hpp"


#include <imgui.h>

#include "frontend/core/error.hpp"
#include "frontend/core/named_table.hpp"
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

namespace {

// A slider or drag edits `value` live; the setting counts as changed when the user lets go (a new
// pipeline per mouse pixel would recompile the programs continuously).
bool edit_int(const char* label, int& value, int low, int high) {
  ImGui::SliderInt(label, &value, low, high);
  return ImGui::IsItemDeactivatedAfterEdit();
}

bool edit_float(const char* label, float& value, float low, float high, const char* format = "%.3f") {
  ImGui::SliderFloat(label, &value, low, high, format);
  return ImGui::IsItemDeactivatedAfterEdit();
}

// A choice among `values`, shown by their `labels`.
template <typename T, std::size_t N>
bool edit_choice(const char* label, T& value, const T (&values)[N], const char* const (&labels)[N]) {
  std::size_t current = 0;
  for (std::size_t i = 0; i < N; ++i)
    if (values[i] == value) current = i;
  bool changed = false;
  if (ImGui::BeginCombo(label, labels[current])) {
    for (std::size_t i = 0; i < N; ++i)
      if (ImGui::Selectable(labels[i], i == current)) {
        changed = i != current;
        value = values[i];
      }
    ImGui::EndCombo();
  }
  return changed;
}

// Keeps an edited copy when `validate` accepts it.
template <typename Settings>
bool accept(bool changed, const Settings& edited, Settings& target, std::string& problem) {
  if (!changed) return false;
  if (const std::string reason = validate(edited); !reason.empty()) {
    problem = reason;
    return false;
  }
  target = edited;
  return true;
}

// What every family's view reads the same way from its pipeline.
template <typename Pipeline>
class pipeline_view : public technique_view {
 public:
  template <typename Source, typename Settings>
  pipeline_view(const shader_library& shaders, const Source& source, const Settings& settings) : pipeline_(shaders, source, settings) {}
  std::string technique() const override { return pipeline_.settings().technique; }
  image read_indirect() const override { return pipeline_.indirect_output().read_image(); }
  std::vector<pass_time> collect_pass_times() override { return pipeline_.collect_pass_times(); }
  pose camera_pose() const override { return pose_of(pipeline_.source().view); }

 protected:
  // The pipeline's camera moved to `where`.
  camera posed_camera(const pose& where) const {
    camera view = pipeline_.source().view;
    apply_pose(where, view, "camera");
    return view;
  }

  Pipeline pipeline_;
};

class rsm_view final : public pipeline_view<rsm_pipeline> {
 public:
  rsm_view(const shader_library& shaders, const scene& source, const rsm_pipeline_settings& settings)
      : pipeline_view(shaders, source, settings), shaders_(shaders) {}

  bool draw() override {
    const int before = pipeline_.view_draws();
    pipeline_.draw_changed();
    if (difference_) difference_->draw_changed();
    return pipeline_.view_draws() != before;
  }

  std::vector<view_layer> layers() const override {
    const rsm_technique& technique = pipeline_.constants().technique;
    std::vector<view_layer> result{view_layer::image};
    if (technique.indirect) result.push_back(view_layer::indirect);
    if (technique.visibility != rsm_visibility::none) result.push_back(view_layer::visibility_difference);
    return result;
  }

  layer_display display(view_layer layer) override {
    if (layer == view_layer::indirect) return {&pipeline_.indirect_output(), nullptr, 0, true, 1.0f};
    if (layer == view_layer::visibility_difference) {
      if (!difference_) {
        // The same frame without visibility: what the approximation removes (as `vplkit render`
        // writes -visibility-difference.png), built when first shown.
        rsm_pipeline_settings without = pipeline_.settings();
        without.technique = "rsm-radial";
        difference_ = std::make_unique<rsm_pipeline>(shaders_, pipeline_.source(), without);
        difference_->draw_changed();
      }
      return {&difference_->indirect_output(), &pipeline_.indirect_output(), 1, true, 8.0f};
    }
    return {&pipeline_.output(), nullptr, 0, false, 1.0f};
  }

  std::vector<pass_time> collect_pass_times() override {
    if (difference_) difference_->collect_pass_times();  // the overlay times the technique itself
    return pipeline_.collect_pass_times();
  }
  pose light_pose() const override { return pose_of(pipeline_.source().light); }

  void set_camera_pose(const pose& where) override {
    const camera view = posed_camera(where);
    pipeline_.set_camera(view);
    if (difference_) difference_->set_camera(view);
  }

  void set_light_pose(const pose& where) override {
    scene_light light = pipeline_.source().light;
    apply_pose(where, light, "light");
    pipeline_.set_light(light);
    if (difference_) difference_->set_light(light);
  }

  std::string draw_counts() const override {
    return "RSM " + std::to_string(pipeline_.rsm_draws()) + ", G-buffer to post filter " + std::to_string(pipeline_.view_draws());
  }

  void store_pose(viewer_scenes& scenes) const override {
    scenes.rsm.view = pipeline_.source().view;
    scenes.rsm.light = pipeline_.source().light;
  }

  bool edit_settings(viewer_scenes& scenes, std::string& problem) override {
    rsm_pipeline_settings edited = scenes.rsm_setup;
    const rsm_technique& technique = pipeline_.constants().technique;
    bool changed = false;
    static constexpr int rsm_sizes[] = {64, 128, 256, 512, 1024, 2048};
    static constexpr const char* rsm_size_labels[] = {"64", "128", "256", "512", "1024", "2048"};
    changed |= edit_choice("RSM size", edited.rsm_size, rsm_sizes, rsm_size_labels);
    if (technique.indirect) {
      changed |= edit_float("radius (of the RSM side)", edited.radius, 0.01f, 1.0f);
      if (technique.pattern == rsm_pattern::radial) {
        changed |= edit_int("paths", edited.radial.paths, 1, 64);
        changed |= edit_int("samples per path", edited.radial.samples_per_path, 1, 64);
      } else {
        changed |= edit_int("disk samples", edited.disk.samples, 1, 1024);
      }
      if (technique.visibility != rsm_visibility::none) changed |= edit_int("slots", edited.slots, 1, 64);
      static constexpr int divisors[] = {1, 2, 4, 8};
      static constexpr const char* divisor_labels[] = {"1 (full size)", "2", "4", "8"};
      changed |= edit_choice("indirect divisor", edited.indirect_divisor, divisors, divisor_labels);
      static constexpr post_filter filters[] = {post_filter::separable, post_filter::full};
      static constexpr const char* filter_labels[] = {"separable", "full 17x17"};
      changed |= edit_choice("post filter", edited.filter, filters, filter_labels);
    }
    return accept(changed, edited, scenes.rsm_setup, problem);
  }

 private:
  const shader_library& shaders_;
  std::unique_ptr<rsm_pipeline> difference_;
};

class lightwave_view final : public pipeline_view<lightwave_pipeline> {
 public:
  lightwave_view(const shader_library& shaders, const scene& source, const lightwave_settings& settings) : pipeline_view(shaders, source, settings) {}

  bool draw() override {
    if (!moved_) return false;
    pipeline_.draw();
    moved_ = false;
    ++main_draws_;
    return true;
  }

  std::vector<view_layer> layers() const override {
    const lightwave_mode mode = find_lightwave_technique(technique()).mode;
    std::vector<view_layer> result{view_layer::image};
    if (mode != lightwave_mode::direct) result.push_back(view_layer::indirect);
    if (mode == lightwave_mode::accurate || mode == lightwave_mode::integrated) result.push_back(view_layer::indirect_shadow);
    return result;
  }

  layer_display display(view_layer layer) override {
    if (layer == view_layer::indirect) return {&pipeline_.indirect_output(), nullptr, 0, true, 1.0f};
    if (layer == view_layer::indirect_shadow) return {&pipeline_.indirect_shadow_output(), nullptr, 2, false, 1.0f};
    return {&pipeline_.output(), nullptr, 0, false, 1.0f};
  }

  pose light_pose() const override { return pose_of(pipeline_.source().light); }

  void set_camera_pose(const pose& where) override {
    pipeline_.set_camera(posed_camera(where));
    moved_ = true;
  }

  void set_light_pose(const pose& where) override {
    spot_light<float> light = pipeline_.source().light.spot;
    apply_pose(where, light, "light");
    pipeline_.set_light(light);
    moved_ = true;
  }

  std::string draw_counts() const override {
    return "VPLs and shadow maps " + std::to_string(pipeline_.rebuilds()) + ", main pass " + std::to_string(main_draws_);
  }

  void store_pose(viewer_scenes& scenes) const override {
    scenes.lightwave.view = pipeline_.source().view;
    scenes.lightwave.light = pipeline_.source().light;
  }

  bool edit_settings(viewer_scenes& scenes, std::string& problem) override {
    lightwave_settings edited = scenes.lightwave_setup;
    const lightwave_mode mode = find_lightwave_technique(technique()).mode;
    bool changed = false;
    if (mode != lightwave_mode::direct && mode != lightwave_mode::faked) {
      changed |= edit_int("ray angle (degrees)", edited.angle_deg, 1, 45);
      changed |= edit_int("VPLs per ray", edited.per_ray, 1, 16);
      static constexpr lightwave_energy energies[] = {lightwave_energy::flux, lightwave_energy::thesis};
      static constexpr const char* energy_labels[] = {"flux", "thesis"};
      changed |= edit_choice("VPL energy", edited.energy, energies, energy_labels);
    }
    if (mode == lightwave_mode::faked) changed |= edit_float("faked multiplier m", edited.faked_multiplier, 1.0f, 2.0f);
    if (mode == lightwave_mode::accurate) {
      changed |= edit_int("shadow maps", edited.accurate_maps, 0, lightwave_max_shadow_maps);
      static constexpr lightwave_shadow_variant variants[] = {lightwave_shadow_variant::importance, lightwave_shadow_variant::thesis};
      static constexpr const char* variant_labels[] = {"importance", "thesis"};
      changed |= edit_choice("shadow variant", edited.shadow_variant, variants, variant_labels);
    }
    if (mode == lightwave_mode::integrated) {
      changed |= edit_int("shadow maps", edited.integrated_maps, 2, lightwave_max_shadow_maps);
      changed |= edit_int("in-between steps", edited.integrated_steps, 0, 32);
    }
    if (mode == lightwave_mode::accurate || mode == lightwave_mode::integrated) {
      changed |= edit_float("shadow map scale", edited.shadow_map_scale, 0.25f, 4.0f, "%.2f");
      changed |= edit_float("VPL field of view (thesis maps)", edited.vpl_field_of_view, 10.0f, 170.0f, "%.0f");
    }
    return accept(changed, edited, scenes.lightwave_setup, problem);
  }

 private:
  bool moved_ = true;  // the first frame draws
  int main_draws_ = 0;
};

class final_gather_view final : public pipeline_view<final_gather_pipeline> {
 public:
  final_gather_view(const shader_library& shaders, const final_gather_scene& source, const final_gather_settings& settings)
      : pipeline_view(shaders, source, settings) {}

  bool draw() override {
    const int before = pipeline_.view_draws();
    pipeline_.draw_changed();
    return pipeline_.view_draws() != before;
  }

  std::vector<view_layer> layers() const override { return {view_layer::image, view_layer::indirect}; }

  layer_display display(view_layer layer) override {
    if (layer == view_layer::indirect) return {&pipeline_.indirect_output(), nullptr, 0, true, 1.0f};
    return {&pipeline_.output(), nullptr, 0, false, 1.0f};
  }

  pose light_pose() const override {
    scene_light light;
    light.spot = pipeline_.source().light;
    return pose_of(light);
  }

  void set_camera_pose(const pose& where) override { pipeline_.set_camera(posed_camera(where)); }

  void set_light_pose(const pose& where) override {
    spot_light<float> light = pipeline_.source().light;
    apply_pose(where, light, "light");
    pipeline_.set_light(light);
  }

  bool has_object() const override { return true; }
  glm::vec3 object_position() const override { return pipeline_.source().reference_point; }
  void set_object_position(glm::vec3 centre) override { pipeline_.set_object_position(centre); }

  std::string draw_counts() const override {
    return "cube map " + std::to_string(pipeline_.cube_draws()) + ", G-buffer and shading " + std::to_string(pipeline_.view_draws());
  }

  void store_pose(viewer_scenes& scenes) const override { scenes.final_gather = pipeline_.source(); }

  bool edit_settings(viewer_scenes& scenes, std::string& problem) override {
    final_gather_settings edited = scenes.final_gather_setup;
    bool changed = false;
    changed |= edit_int("M (small cube map side)", edited.resolution, 1, 16);
    changed |= edit_int("cube map face size", edited.face_size, 16, 1024);
    if (pipeline_.variant() == final_gather_variant::environment_map) changed |= edit_int("K (irradiance map side)", edited.environment_resolution, 2, 64);
    return accept(changed, edited, scenes.final_gather_setup, problem);
  }
};

}  // namespace

std::vector<std::string> technique_names() {
  std::vector<std::string> names = names_of(rsm_techniques());
  for (const std::string& name : names_of(lightwave_techniques())) names.push_back(name);
  for (const std::string& name : names_of(final_gather_techniques())) names.push_back(name);
  return names;
}

std::unique_ptr<technique_view> make_technique_view(const shader_library& shaders, const viewer_scenes& scenes, const std::string& technique) {
  if (has_name(rsm_techniques(), technique)) {
    rsm_pipeline_settings settings = scenes.rsm_setup;
    settings.technique = technique;
    return std::make_unique<rsm_view>(shaders, scenes.rsm, settings);
  }
  if (has_name(lightwave_techniques(), technique)) {
    if (scenes.lightwave.light.kind != light_kind::spot)
      throw error("scene " + scenes.lightwave.name + " has a directional light; the Light Wave techniques need a spot light");
    lightwave_settings settings = scenes.lightwave_setup;
    settings.technique = technique;
    return std::make_unique<lightwave_view>(shaders, scenes.lightwave, settings);
  }
  final_gather_settings settings = scenes.final_gather_setup;
  settings.technique = find_final_gather_technique(technique).name;
  return std::make_unique<final_gather_view>(shaders, scenes.final_gather, settings);
}

}  // namespace vplkit
