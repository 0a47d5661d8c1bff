// CPU/GPU parity of include/vplkit/irradiance.hpp against shaders/lib/irradiance.glsl: pixel_light_irradiance (Eq. 3.2) in the fragment, vertex and compute stages,
// on every target, texel by texel (vplkit/parity/parity.hpp).
#include <doctest/doctest.h>

#include <array>
#include <cstring>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/irradiance.hpp>

#include <vplkit/parity/doctest.hpp>

#include "tests/parity/targets.hpp"

using namespace vplkit;
using namespace vplkit::parity;

namespace {

// Vulkan has no default-block uniforms: the settings go in a std140 block and the flux in a
// one-texel table (read exactly), on every target alike.
kernel_source irradiance_kernel() {
  kernel_source source;
  source.name = "pixel_light_irradiance";
  source.includes = {"lib/irradiance.glsl"};
  source.body = "fout0 = vec4(pixel_light_irradiance(fin0.xyz, fin1.xyz, fin2.xyz, fin3.xyz, flux_table(ivec2(0)).xyz, settings), 0.0);";
  source.float_outputs = 1;
  return source;
}

kernel_resources irradiance_resources(const glm::vec3& flux, const irradiance_settings<float>& settings) {
  kernel_resources resources;
  resources.tables = {{"flux_table", 1, 1, {glm::vec4(flux, 0.0f)}}};
  resources.blocks = {settings_block("settings", settings)};
  return resources;
}

std::vector<glm::vec4> irradiance_on_cpu(const kernel_inputs& inputs, const glm::vec3& flux, const irradiance_settings<float>& settings) {
  std::vector<glm::vec4> out(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i)
    out[i] = glm::vec4(pixel_light_irradiance(glm::vec3(inputs.floats[0][i]), glm::vec3(inputs.floats[1][i]),
                                              glm::vec3(inputs.floats[2][i]), glm::vec3(inputs.floats[3][i]), flux, settings),
                       0.0f);
  return out;
}

// Eq. 3.2 is two dot products (3 multiplies, 2 adds each), a max, two divides and a product:
// about 8 roundings. llvmpipe may contract a multiply-add into an FMA (one rounding fewer)
// where the C++ build does not, and near-tangent configurations cancel in the dot products, so
// the relative error of a tiny result is unbounded while its absolute error stays at float
// precision of the unclamped term: pass at 16 ulp, 1e-5 relative, or 1e-6 absolute (results
// here are O(1) to O(1e4): the scale is 1 / min_distance^2 = 1e4 at most).
tolerance irradiance_tolerance() {
  return {1e-6f, 1e-5f, 16, 0.0, "about 8 roundings, FMA contraction on llvmpipe, cancellation near tangency"};
}

// Runs Eq. 3.2 as each of `runs` says and compares every run with the C++ twin, naming the target
// and stage in each comparison.
void irradiance_on(const std::vector<testing::target_run>& runs, const kernel_inputs& inputs, const glm::vec3& flux,
                   const irradiance_settings<float>& settings) {
  const kernel_resources resources = irradiance_resources(flux, settings);
  const std::vector<glm::vec4> cpu = irradiance_on_cpu(inputs, flux, settings);
  kernel_source source = irradiance_kernel();
  for (const testing::target_run& run : runs) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = "pixel_light_irradiance (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
    require_parity(compare(source.name, gpu.floats[0], cpu, inputs, irradiance_tolerance(), 3));
  }
}

}  // namespace

TEST_CASE("parity: pixel_light_irradiance (Eq. 3.2) in the fragment or compute stage, on every target") {
  irradiance_on(testing::every_target(), geometry_inputs(8), glm::vec3(1.0f, 0.25f, 3.0f), irradiance_settings<float>{0.01f});
}

TEST_CASE("parity: pixel_light_irradiance (Eq. 3.2) in the vertex stage through transform feedback on every GL target, and in compute on gl45 and vulkan") {
  irradiance_on(testing::every_vertex_target(), geometry_inputs(9), glm::vec3(2.0f, 1.0f, 0.5f), irradiance_settings<float>{0.05f});
}
