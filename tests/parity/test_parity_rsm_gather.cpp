// CPU/GPU parity of include/vplkit/rsm_gather.hpp against shaders/lib/rsm_gather.glsl: the whole
// gather_rsm, receiver by receiver, for every pattern and visibility (VPLKIT_RSM_PATTERN,
// VPLKIT_VISIBILITY), with and without the coverage's coarse lights (VPLKIT_RSM_COVERAGE), on the
// synthetic RSM of the kernel tests (tests/kernels/synthetic_rsm.hpp: a lit floor seen from an
// orthographic light, with a block standing on it). The parts (pattern, Eq. 3.2, the micro linear
// buffer, the coarse lights) have their own parity tests; this one catches a twin whose loop,
// skips, order of visibility calls or weighting differs, which the parts' tests cannot see. It
// runs on every target (tests/parity/targets.hpp): the RSM and the coarse lights are
// kernel_tables (textures or storage buffers), the settings a std140 uniform block
// (vplkit/std140.hpp), which on Vulkan is a uniform buffer at set 0.
#include <doctest/doctest.h>

#include <random>
#include <string>
#include <vector>

#include <vplkit/rsm_coverage.hpp>
#include <vplkit/rsm_gather.hpp>

#include <vplkit/parity/doctest.hpp>

#include "tests/kernels/synthetic_rsm.hpp"
#include "tests/parity/targets.hpp"

using namespace vplkit;
using namespace vplkit::parity;

namespace {

constexpr int size = testing::rsm_size;  // 256 texels per side
constexpr int receivers_side = 32;       // 1024 receivers per variant
constexpr int coverage_blocks = 8;

// The synthetic RSM in float, texel (x, y) at y * size + x. Its flux varies from texel to texel
// (the kernel tests' is 1 everywhere), so that a sample that lands on the wrong texel changes
// the result, and a strip along the left edge is empty (eye z >= 0: skipped by both twins).
struct float_rsm {
  std::vector<rsm_texel<float>> texels;
  std::vector<glm::vec4> position, normal, flux;  // the three textures' texels
  rsm_texel<float> operator()(glm::ivec2 t) const { return texels[static_cast<std::size_t>(t.y * size + t.x)]; }
};

float_rsm make_rsm() {
  testing::synthetic_rsm synthetic;
  synthetic.block_x0 = 0.3;
  synthetic.block_x1 = 0.9;
  synthetic.block_height = 0.8;
  float_rsm rsm;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const rsm_texel<double> t = synthetic(glm::ivec2(x, y));
      rsm_texel<float> texel{glm::vec3(t.position), glm::vec3(t.normal),
                             glm::vec3(1.0f, 0.25f + 0.25f * static_cast<float>(x % 4), 0.5f + 0.125f * static_cast<float>(y % 5))};
      if (x < 6) texel.position.z = 0.0f;  // empty
      rsm.texels.push_back(texel);
      rsm.position.push_back(glm::vec4(texel.position, 0.0f));
      rsm.normal.push_back(glm::vec4(texel.normal, 0.0f));
      rsm.flux.push_back(glm::vec4(texel.flux, 0.0f));
    }
  return rsm;
}

// Receivers in the light's eye space, made in double from world positions as the kernel tests
// make them and rounded once: both twins read the same floats. Most lie above the floor (some in
// the block's shadow, some inside the block), about one in eight projects off the map (where the
// coverage adds the blocks beyond the pattern's reach) and one in sixteen lies behind the light
// (eye z >= 0: the coverage alone). Normals are random, half of them turned to face the floor.
kernel_inputs make_receivers() {
  kernel_inputs inputs = grid_of(receivers_side, receivers_side, 3, 1);
  std::mt19937 random(37);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> normal;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const double half = (i % 8 == 3) ? 3.4 : 2.4;  // the map covers +-2.56
    glm::dvec3 world(half * (2.0 * unit(random) - 1.0), 0.05 + 1.5 * unit(random), half * (2.0 * unit(random) - 1.0));
    if (i % 16 == 5) world.y = testing::light_height + 0.5 + unit(random);  // behind the light
    glm::dvec3 n = glm::normalize(glm::dvec3(normal(random), normal(random), normal(random)));
    if (i % 2 == 0 && n.y > 0.0) n.y = -n.y;
    const glm::uvec2 pixel(static_cast<unsigned>(i % receivers_side), static_cast<unsigned>(i / receivers_side));
    const gather_receiver<double> r = testing::receiver_at(world, pixel, n);
    inputs.floats[0][i] = glm::vec4(glm::vec3(r.position), 0.0f);
    inputs.floats[1][i] = glm::vec4(glm::vec3(r.normal), 0.0f);
    inputs.floats[2][i] = glm::vec4(glm::vec2(r.rsm_coordinate), 0.0f, 0.0f);
    inputs.uints[0][i] = glm::uvec4(pixel, 0u, 0u);
  }
  return inputs;
}

gather_receiver<float> receiver_of(const kernel_inputs& inputs, std::size_t i) {
  return {glm::vec3(inputs.floats[0][i]), glm::vec3(inputs.floats[1][i]), glm::vec2(inputs.floats[2][i]), glm::uvec2(inputs.uints[0][i])};
}

using coarse_lights = std::vector<coarse_light<float>>;

template <rsm_pattern Pattern, rsm_visibility Visibility>
std::vector<glm::vec4> gather_on_cpu(const kernel_inputs& inputs, const float_rsm& rsm, const coarse_lights& coarse, bool coverage,
                                     const rsm_gather_settings<float>& settings) {
  std::vector<glm::vec4> out(inputs.size());
  const auto coarse_fetch = [&](glm::ivec2 b) { return coarse[static_cast<std::size_t>(b.y * coverage_blocks + b.x)]; };
  // The shader's rsm_depth_coarse_visibility (below): a half-space stand-in for the cube's test,
  // an exact decision on both sides, so that the twins' use of it (every pattern and visibility
  // with coverage) is compared.
  const auto coarse_visibility = [](const glm::vec3& x, const glm::vec3& x_c) { return x_c.x > x.x ? 0.0f : 1.0f; };
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const gather_receiver<float> receiver = receiver_of(inputs, i);
    const glm::vec3 e = coverage ? gather_rsm<Pattern, Visibility>(receiver, rsm, coarse_fetch, coarse_visibility, settings)
                                 : gather_rsm<Pattern, Visibility>(receiver, rsm, settings);
    out[i] = glm::vec4(e, 0.0f);
  }
  return out;
}

struct variant {
  const char* name;
  int pattern;     // VPLKIT_RSM_PATTERN
  int visibility;  // VPLKIT_VISIBILITY
  bool coverage;   // VPLKIT_RSM_COVERAGE
  int perspective;
  int baseline;  // the variant it changes one thing of (-1: none): their C++ results must differ
  std::vector<glm::vec4> (*cpu)(const kernel_inputs&, const float_rsm&, const coarse_lights&, bool, const rsm_gather_settings<float>&);
};

// Every pattern and visibility, the pattern alone; the coverage with both patterns and with the
// visibility that reads the most (alg6_ray); alg6_ray also with a perspective light's `up`.
const variant variants[] = {
    {"radial, no visibility", 0, 0, false, 0, -1, gather_on_cpu<rsm_pattern::radial, rsm_visibility::none>},
    {"radial, Alg. 2", 0, 2, false, 0, 0, gather_on_cpu<rsm_pattern::radial, rsm_visibility::alg2>},
    {"radial, Alg. 3", 0, 3, false, 0, 0, gather_on_cpu<rsm_pattern::radial, rsm_visibility::alg3>},
    {"radial, Alg. 6", 0, 6, false, 0, 0, gather_on_cpu<rsm_pattern::radial, rsm_visibility::alg6>},
    {"radial, alg6_ray", 0, 7, false, 0, 0, gather_on_cpu<rsm_pattern::radial, rsm_visibility::alg6_ray>},
    {"radial, alg6_ray, perspective up", 0, 7, false, 1, 4, gather_on_cpu<rsm_pattern::radial, rsm_visibility::alg6_ray>},
    {"disk", 1, 0, false, 0, -1, gather_on_cpu<rsm_pattern::disk, rsm_visibility::none>},
    {"radial, alg6_ray, coverage", 0, 7, true, 0, 4, gather_on_cpu<rsm_pattern::radial, rsm_visibility::alg6_ray>},
    {"disk, coverage", 1, 0, true, 0, 6, gather_on_cpu<rsm_pattern::disk, rsm_visibility::none>},
};

}  // namespace

TEST_CASE("parity: gather_rsm for every pattern and visibility, with and without coverage, on a synthetic RSM, on every target") {
  const float_rsm rsm = make_rsm();
  const kernel_inputs inputs = make_receivers();
  // 12 paths x 10 samples over 0.4 of the map (102 texels), 8 slots; the disk's 400 samples over
  // the same radius; coverage 8 x 8 blocks interleaved over 2 x 2 pixels (phases differ by pixel).
  radial_pattern_settings<float> radial;
  radial.paths = 12;
  radial.samples_per_path = 10;
  rsm_gather_settings<float> settings = make_rsm_gather_settings(radial, disk_pattern_settings<float>{}, 0.4f, 8, glm::ivec2(size));
  settings.coverage_blocks = coverage_blocks;
  settings.coverage_interleave = 2;
  coarse_lights coarse;
  std::vector<glm::vec4> coarse_position_extent, coarse_normal, coarse_flux;
  for (int y = 0; y < coverage_blocks; ++y)
    for (int x = 0; x < coverage_blocks; ++x) {
      coarse.push_back(reduce_rsm_block<float>(glm::ivec2(x, y), coverage_blocks, glm::ivec2(size), rsm));
      coarse_position_extent.push_back(glm::vec4(coarse.back().position, coarse.back().extent));
      coarse_normal.push_back(glm::vec4(coarse.back().normal, 0.0f));
      coarse_flux.push_back(glm::vec4(coarse.back().flux, 0.0f));
    }
  // The RSM and the coarse lights as tables of floats, read exactly: the fetches add no arithmetic.
  kernel_resources resources;
  resources.tables = {{"rsm_position", size, size, rsm.position},
                      {"rsm_normal", size, size, rsm.normal},
                      {"rsm_flux", size, size, rsm.flux},
                      {"coarse_a", coverage_blocks, coverage_blocks, coarse_position_extent},
                      {"coarse_b", coverage_blocks, coverage_blocks, coarse_normal},
                      {"coarse_c", coverage_blocks, coverage_blocks, coarse_flux}};

  std::size_t behind = 0, off_map = 0;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    behind += inputs.floats[0][i].z >= 0.0f;
    const glm::vec2 c(inputs.floats[2][i]);
    off_map += inputs.floats[0][i].z < 0.0f && (c.x < 0.0f || c.y < 0.0f || c.x > size || c.y > size);
  }
  REQUIRE(behind >= 32u);  // the grid holds every case the gather branches on
  REQUIRE(off_map >= 32u);

  std::vector<std::vector<glm::vec4>> results;
  for (const variant& v : variants) {
    const std::string variant_name = v.name;
    CAPTURE(variant_name);
    settings.perspective = v.perspective;
    const std::vector<glm::vec4> cpu = v.cpu(inputs, rsm, coarse, v.coverage, settings);
    // Properties the comparison needs: the variant gathers light at most receivers (a gather that
    // returned 0 everywhere on both sides would pass any tolerance), and the one thing it changes
    // (a visibility, the coverage, alg6_ray's `up`) changes the result at many receivers, so that
    // a twin that ignored it would fail.
    std::size_t lit = 0, changed = 0;
    for (std::size_t i = 0; i < cpu.size(); ++i) {
      lit += cpu[i].x > 0.0f;
      if (v.baseline >= 0) changed += cpu[i] != results[static_cast<std::size_t>(v.baseline)][i];
    }
    MESSAGE(variant_name << ": " << lit << " of " << cpu.size() << " receivers lit, " << changed << " changed by it");
    CHECK(lit > inputs.size() / 3);
    if (v.baseline >= 0) CHECK(changed > inputs.size() / 20);
    results.push_back(cpu);
    // The tolerance, from the parts' parity tests: each term is Eq. 3.2 (test_parity_irradiance:
    // 16 ulp, or 1e-6 absolute near tangency, where the terms cancel) times a pattern weight (2-4
    // ulp, test_parity_rsm_pattern) and a visibility verdict (exact: small integers from exact
    // slot decisions, test_parity_micro_linear_buffer), about 2e-6 relative; the texel each sample
    // reads is a floor of exact offsets, no flip allowed (none happened). The N terms are positive
    // and summed in the same order on both sides, so the sums part by at most 2 (N - 1) roundings
    // of the sum: relative 2 N 2^-24 + 2e-6, with N the samples plus the coarse lights one
    // receiver gathers (radial 120 + 16: 1.8e-5; disk 400 + 16: 5.2e-5). Measured on llvmpipe:
    // 2.6e-6 relative at most (disk 9.4e-7).
    const int terms = (v.pattern == 0 ? radial.paths * radial.samples_per_path : settings.disk.samples) +
                      (v.coverage ? coverage_blocks * coverage_blocks / (settings.coverage_interleave * settings.coverage_interleave) : 0);
    const float relative = static_cast<float>(2.0 * terms * 0x1p-24 + 2e-6);
    resources.blocks = {settings_block("settings", settings)};
    for (const testing::target_run& run : testing::every_target()) {
      kernel_source source;
      source.name = std::string("gather_rsm (") + v.name + ", " + run.name() + ")";
      CAPTURE(source.name);
      if (!testing::target_runs(run.where)) continue;
      source.defines = {{"VPLKIT_RSM_PATTERN", std::to_string(v.pattern)},
                        {"VPLKIT_VISIBILITY", std::to_string(v.visibility)},
                        {"VPLKIT_RSM_COVERAGE", v.coverage ? "1" : "0"}};
      source.includes = {"lib/rsm_gather.glsl"};
      source.declarations =
          "rsm_texel rsm_fetch(ivec2 t) { return rsm_texel(rsm_position(t).xyz, rsm_normal(t).xyz, rsm_flux(t).xyz); }\n"
          "#if VPLKIT_RSM_COVERAGE\n"
          "coarse_light rsm_coarse_fetch(ivec2 b) {\n"
          "  vec4 a = coarse_a(b);\n"
          "  return coarse_light(a.xyz, coarse_b(b).xyz, coarse_c(b).xyz, a.w);\n"
          "}\n"
          "#if VPLKIT_VISIBILITY != 8\n"
          "float rsm_depth_coarse_visibility(vec3 x, vec3 xc) { return xc.x > x.x ? 0.0 : 1.0; }\n"
          "#endif\n"
          "#endif\n";
      source.body = "fout0 = vec4(gather_rsm(gather_receiver(fin0.xyz, fin1.xyz, fin2.xy, uin0.xy), settings), 0.0);";
      source.float_outputs = 1;
      const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
      require_parity(compare(source.name, gpu.floats[0], cpu, inputs,
                             {1e-6f, relative, 16, 0.0, "Eq. 3.2's error per term and 2 N roundings of a sum of N positive terms"}, 3));
    }
  }
}
