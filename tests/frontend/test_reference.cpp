// The CPU reference (frontend/reference.hpp): closed forms for the direct light and for one
// bounce off a uniformly lit floor, determinism, and the brute-force RSM gather with visibility
// converging to the RSM-free Monte Carlo reference as the RSM resolution grows.
#include <doctest/doctest.h>

#include <cmath>

#include "frontend/reference.hpp"
#include "frontend/rsm_pipeline.hpp"
#include "tests/closed_forms.hpp"
#include "tests/parity/parity_harness.hpp"

using namespace vplkit;

namespace {

using closed_forms::parallel_rectangle;

}  // namespace

TEST_CASE("reference direct light: a spot light over a plane gives I h / r^3, and an occluder casts its shadow") {
  mesh floor;
  add_quad(floor, {-5, 0, 5}, {5, 0, 5}, {5, 0, -5}, {-5, 0, -5}, {0, 1, 0}, glm::vec3(0.5f));
  scene_light light;
  light.spot.position = {0.0f, 2.0f, 0.0f};
  light.spot.direction = {0.0f, -1.0f, 0.0f};
  light.spot.intensity = glm::vec3(3.0f);
  light.spot.cos_inner = std::cos(glm::radians(70.0f));
  light.spot.cos_outer = std::cos(glm::radians(80.0f));
  const ray_scene rays(floor);
  for (float d : {0.0f, 0.5f, 1.0f, 2.5f}) {
    const glm::vec3 e = direct_irradiance(rays, light, {}, glm::vec3(d, 0.0f, 0.0f), glm::vec3(0, 1, 0));
    const double r = std::sqrt(4.0 + d * d);
    CHECK(e.x == doctest::Approx(3.0 * 2.0 / (r * r * r)).epsilon(1e-5));
  }
  mesh blocked = floor;
  add_quad(blocked, {-0.2f, 1, 0.2f}, {0.2f, 1, 0.2f}, {0.2f, 1, -0.2f}, {-0.2f, 1, -0.2f}, {0, 1, 0}, glm::vec3(0.5f));
  const ray_scene blocked_rays(blocked);
  CHECK(direct_irradiance(blocked_rays, light, {}, glm::vec3(0.0f), glm::vec3(0, 1, 0)) == glm::vec3(0.0f));
  CHECK(direct_irradiance(blocked_rays, light, {}, glm::vec3(2.0f, 0, 0), glm::vec3(0, 1, 0)).x > 0.0f);
}

TEST_CASE("reference one bounce: a point facing a uniformly lit floor gets albedo E0 F (Howell B-3 x 4)") {
  // A 2a x 2a floor lit straight down with irradiance E0 (directional light): its radiance is
  // albedo E0 / pi everywhere, so a point at height h facing it receives albedo E0 F.
  const float a = 1.0f, h = 0.5f, albedo = 0.6f;
  mesh floor;
  add_quad(floor, {-a, 0, a}, {a, 0, a}, {a, 0, -a}, {-a, 0, -a}, {0, 1, 0}, glm::vec3(albedo));
  scene_light light;
  light.kind = light_kind::directional;
  light.directional.direction = {0.0f, -1.0f, 0.0f};
  light.directional.irradiance = glm::vec3(2.0f);
  const ray_scene rays(floor);
  const int samples = 20000;
  const glm::vec3 e = one_bounce_irradiance(rays, light, {}, glm::vec3(0, h, 0), glm::vec3(0, -1, 0), samples, 7u, 1u);
  const double exact = albedo * 2.0 * 4.0 * parallel_rectangle(a, a, h);
  // A Bernoulli estimate of F (hit or miss) times a constant: sigma = sqrt(F (1 - F) / N).
  const double f = exact / (albedo * 2.0);
  const double sigma = albedo * 2.0 * std::sqrt(f * (1 - f) / samples);
  CAPTURE(e.x);
  CAPTURE(exact);
  CHECK(std::fabs(e.x - exact) < 4.0 * sigma);
  // Deterministic for a seed, different for another.
  CHECK(one_bounce_irradiance(rays, light, {}, glm::vec3(0, h, 0), glm::vec3(0, -1, 0), 256, 7u, 1u) ==
        one_bounce_irradiance(rays, light, {}, glm::vec3(0, h, 0), glm::vec3(0, -1, 0), 256, 7u, 1u));
  CHECK(one_bounce_irradiance(rays, light, {}, glm::vec3(0, h, 0), glm::vec3(0, -1, 0), 256, 7u, 1u) !=
        one_bounce_irradiance(rays, light, {}, glm::vec3(0, h, 0), glm::vec3(0, -1, 0), 256, 8u, 1u));
}

TEST_CASE("the brute-force RSM gather with visibility converges to the Monte Carlo one-bounce reference as the RSM grows") {
  const scene box = make_cornell_box();
  const ray_scene rays(box.geometry);
  double previous = 1e30;
  for (int rsm : {16, 32, 64}) {
    rsm_pipeline_settings settings;
    settings.width = settings.height = 24;
    settings.rsm_size = rsm;
    settings.format = texel_format::rgba32f;
    settings.technique = "rsm-radial";
    rsm_pipeline pipeline(parity::test_shaders(), box, settings);
    pipeline.render();
    const rsm_pass_buffers buffers = pipeline.read_buffers();
    const image_buffer brute = reference_rsm_gather(rays, buffers, pipeline.constants(), true, 2);
    double error = 0.0, level = 0.0;
    for (int y = 0; y < brute.height; ++y)
      for (int x = 0; x < brute.width; ++x) {
        const glm::ivec2 sample = glm::min(glm::ivec2(x, y) * 2, glm::ivec2(23));
        const glm::vec4 position_depth = buffers.gbuffer[0].at(sample);
        if (!(position_depth.w < 0.0f)) continue;
        const glm::vec3 p(position_depth), n(buffers.gbuffer[2].at(sample));
        const glm::vec3 mc = one_bounce_irradiance(rays, box.light, {}, p, n, 512, 3u, static_cast<std::uint32_t>(y * 64 + x));
        const glm::vec3 gathered(brute.at(glm::ivec2(x, y)));
        error += std::fabs(gathered.x + gathered.y + gathered.z - (mc.x + mc.y + mc.z));
        level += mc.x + mc.y + mc.z;
      }
    const double relative = error / level;
    MESSAGE("RSM " << rsm << "^2: brute-force gather with visibility vs Monte Carlo one bounce, mean absolute difference " << relative
                   << " of the mean level");
    CHECK(relative < previous);
    previous = relative;
  }
  CHECK(previous < 0.2);
}
