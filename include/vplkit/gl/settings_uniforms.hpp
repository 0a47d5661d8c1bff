// The one place where each kernel settings struct is copied into its GLSL twin (a uniform struct
// of the same name and fields). Every program that includes a lib file fills it from here, and so
// do users' own shaders that take vplkit's settings as uniforms (installed with vplkit::parity).
#pragma once

#include <string>

#include <vplkit/bilateral.hpp>
#include <vplkit/direct_light.hpp>
#include <vplkit/irradiance.hpp>
#include <vplkit/lightwave.hpp>
#include <vplkit/micro_linear_buffer.hpp>
#include <vplkit/rsm_gather.hpp>
#include <vplkit/rsm_packing.hpp>
#include <vplkit/rsm_pattern.hpp>
#include <vplkit/shadow.hpp>

#include <vplkit/gl/program.hpp>

namespace vplkit {

void set_uniforms(const program& target, const std::string& name, const irradiance_settings<float>& settings);
void set_uniforms(const program& target, const std::string& name, const elevation_slots<float>& slots);
void set_uniforms(const program& target, const std::string& name, const spot_light<float>& light);
void set_uniforms(const program& target, const std::string& name, const directional_light<float>& light);
void set_uniforms(const program& target, const std::string& name, const radial_pattern_constants<float>& constants);
void set_uniforms(const program& target, const std::string& name, const disk_pattern_settings<float>& settings);
void set_uniforms(const program& target, const std::string& name, const rsm_gather_settings<float>& settings);
void set_uniforms(const program& target, const std::string& name, const rsm_unprojection<float>& light);
void set_uniforms(const program& target, const std::string& name, const shadow_density_settings<float>& settings);
void set_uniforms(const program& target, const std::string& name, const bilateral_settings<float>& settings);
void set_uniforms(const program& target, const std::string& name, const lightwave_layout_settings<float>& settings);
void set_uniforms(const program& target, const std::string& name, const lightwave_shading_settings<float>& settings);

}  // namespace vplkit
