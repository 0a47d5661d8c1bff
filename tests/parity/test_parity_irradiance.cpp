// CPU/GPU parity of include/vplkit/irradiance.hpp against shaders/lib/irradiance.glsl: pixel_light_irradiance (Eq. 3.2) in the fragment and the vertex stage, texel by
// texel (tests/parity/parity_harness.hpp).
#include <doctest/doctest.h>

#include <array>
#include <cstring>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/irradiance.hpp>

#include "frontend/gl/settings_uniforms.hpp"
#include "tests/parity/parity_harness.hpp"
#include "tests/parity/parity_inputs.hpp"

using namespace vplkit;
using namespace vplkit::parity;

TEST_CASE("parity: pixel_light_irradiance (Eq. 3.2) in the fragment stage") {
  const kernel_inputs inputs = geometry_inputs(8);
  const glm::vec3 flux(1.0f, 0.25f, 3.0f);
  const irradiance_settings<float> settings{0.01f};
  const kernel_outputs gpu = run_fragment(irradiance_kernel(), inputs, [&](const program& p) {
    set_uniforms(p, "settings", settings);
    p.set("flux", flux);
  });
  require_parity(compare("pixel_light_irradiance", gpu.floats[0], irradiance_on_cpu(inputs, flux, settings), inputs,
                         irradiance_tolerance(), 3));
}

TEST_CASE("parity: pixel_light_irradiance (Eq. 3.2) in the vertex stage, through transform feedback") {
  const kernel_inputs inputs = geometry_inputs(9);
  const glm::vec3 flux(2.0f, 1.0f, 0.5f);
  const irradiance_settings<float> settings{0.05f};
  const kernel_outputs gpu = run_vertex(irradiance_kernel(), inputs, [&](const program& p) {
    set_uniforms(p, "settings", settings);
    p.set("flux", flux);
  });
  require_parity(compare("pixel_light_irradiance (vertex)", gpu.floats[0], irradiance_on_cpu(inputs, flux, settings), inputs,
                         irradiance_tolerance(), 3));
}
