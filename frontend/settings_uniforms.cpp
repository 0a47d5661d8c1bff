#include "frontend/settings_uniforms.hpp"

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

}  // namespace vplkit
