// The CPU reference (frontend/reference/reference.hpp): closed forms for the direct light and for one
// bounce off a uniformly lit floor, determinism, and the brute-force RSM gather with visibility
// converging to the RSM-free Monte Carlo reference as the RSM resolution grows; the brute force
// against the polygon form factor, with and without a known occluder, and the pattern's own
// samples with ray-cast visibility.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/direct_light.hpp>
#include <vplkit/parity/parity.hpp>

#include "frontend/core/error.hpp"
#include "frontend/reference/reference.hpp"
#include "frontend/techniques/rsm/rsm_cpu_mirror.hpp"
#include "frontend/techniques/rsm/rsm_pipeline.hpp"
#include "tests/closed_forms.hpp"

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
  const std::vector<scene_light> lights{light};
  const ray_scene rays(floor);
  const int samples = 20000;
  const glm::vec3 e = one_bounce_irradiance(rays, lights, {}, glm::vec3(0, h, 0), glm::vec3(0, -1, 0), samples, 7u, 1u);
  const double exact = albedo * 2.0 * 4.0 * parallel_rectangle(a, a, h);
  // A Bernoulli estimate of F (hit or miss) times a constant: sigma = sqrt(F (1 - F) / N).
  const double f = exact / (albedo * 2.0);
  const double sigma = albedo * 2.0 * std::sqrt(f * (1 - f) / samples);
  CAPTURE(e.x);
  CAPTURE(exact);
  CHECK(std::fabs(e.x - exact) < 4.0 * sigma);
  // Deterministic for a seed, different for another.
  CHECK(one_bounce_irradiance(rays, lights, {}, glm::vec3(0, h, 0), glm::vec3(0, -1, 0), 256, 7u, 1u) ==
        one_bounce_irradiance(rays, lights, {}, glm::vec3(0, h, 0), glm::vec3(0, -1, 0), 256, 7u, 1u));
  CHECK(one_bounce_irradiance(rays, lights, {}, glm::vec3(0, h, 0), glm::vec3(0, -1, 0), 256, 7u, 1u) !=
        one_bounce_irradiance(rays, lights, {}, glm::vec3(0, h, 0), glm::vec3(0, -1, 0), 256, 8u, 1u));
}

TEST_CASE("the brute-force RSM gather with visibility converges to the Monte Carlo one-bounce reference as the RSM grows" * doctest::test_suite("slow")) {
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
    rsm_brute_force_options options;
    options.exact_visibility = true;
    options.threads = 2;
    const image brute = reference_rsm_gather(rays, buffers, pipeline.constants(), options);
    double error = 0.0, level = 0.0;
    for (int y = 0; y < brute.height; ++y)
      for (int x = 0; x < brute.width; ++x) {
        const glm::ivec2 sample = glm::min(glm::ivec2(x, y) * 2, glm::ivec2(23));
        const glm::vec4 position_depth = buffers.gbuffer[0].at(sample);
        if (!(position_depth.w < 0.0f)) continue;
        const glm::vec3 p(position_depth), n(buffers.gbuffer[2].at(sample));
        const glm::vec3 mc = one_bounce_irradiance(rays, box.lights, {}, p, n, 512, 3u, static_cast<std::uint32_t>(y * 64 + x));
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

namespace {

// A synthetic frame for the brute-force RSM gather: an RSM of n x n texels showing a 2a x 2a
// floor at y = 0 lit uniformly (flux per texel = radiosity x texel area), seen by an orthographic
// light from straight above, and one receiver at height h facing down over the floor's centre.
struct floor_frame {
  rsm_pass_buffers buffers;
  rsm_frame_constants constants;
  floor_frame(int n, float a, float h, float radiosity) {
    const float texel = 2.0f * a / static_cast<float>(n);
    // Every texel: the floor 5 below the light (eye depth -5), its normal towards the light
    // (eye +z); the positions come back from the centre rays of the orthographic unprojection.
    buffers.rsm.width = buffers.rsm.height = n;
    buffers.rsm.texels.assign(static_cast<std::size_t>(n) * static_cast<std::size_t>(n),
                              pack_rsm_texel(-5.0f, glm::vec3(0, 0, 1), glm::vec3(radiosity * texel * texel)));
    for (int i = 0; i < 3; ++i) {
      buffers.gbuffer[i].width = buffers.gbuffer[i].height = 1;
      buffers.gbuffer[i].texels.assign(1, glm::vec4(0.0f));
    }
    buffers.gbuffer[0].texels[0] = glm::vec4(0.0f, h, 0.0f, -3.0f);
    buffers.gbuffer[2].texels[0] = glm::vec4(0.0f, -1.0f, 0.0f, 0.0f);
    const glm::mat4 view = glm::lookAt(glm::vec3(0, 5, 0), glm::vec3(0), glm::vec3(0, 0, -1));
    constants.light.view = view;
    constants.light.view_projection = glm::ortho(-a, a, -a, a, 0.1f, 20.0f) * view;
    constants.unprojection = make_rsm_unprojection(a, false, glm::ivec2(n));
    constants.gather.rsm_size = glm::ivec2(n);
    constants.gather.irradiance.min_distance = 1e-4f;
    constants.image_size = constants.indirect_size = glm::ivec2(1);
    constants.indirect_divisor = 1;
  }
};

}  // namespace

TEST_CASE("brute-force RSM gather: a receiver facing a uniformly lit square floor gets the polygon form factor (Howell B-3)") {
  const float a = 1.0f, h = 0.5f, radiosity = 2.0f;
  const floor_frame frame(256, a, h, radiosity);
  mesh floor;
  add_quad(floor, {-a, 0, a}, {a, 0, a}, {a, 0, -a}, {-a, 0, -a}, {0, 1, 0}, glm::vec3(0.5f));
  const ray_scene rays(floor);
  rsm_brute_force_options options;
  options.threads = 2;
  // E = B F for a Lambertian source of radiosity B; F of the square = 4 x B-3 with a corner below.
  const double exact = radiosity * 4.0 * parallel_rectangle(a, a, h);
  const glm::vec4 none = reference_rsm_gather(rays, frame.buffers, frame.constants, options).texels[0];
  CHECK(none.x == doctest::Approx(exact).epsilon(2e-3));
  CHECK(none.w == 1.0f);
  // Nothing between the receiver and the floor: exact visibility keeps everything.
  options.exact_visibility = true;
  const glm::vec4 seen = reference_rsm_gather(rays, frame.buffers, frame.constants, options).texels[0];
  CHECK(seen.x == doctest::Approx(exact).epsilon(2e-3));
  // Cut to a radius of r texels: a coaxial disk of radius R = r x texel, F = R^2 / (R^2 + h^2).
  options.exact_visibility = false;
  options.max_radius = 64.0f;
  const double disk_radius = 64.0 * 2.0 * a / 256.0;
  const glm::vec4 cut = reference_rsm_gather(rays, frame.buffers, frame.constants, options).texels[0];
  CHECK(cut.x == doctest::Approx(radiosity * disk_radius * disk_radius / (disk_radius * disk_radius + h * h)).epsilon(5e-3));
}

TEST_CASE("brute-force RSM gather with exact visibility: a square occluder halfway up hides the floor square twice its size") {
  // An occluder [-b, b]^2 at height h/2 (in the ray scene only: the light does not see it, so
  // the RSM is still the whole floor): from the receiver at height h it hides [-2b, 2b]^2 of the
  // floor, so the visible irradiance is B (F(a) - F(2b)).
  const float a = 1.0f, h = 0.5f, b = 0.2f, radiosity = 2.0f;
  const floor_frame frame(256, a, h, radiosity);
  mesh scene;
  add_quad(scene, {-a, 0, a}, {a, 0, a}, {a, 0, -a}, {-a, 0, -a}, {0, 1, 0}, glm::vec3(0.5f));
  add_quad(scene, {-b, h / 2, b}, {b, h / 2, b}, {b, h / 2, -b}, {-b, h / 2, -b}, {0, 1, 0}, glm::vec3(0.5f));
  const ray_scene rays(scene);
  rsm_brute_force_options options;
  options.exact_visibility = true;
  options.threads = 2;
  const glm::vec4 seen = reference_rsm_gather(rays, frame.buffers, frame.constants, options).texels[0];
  const double whole = 4.0 * parallel_rectangle(a, a, h), hidden = 4.0 * parallel_rectangle(2 * b, 2 * b, h);
  CHECK(seen.x == doctest::Approx(radiosity * (whole - hidden)).epsilon(1e-2));
  CHECK(seen.w == doctest::Approx((whole - hidden) / whole).epsilon(1e-2));
  // The receiver stride leaves the receivers it skips at 0 (here, none: one receiver).
  options.receiver_stride = 0;
  CHECK_THROWS_AS(reference_rsm_gather(rays, frame.buffers, frame.constants, options), vplkit::error);
}

TEST_CASE("the radial pattern's own samples with ray-cast visibility: no occluder equals the gather, an occluder removes its share") {
  const float a = 1.0f, h = 0.5f, b = 0.2f, radiosity = 2.0f;
  floor_frame frame(256, a, h, radiosity);
  frame.constants.gather.radial = make_radial_pattern_constants(radial_pattern_settings<float>{32, 16, 1.0f, 256.0f});
  mesh floor;
  add_quad(floor, {-a, 0, a}, {a, 0, a}, {a, 0, -a}, {-a, 0, -a}, {0, 1, 0}, glm::vec3(0.5f));
  mesh blocked = floor;
  add_quad(blocked, {-b, h / 2, b}, {b, h / 2, b}, {b, h / 2, -b}, {-b, h / 2, -b}, {0, 1, 0}, glm::vec3(0.5f));
  const ray_scene open_rays(floor), blocked_rays(blocked);
  const image open = gather_with_ray_cast_visibility(open_rays, frame.buffers, frame.constants, 1, 1);
  const std::vector<rsm_texel<float>> rsm = unpack_rsm(frame.buffers, frame.constants);
  const auto fetch = [&](glm::ivec2 t) { return rsm[static_cast<std::size_t>(t.y) * 256u + static_cast<std::size_t>(t.x)]; };
  const gather_receiver<float> receiver = make_gather_receiver(glm::vec3(0, h, 0), glm::vec3(0, -1, 0), frame.constants.light.view,
                                                               frame.constants.light.view_projection, glm::ivec2(256), glm::uvec2(0));
  CHECK(open.texels[0].x == doctest::Approx(gather_rsm<rsm_pattern::radial, rsm_visibility::none>(receiver, fetch, frame.constants.gather).x));
  const image shadowed = gather_with_ray_cast_visibility(blocked_rays, frame.buffers, frame.constants, 1, 1);
  const double hidden_share = parallel_rectangle(2 * b, 2 * b, h) / parallel_rectangle(a, a, h);
  CHECK(shadowed.texels[0].x / open.texels[0].x == doctest::Approx(1.0 - hidden_share).epsilon(0.15));
}

TEST_CASE("the Monte Carlo reference lights the surface the camera sees on its normal's side, as the GL techniques do, and counts back faces") {
  // A square at z = 0 filling the view of a camera on +z. With its normal towards the camera and the
  // spot on the camera's side it is lit; reversed (normal -z) the camera sees its back and the lit
  // side is away from the light: black, every pixel counted. With the spot behind it, the reversed
  // square is lit on its normal's side though the camera sees its back: the G-buffer and the
  // direct light of every GL technique keep the normal, and so does the reference.
  const auto square = [](float normal_z, float light_z) {
    scene s;
    s.name = "square";
    if (normal_z > 0.0f) add_quad(s.geometry, {-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}, {0, 0, 1}, glm::vec3(0.5f));
    else add_quad(s.geometry, {-2, -2, 0}, {-2, 2, 0}, {2, 2, 0}, {2, -2, 0}, {0, 0, -1}, glm::vec3(0.5f));
    s.view.position = {0.0f, 0.0f, 3.0f};
    s.view.target = {0.0f, 0.0f, 0.0f};
    s.lights.emplace_back();
    s.lights[0].spot.position = {0.0f, 0.0f, light_z};
    s.lights[0].spot.direction = {0.0f, 0.0f, light_z > 0.0f ? -1.0f : 1.0f};
    s.lights[0].spot.intensity = glm::vec3(4.0f);
    s.lights[0].spot.cos_inner = std::cos(glm::radians(70.0f));
    s.lights[0].spot.cos_outer = std::cos(glm::radians(80.0f));
    return reference_one_bounce(s, 16, 16, 0, 1u, 1);
  };
  const one_bounce_images front = square(1.0f, 2.0f), back_dark = square(-1.0f, 2.0f), back_lit = square(-1.0f, -2.0f);
  CHECK(front.back_facing_pixels == 0);
  CHECK(back_dark.back_facing_pixels == 16 * 16);
  CHECK(back_lit.back_facing_pixels == 16 * 16);
  float front_sum = 0.0f, dark_max = 0.0f, lit_sum = 0.0f;
  for (std::size_t i = 0; i < front.radiance.texels.size(); ++i) {
    front_sum += front.radiance.texels[i].x;
    dark_max = std::max(dark_max, back_dark.radiance.texels[i].x);
    lit_sum += back_lit.radiance.texels[i].x;
  }
  CHECK(front_sum > 0.0f);
  CHECK(dark_max == 0.0f);
  // The spot 2 in front of the square's lit side either way: the same light, mirrored.
  CHECK(lit_sum == doctest::Approx(front_sum).epsilon(1e-4));
}

TEST_CASE("reference direct light of a point light: point_light_irradiance where unoccluded, 0 behind a wall") {
  mesh floor;
  add_quad(floor, {-5, 0, 5}, {5, 0, 5}, {5, 0, -5}, {-5, 0, -5}, {0, 1, 0}, glm::vec3(0.5f));
  scene_light bulb;
  bulb.kind = light_kind::point;
  bulb.point.position = {0.5f, 2.0f, -0.5f};
  bulb.point.intensity = {3.0f, 2.0f, 1.0f};
  const ray_scene rays(floor);
  for (const glm::vec3 x : {glm::vec3(0.0f), glm::vec3(1.5f, 0.0f, 0.5f), glm::vec3(-3.0f, 0.0f, 4.0f)}) {
    CAPTURE(x);
    const glm::vec3 expected = point_light_irradiance(x, glm::vec3(0, 1, 0), bulb.point);
    const glm::vec3 e = direct_irradiance(rays, bulb, {}, x, glm::vec3(0, 1, 0));
    REQUIRE(expected.x > 0.0f);
    for (int c = 0; c < 3; ++c) CHECK(e[c] == doctest::Approx(expected[c]).epsilon(1e-6));
  }
  // A wall at x = 1 between the bulb and the floor beyond it: no direct light there, light on the bulb's side.
  mesh walled = floor;
  add_quad(walled, {1, 0, -5}, {1, 0, 5}, {1, 4, 5}, {1, 4, -5}, {-1, 0, 0}, glm::vec3(0.5f));
  const ray_scene walled_rays(walled);
  CHECK(direct_irradiance(walled_rays, bulb, {}, glm::vec3(2.0f, 0.0f, -0.5f), glm::vec3(0, 1, 0)) == glm::vec3(0.0f));
  CHECK(direct_irradiance(walled_rays, bulb, {}, glm::vec3(0.0f, 0.0f, -0.5f), glm::vec3(0, 1, 0)).x > 0.0f);
  // Below the bulb's horizon (a receiver facing away from it): 0, as the kernel says.
  CHECK(direct_irradiance(rays, bulb, {}, glm::vec3(0.0f), glm::vec3(0, -1, 0)) == glm::vec3(0.0f));
}

TEST_CASE("the Monte Carlo reference is linear in the lights: two lights' images are the sum of each alone within float rounding") {
  // A floor and a back wall seen by the camera, a spot and a point light: the direct light and the
  // bounce both add up, with the same sample directions (they depend on the seed and the pixel only).
  scene s;
  s.name = "two lights";
  add_quad(s.geometry, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, {-2, 0, -2}, {0, 1, 0}, glm::vec3(0.7f));
  add_quad(s.geometry, {-2, 0, -2}, {2, 0, -2}, {2, 3, -2}, {-2, 3, -2}, {0, 0, 1}, glm::vec3(0.6f, 0.2f, 0.2f));
  s.view.position = {0.0f, 1.5f, 3.0f};
  s.view.target = {0.0f, 0.8f, -2.0f};
  scene_light spot;
  spot.spot.position = {-1.0f, 2.5f, 0.0f};
  spot.spot.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.4f));
  spot.spot.intensity = glm::vec3(4.0f);
  spot.spot.cos_inner = std::cos(glm::radians(30.0f));
  spot.spot.cos_outer = std::cos(glm::radians(50.0f));
  scene_light bulb;
  bulb.kind = light_kind::point;
  bulb.point.position = {1.0f, 1.0f, -1.0f};
  bulb.point.intensity = {1.0f, 2.0f, 3.0f};
  const auto render = [&](std::vector<scene_light> lights) {
    scene lit = s;
    lit.lights = std::move(lights);
    return reference_one_bounce(lit, 12, 10, 8, 3u, 1);
  };
  const one_bounce_images a = render({spot}), b = render({bulb}), both = render({spot, bulb});
  float largest = 0.0f;
  for (const glm::vec4& texel : both.radiance.texels) largest = std::max({largest, texel.x, texel.y, texel.z});
  REQUIRE(largest > 0.0f);
  double indirect_sum = 0.0;
  for (std::size_t i = 0; i < both.radiance.texels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const float sum = a.radiance.texels[i][c] + b.radiance.texels[i][c];
      CHECK(std::fabs(both.radiance.texels[i][c] - sum) <= 1e-5f * std::max(sum, 1e-3f * largest));
      const float indirect_sum_here = a.indirect.texels[i][c] + b.indirect.texels[i][c];
      CHECK(std::fabs(both.indirect.texels[i][c] - indirect_sum_here) <= 1e-5f * std::max(indirect_sum_here, 1e-3f * largest));
      indirect_sum += both.indirect.texels[i][c];
    }
  }
  CHECK(indirect_sum > 0.0);  // the bounce is there to be summed
}
