// CPU/GPU parity of include/vplkit/rsm_pattern.hpp against shaders/lib/rsm_pattern.glsl: the radial and the disk pattern, offsets and weights, texel by
// texel (vplkit/parity/parity.hpp).
#include <doctest/doctest.h>

#include <array>
#include <cstring>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/rsm_pattern.hpp>
#include <vplkit/polynomial_math.hpp>

#include <vplkit/gl/settings_uniforms.hpp>
#include <vplkit/parity/doctest.hpp>

#include "tests/parity/targets.hpp"

using namespace vplkit;
using namespace vplkit::parity;

TEST_CASE("parity: radial_pattern_sample, rsm_disk_pixel_shift and rsm_disk_sample, offsets and weights, on every target") {
  // Texel (x, y) evaluates path x % 16, sample y % 16 for receiver pixel (x, y): 4096 samples.
  const kernel_inputs inputs = grid_of(64, 64, 0, 1);
  kernel_inputs indexed = inputs;
  for (std::size_t i = 0; i < indexed.size(); ++i)
    indexed.uints[0][i] = glm::uvec4(static_cast<unsigned>(i % 64), static_cast<unsigned>(i / 64), 0u, 0u);
  radial_pattern_settings<float> settings;
  settings.paths = 16;
  settings.samples_per_path = 16;
  settings.seed = 99;
  const radial_pattern_constants<float> constants = make_radial_pattern_constants(settings);
  disk_pattern_settings<float> disk, printed;
  disk.seed = printed.seed = 5;
  printed.printed_weights = true;
  printed.per_pixel_shift = false;  // and the original's fixed pattern: both branches of rsm_disk_pixel_shift
  kernel_source source;
  source.name = "patterns";
  source.includes = {"lib/rsm_pattern.glsl"};
  source.body = R"(
    pattern_sample r = radial_pattern_sample(int(uin0.x % 16u), int(uin0.y % 16u), uin0.xy, radial);
    vec2 shift = rsm_disk_pixel_shift(uin0.xy, disk);
    pattern_sample d = rsm_disk_sample(int(uin0.x + 64u * uin0.y), shift, disk);
    pattern_sample q = rsm_disk_sample(int(uin0.x + 64u * uin0.y), rsm_disk_pixel_shift(uin0.xy, printed), printed);
    fout0 = vec4(r.offset, r.weight, 0.0);
    fout1 = vec4(d.offset, d.weight, 0.0);
    fout2 = vec4(q.offset, q.weight, 0.0);
    fout3 = vec4(shift, 0.0, 0.0);)";
  source.float_outputs = 4;
  // The settings as std140 blocks, which every target has.
  kernel_resources resources;
  resources.blocks = {settings_block("radial", constants), settings_block("disk", disk), settings_block("printed", printed)};
  std::vector<glm::vec4> cpu_radial(indexed.size()), cpu_disk(indexed.size()), cpu_printed(indexed.size()), cpu_shift(indexed.size());
  for (std::size_t i = 0; i < indexed.size(); ++i) {
    const glm::uvec2 pixel(indexed.uints[0][i]);
    const auto r = radial_pattern_sample(static_cast<int>(pixel.x % 16), static_cast<int>(pixel.y % 16), pixel, constants);
    const glm::vec2 shift = rsm_disk_pixel_shift(pixel, disk);
    const auto d = rsm_disk_sample(static_cast<int>(pixel.x + 64 * pixel.y), shift, disk);
    const auto q = rsm_disk_sample(static_cast<int>(pixel.x + 64 * pixel.y), rsm_disk_pixel_shift(pixel, printed), printed);
    cpu_radial[i] = glm::vec4(r.offset, r.weight, 0.0f);
    cpu_disk[i] = glm::vec4(d.offset, d.weight, 0.0f);
    cpu_printed[i] = glm::vec4(q.offset, q.weight, 0.0f);
    cpu_shift[i] = glm::vec4(shift, 0.0f, 0.0f);
  }
  // Hash bits, exact float-from-bits, +,* and the polynomial: bit-identical unless llvmpipe
  // contracts multiply-adds; offsets decide which texel is fetched, so allow 2 ulp at most.
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = "patterns (" + target + ")";
    const kernel_outputs gpu = run.run(source, indexed, run.where, resources);
    require_parity(compare("rsm_disk_pixel_shift (" + target + ")", gpu.floats[3], cpu_shift, indexed, {0.0f, 0.0f, 0, 0.0, "hash bits to float"}, 2));
    require_parity(compare("radial_pattern_sample (" + target + ")", gpu.floats[0], cpu_radial, indexed, {0.0f, 0.0f, 2, 0.0, "+,* only"}, 3));
    // The disk weight divides by N (llvmpipe's divide need not be correctly rounded): 4 ulp.
    require_parity(compare("rsm_disk_sample (" + target + ")", gpu.floats[1], cpu_disk, indexed, {0.0f, 0.0f, 4, 0.0, "+,*, one divide"}, 3));
    require_parity(compare("rsm_disk_sample, printed weights (" + target + ")", gpu.floats[2], cpu_printed, indexed,
                           {0.0f, 0.0f, 4, 0.0, "+,*, one divide"}, 3));
  }
}
