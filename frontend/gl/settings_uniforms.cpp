#include <vplkit/gl/settings_uniforms.hpp>

namespace vplkit {

void set_uniforms(const program& target, const std::string& name, const irradiance_settings<float>& settings) {
  target.set(name + ".min_distance", settings.min_distance);
}

void set_uniforms(const program& target, const std::string& name, const elevation_slots<float>& slots) {
  target.set(name + ".count", slots.count);
  for (int k = 0; k < micro_linear_buffer_max_slots - 1; ++k)
    target.set(name + ".boundary_tangent[" + std::to_string(k) + "]", slots.boundary_tangent[k]);
}

void set_uniforms(const program& target, const std::string& name, const spot_light<float>& light) {
  target.set(name + ".position", light.position);
  target.set(name + ".direction", light.direction);
  target.set(name + ".intensity", light.intensity);
  target.set(name + ".cos_inner", light.cos_inner);
  target.set(name + ".cos_outer", light.cos_outer);
}

void set_uniforms(const program& target, const std::string& name, const directional_light<float>& light) {
  target.set(name + ".direction", light.direction);
  target.set(name + ".irradiance", light.irradiance);
}

void set_uniforms(const program& target, const std::string& name, const radial_pattern_constants<float>& constants) {
  target.set(name + ".paths", constants.paths);
  target.set(name + ".samples_per_path", constants.samples_per_path);
  target.set(name + ".min_radius", constants.min_radius);
  target.set(name + ".ring_ratio", constants.ring_ratio);
  target.set(name + ".path_turns", constants.path_turns);
  target.set(name + ".path_angle", constants.path_angle);
  target.set(name + ".rotation_jitter", constants.rotation_jitter);
  target.set(name + ".angle_jitter", constants.angle_jitter);
  target.set(name + ".scale_jitter", constants.scale_jitter);
  target.set(name + ".seed", static_cast<unsigned>(constants.seed));
}

void set_uniforms(const program& target, const std::string& name, const disk_pattern_settings<float>& settings) {
  target.set(name + ".samples", settings.samples);
  target.set(name + ".max_radius", settings.max_radius);
  target.set(name + ".seed", static_cast<unsigned>(settings.seed));
}

void set_uniforms(const program& target, const std::string& name, const rsm_gather_settings<float>& settings) {
  set_uniforms(target, name + ".irradiance", settings.irradiance);
  set_uniforms(target, name + ".radial", settings.radial);
  set_uniforms(target, name + ".disk", settings.disk);
  set_uniforms(target, name + ".slots", settings.slots);
  target.set(name + ".rsm_size", settings.rsm_size);
}

void set_uniforms(const program& target, const std::string& name, const rsm_unprojection<float>& light) {
  target.set(name + ".ray_origin", light.ray_origin);
  target.set(name + ".ray_step", light.ray_step);
  target.set(name + ".perspective", light.perspective);
}

void set_uniforms(const program& target, const std::string& name, const shadow_density_settings<float>& settings) {
  target.set(name + ".kernel_size", settings.kernel_size);
  target.set(name + ".depth_bias", settings.depth_bias);
}

void set_uniforms(const program& target, const std::string& name, const bilateral_settings<float>& settings) {
  target.set(name + ".kernel_size", settings.kernel_size);
  target.set(name + ".spatial_sigma", settings.spatial_sigma);
  target.set(name + ".depth_sigma", settings.depth_sigma);
  target.set(name + ".normal_power", settings.normal_power);
}

void set_uniforms(const program& target, const std::string& name, const lightwave_layout_settings<float>& settings) {
  target.set(name + ".light_position", settings.light_position);
  target.set(name + ".light_direction", settings.light_direction);
  target.set(name + ".angle_deg", settings.angle_deg);
  target.set(name + ".per_ray", settings.per_ray);
  target.set(name + ".max_distance", settings.max_distance);
}

void set_uniforms(const program& target, const std::string& name, const lightwave_shading_settings<float>& settings) {
  target.set(name + ".specular_strength", settings.specular_strength);
  target.set(name + ".specular_exponent", settings.specular_exponent);
}

}  // namespace vplkit
