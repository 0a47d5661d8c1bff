// Properties of the RSM gather (include/vplkit/rsm_gather.hpp), the shadow density (Alg. 4,
// include/vplkit/shadow.hpp), the bilateral post filter (include/vplkit/bilateral.hpp) and the
// RSM flux of the lights (include/vplkit/direct_light.hpp), on synthetic RSMs.
#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/bilateral.hpp>
#include <vplkit/direct_light.hpp>
#include <vplkit/rsm_gather.hpp>
#include <vplkit/shadow.hpp>

#include "tests/closed_forms.hpp"

using namespace vplkit;

namespace {

constexpr int rsm_size = 256;
constexpr double texel = 0.02;   // world units per RSM texel: the RSM covers 5.12 x 5.12
constexpr double light_height = 10.0;

// An orthographic light looking straight down (-y) at the origin; eye space x = world x,
// eye y = -world z, eye z = world y - light_height.
glm::dmat4 light_view() { return glm::lookAt(glm::dvec3(0, light_height, 0), glm::dvec3(0), glm::dvec3(0, 0, -1)); }
glm::dmat4 light_view_projection() {
  const double half = 0.5 * rsm_size * texel;
  return glm::ortho(-half, half, -half, half, 0.1, 20.0) * light_view();
}

// A synthetic RSM: a floor at y = 0 (normal up) with flux 1 per texel, and optionally a block
// [x0, x1] x [0, height] x all z standing on it, seen from above as its top face.
struct synthetic_rsm {
  double block_x0 = 1e9, block_x1 = 1e9, block_height = 0.0;
  bool in_block(double x) const { return x >= block_x0 && x <= block_x1; }
  glm::dvec3 world_of(glm::ivec2 t) const {
    return {(t.x + 0.5 - rsm_size / 2) * texel, 0.0, -(t.y + 0.5 - rsm_size / 2) * texel};
  }
  rsm_texel<double> operator()(glm::ivec2 t) const {
    glm::dvec3 p = world_of(t);
    if (in_block(p.x)) p.y = block_height;
    return {p, p.y - light_height, glm::dvec3(0, 1, 0), glm::dvec3(1.0)};
  }
};

rsm_gather_settings<double> gather_settings() {
  rsm_gather_settings<double> settings;
  radial_pattern_settings<double> radial;
  radial.paths = 32;
  radial.samples_per_path = 16;
  radial.max_radius = 120.0;
  settings.radial = make_radial_pattern_constants(radial);
  settings.light_view = light_view();
  settings.rsm_size = glm::ivec2(rsm_size);
  return settings;
}

// A receiver at height h above the floor, facing down (the underside of a table).
gather_receiver<double> receiver_at(glm::dvec3 position, glm::uvec2 pixel) {
  return {position, glm::dvec3(0, -1, 0), glm::dvec2(map_coordinate(light_view_projection(), position, glm::ivec2(rsm_size))), pixel};
}

template <rsm_visibility V>
glm::dvec3 gather(const synthetic_rsm& rsm, const gather_receiver<double>& receiver) {
  return gather_rsm<rsm_pattern::radial, V>(receiver, rsm, gather_settings());
}

}  // namespace

TEST_CASE("gather of a uniform floor matches the closed form of a Lambertian disk source") {
  // A receiver at height h over an infinite Lambertian floor of radiosity B = flux / texel area
  // gets E = B within the sampled annulus [r_min, r_max] (texels -> world):
  //   E = B h^2 (1 / (h^2 + a^2) - 1 / (h^2 + b^2)) ... times pi / pi (Eq. 3.2 + the gather's 1/pi).
  const synthetic_rsm floor;
  const double h = 0.3;
  double mean = 0.0;
  const int receivers = 64;
  for (int i = 0; i < receivers; ++i) mean += gather<rsm_visibility::none>(floor, receiver_at({0.0, h, 0.0}, glm::uvec2(i, 0))).x;
  mean /= receivers;
  const double radiosity = 1.0 / (texel * texel);
  const double a = gather_settings().radial.min_radius * texel, b = 120.0 * texel;
  const double exact = radiosity * h * h * (1.0 / (h * h + a * a) - 1.0 / (h * h + b * b));
  CAPTURE(mean);
  CAPTURE(exact);
  CHECK(mean == doctest::Approx(exact).epsilon(0.03));
}

TEST_CASE("with no occluder, Alg. 6 and Alg. 3 equal no visibility exactly") {
  // Over a plane the samples of a path fall in elevation slots that never decrease: each slot is
  // claimed by its first sample, the following ones in it are its neighbours (Alg. 3's
  // propagation), so nothing is occluded. (Alg. 2, without the propagation, occludes them: the
  // Fig. 3.4 artefact.)
  const synthetic_rsm floor;
  for (unsigned i = 0; i < 32; ++i) {
    const gather_receiver<double> receiver = receiver_at({0.1 * i - 1.0, 0.3, 0.05 * i}, glm::uvec2(i, 1));
    const glm::dvec3 none = gather<rsm_visibility::none>(floor, receiver);
    REQUIRE(gather<rsm_visibility::alg6>(floor, receiver) == none);
    REQUIRE(gather<rsm_visibility::alg3>(floor, receiver) == none);
    REQUIRE(gather<rsm_visibility::alg2>(floor, receiver).x < 0.5 * none.x);
  }
}

TEST_CASE("a receiver behind the light (no projection onto the RSM) gathers nothing") {
  const synthetic_rsm floor;
  // Above the light (eye z > 0): its perspective projection would be mirrored.
  const gather_receiver<double> above = receiver_at({0.2, light_height + 1.0, 0.1}, glm::uvec2(1, 1));
  CHECK(gather<rsm_visibility::none>(floor, above) == glm::dvec3(0.0));
  CHECK(gather<rsm_visibility::alg6>(floor, above) == glm::dvec3(0.0));
}

TEST_CASE("visibility never adds light") {
  synthetic_rsm scene;
  scene.block_x0 = 0.2;
  scene.block_x1 = 0.6;
  scene.block_height = 0.8;
  for (unsigned i = 0; i < 64; ++i) {
    const gather_receiver<double> receiver = receiver_at({0.03 * i - 1.0, 0.1 + 0.01 * i, 0.02 * i - 0.5}, glm::uvec2(i, 2));
    const double none = gather<rsm_visibility::none>(scene, receiver).x;
    REQUIRE(gather<rsm_visibility::alg2>(scene, receiver).x <= none);
    REQUIRE(gather<rsm_visibility::alg3>(scene, receiver).x <= none);
    REQUIRE(gather<rsm_visibility::alg6>(scene, receiver).x <= none);
  }
}

TEST_CASE("a block between a receiver and the far floor: Alg. 6 removes the share of light the block hides") {
  // A low receiver on a wall facing +x (x = 0, 0.05 above the floor) is lit by the floor in
  // front of it. A block from x = 0.3 to 0.5, 0.6 high, hides the floor beyond it. Along a path
  // towards +x the near floor fills the lowest elevation slots, the block's top claims a high
  // one and interrupts the run, so the far floor, back in a slot already claimed, is occluded.
  // (What the approximation cannot see: an occluder whose top is not in the RSM sample's slot
  // and no nearer sample in that slot; a receiver high above the floor behind a block is such a
  // case, the micro linear buffer then leaks.)
  synthetic_rsm scene;
  scene.block_x0 = 0.3;
  scene.block_x1 = 0.5;
  scene.block_height = 0.6;
  const synthetic_rsm open_floor;
  double removed = 0.0, ratio = 0.0;
  const int receivers = 32;
  for (int i = 0; i < receivers; ++i) {
    gather_receiver<double> receiver = receiver_at({0.0, 0.05, 0.01 * i - 0.16}, glm::uvec2(static_cast<unsigned>(i), 3u));
    receiver.normal = glm::dvec3(1, 0, 0);
    // Exact visibility: the floor beyond the block's near face is hidden (the block is taller
    // than the receiver), everything in front of it is seen.
    const auto seen_floor = [&](glm::ivec2 t) {
      rsm_texel<double> light = open_floor(t);
      if (light.position.x >= scene.block_x0) light.flux = glm::dvec3(0.0);
      return light;
    };
    const double none = gather<rsm_visibility::none>(scene, receiver).x;
    const double alg6 = gather<rsm_visibility::alg6>(scene, receiver).x;
    const double exact = gather_rsm<rsm_pattern::radial, rsm_visibility::none>(receiver, seen_floor, gather_settings()).x;
    REQUIRE(none > exact);
    removed += (none - alg6) / (none - exact);
    ratio += alg6 / exact;
  }
  removed /= receivers;
  ratio /= receivers;
  MESSAGE("hidden light removed by Alg. 6: " << removed << ", Alg. 6 / exact visibility: " << ratio);
  // Measured: 0.998 of the hidden light removed, 1.0002 of the exact value kept. The bounds
  // leave room for other seeds: 90% of the hidden light goes, the seen light stays within 5%.
  CHECK(removed > 0.9);
  CHECK(ratio > 0.95);
  CHECK(ratio < 1.05);
}

TEST_CASE("Alg. 4: a flat lit floor is lit, an occluder's shadow is dark, the window softens the edge") {
  // Depths of the synthetic scene: floor at y = 0 (eye depth -10), block top at eye depth -9.2.
  synthetic_rsm scene;
  scene.block_x0 = 0.3;
  scene.block_x1 = 0.8;
  scene.block_height = 0.8;
  const auto depth = [&](glm::ivec2 t) { return scene(t).eye_depth; };
  const shadow_density_settings<double> settings;  // kernel 4, bias 0.02
  const auto density_at = [&](double x) {
    const glm::dvec3 floor_point(x, 0.0, 0.1);
    return shadow_density(map_coordinate(light_view_projection(), floor_point, glm::ivec2(rsm_size)), floor_point.y - light_height,
                          glm::dvec2(0.0), depth, glm::ivec2(rsm_size), settings);
  };
  CHECK(density_at(-1.0) == 1.0);  // open floor
  CHECK(density_at(0.5) == 0.0);   // under the block (the light looks straight down)
  const double edge = density_at(0.3);  // straddling the block's edge: partly shadowed
  CHECK(edge > 0.0);
  CHECK(edge < 1.0);
  // The block's own top is lit: its window sees only itself (and the lower floor beyond it).
  const glm::dvec3 top(0.55, 0.8, 0.1);
  CHECK(shadow_density(map_coordinate(light_view_projection(), top, glm::ivec2(rsm_size)), top.y - light_height, glm::dvec2(0.0), depth,
                       glm::ivec2(rsm_size), settings) == 1.0);
  // Outside the RSM counts as not lit (Alg. 4, line 5).
  CHECK(shadow_density(glm::dvec2(-10.0), -10.0, glm::dvec2(0.0), depth, glm::ivec2(rsm_size), settings) == 0.0);
}

TEST_CASE("Alg. 4: the receiver-plane gradient removes self-shadowing of a slope; without it the slope shadows itself") {
  // A slope whose depth falls 0.05 per RSM texel in x: a 4 x 4 window spans 0.2 of depth.
  const auto slope_depth = [](glm::ivec2 t) { return -10.0 - 0.05 * (t.x + 0.5 - 128.0); };
  const shadow_density_settings<double> settings;
  const glm::dvec2 centre(128.3, 100.6);
  const double receiver = -10.0 - 0.05 * (centre.x - 128.0);
  CHECK(shadow_density(centre, receiver, glm::dvec2(-0.05, 0.0), slope_depth, glm::ivec2(256), settings) == 1.0);
  CHECK(shadow_density(centre, receiver, glm::dvec2(0.0), slope_depth, glm::ivec2(256), settings) < 1.0);
}

TEST_CASE("bilateral filter keeps a constant image and does not blur across a depth edge") {
  const glm::ivec2 size(32, 32);
  bilateral_settings<double> settings;
  // Constant irradiance on one plane: unchanged.
  const auto constant = [](glm::ivec2) { return bilateral_tap<double>{glm::dvec3(0.7, 0.2, 0.1), -5.0, glm::dvec3(0, 0, 1)}; };
  const glm::dvec3 kept = bilateral_filter(glm::dvec2(10.5, 20.5), -5.0, glm::dvec3(0, 0, 1), constant, size, settings);
  CHECK(kept.x == doctest::Approx(0.7).epsilon(1e-12));
  CHECK(kept.y == doctest::Approx(0.2).epsilon(1e-12));
  // Left half near (depth -5, irradiance 1), right half far (depth -10, irradiance 0): a pixel
  // next to the edge on the near side keeps its value; a plain blur would mix in about 0.4.
  const auto step = [](glm::ivec2 t) {
    return t.x < 16 ? bilateral_tap<double>{glm::dvec3(1.0), -5.0, glm::dvec3(0, 0, 1)}
                    : bilateral_tap<double>{glm::dvec3(0.0), -10.0, glm::dvec3(0, 0, 1)};
  };
  CHECK(bilateral_filter(glm::dvec2(15.5, 16.5), -5.0, glm::dvec3(0, 0, 1), step, size, settings).x > 0.999);
  CHECK(bilateral_filter(glm::dvec2(16.5, 16.5), -10.0, glm::dvec3(0, 0, 1), step, size, settings).x < 0.001);
  // The same across a crease (normals at 90 degrees, equal depth).
  const auto crease = [](glm::ivec2 t) {
    return t.x < 16 ? bilateral_tap<double>{glm::dvec3(1.0), -5.0, glm::dvec3(0, 0, 1)}
                    : bilateral_tap<double>{glm::dvec3(0.0), -5.0, glm::dvec3(1, 0, 0)};
  };
  CHECK(bilateral_filter(glm::dvec2(15.5, 16.5), -5.0, glm::dvec3(0, 0, 1), crease, size, settings).x == doctest::Approx(1.0));
  // Separable: each axis alone keeps the constant too.
  CHECK(bilateral_filter_axis(glm::dvec2(3.5, 3.5), -5.0, glm::dvec3(0, 0, 1), constant, size, 0, settings).z ==
        doctest::Approx(0.1).epsilon(1e-12));
  // Weights: spatial Gaussian (exp(-1/2) at one sigma), relative depth, normal power.
  CHECK(bilateral_weight(glm::dvec2(4.0, 0.0), -5.0, -5.0, glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1), settings) ==
        doctest::Approx(std::exp(-0.5)).epsilon(1e-12));
  CHECK(bilateral_weight(glm::dvec2(0.0), -10.0, -10.5, glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1), settings) ==
        doctest::Approx(std::exp(-0.5)).epsilon(1e-12));  // 5% of the depth = one depth sigma
  const glm::dvec3 tilted(std::sin(0.5), 0.0, std::cos(0.5));
  CHECK(bilateral_weight(glm::dvec2(0.0), -5.0, -5.0, glm::dvec3(0, 0, 1), tilted, settings) ==
        doctest::Approx(std::pow(std::cos(0.5), 8)).epsilon(1e-12));
}

TEST_CASE("RSM flux: the texels of a spot light's RSM cover the frustum's solid angle") {
  // A square frustum of half-angle a subtends 4 asin(sin^2 a); the texel solid angles must add
  // up to it (a midpoint rule of the exact cos^3 density).
  for (double half_angle : {0.3, 0.7, 1.2}) {
    const double t = std::tan(half_angle);
    const int size = 256;
    double total = 0.0;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const glm::dvec2 ndc((x + 0.5) / size * 2 - 1, (y + 0.5) / size * 2 - 1);
        total += perspective_texel_solid_angle(ndc, t, glm::ivec2(size));
      }
    const double exact = 4.0 * std::asin(std::sin(half_angle) * std::sin(half_angle));
    CAPTURE(half_angle);
    CHECK(total == doctest::Approx(exact).epsilon(1e-4));
  }
  // A texel flux is albedo * I * cone * solid angle, and nothing for a surface facing away.
  spot_light<double> light;
  light.position = {0, 2, 0};
  light.intensity = glm::dvec3(5.0);
  const glm::dvec3 albedo(0.5), below(0, 0, 0);
  const double omega = perspective_texel_solid_angle(glm::dvec2(0.0), 1.0, glm::ivec2(64));
  CHECK(spot_light_texel_flux(albedo, below, glm::dvec3(0, 1, 0), light, glm::dvec2(0.0), 1.0, glm::ivec2(64)).x ==
        doctest::Approx(0.5 * 5.0 * omega));
  CHECK(spot_light_texel_flux(albedo, below, glm::dvec3(0, -1, 0), light, glm::dvec2(0.0), 1.0, glm::ivec2(64)).x == 0.0);
  directional_light<double> sun;
  sun.irradiance = glm::dvec3(2.0);
  CHECK(directional_light_texel_flux(albedo, glm::dvec3(0, 1, 0), sun, 0.01).y == doctest::Approx(0.01));
  CHECK(directional_light_texel_flux(albedo, glm::dvec3(0, -1, 0), sun, 0.01).y == 0.0);
  CHECK(directional_light_irradiance(glm::dvec3(0, 1, 0), sun).z == doctest::Approx(2.0));
}

namespace {

// A flat floor lit uniformly, seen by an orthographic light from straight above, covering
// [-1, 1]^2 with `size`^2 texels of flux `flux_per_texel` each.
struct flat_rsm {
  int size;
  double flux_per_texel;
  double texel() const { return 2.0 / size; }
  glm::dvec3 world_of(glm::ivec2 t) const { return {(t.x + 0.5) * texel() - 1.0, 0.0, 1.0 - (t.y + 0.5) * texel()}; }
  rsm_texel<double> operator()(glm::ivec2 t) const { return {world_of(t), -light_height, glm::dvec3(0, 1, 0), glm::dvec3(flux_per_texel)}; }
  glm::dmat4 view_projection() const { return glm::ortho(-1.0, 1.0, -1.0, 1.0, 0.1, 20.0) * light_view(); }
};

}  // namespace

TEST_CASE("at the default settings the radial gather finds the light of the whole RSM (within 10 %), whatever the RSM's size") {
  // The defaults scale the radius with the RSM (default_rsm_gather_settings). Over a uniformly
  // lit flat RSM, the mean of the gather over 256 receivers' patterns (the expectation over the
  // per-pixel rotation and scale) is compared with the brute-force sum over every texel, for a
  // receiver facing the floor near the RSM's centre and near a corner, at two heights.
  for (int size : {128, 256, 512}) {
    const flat_rsm floor{size, 4.0 / (size * size)};  // the same total flux at every size
    rsm_gather_settings<double> settings = default_rsm_gather_settings<double>(glm::ivec2(size));
    settings.light_view = light_view();
    for (double height : {0.1, 0.5})
      for (glm::dvec2 where : {glm::dvec2(0.05, -0.1), glm::dvec2(-0.7, 0.65)}) {
        const glm::dvec3 position(where.x, height, where.y), normal(0, -1, 0);
        double brute_force = 0.0;
        for (int y = 0; y < size; ++y)
          for (int x = 0; x < size; ++x) {
            const rsm_texel<double> light = floor(glm::ivec2(x, y));
            brute_force += pixel_light_irradiance(position, normal, light.position, light.normal, light.flux, settings.irradiance).x;
          }
        brute_force /= 3.14159265358979323846;
        double mean = 0.0;
        const int receivers = 256;
        for (int i = 0; i < receivers; ++i) {
          const gather_receiver<double> receiver{position, normal, map_coordinate(floor.view_projection(), position, glm::ivec2(size)),
                                                 glm::uvec2(static_cast<unsigned>(i), 7u)};
          mean += gather_rsm<rsm_pattern::radial, rsm_visibility::none>(receiver, floor, settings).x / receivers;
        }
        CAPTURE(size);
        CAPTURE(height);
        CAPTURE(where.x);
        CAPTURE(mean);
        CAPTURE(brute_force);
        CHECK(std::fabs(mean / brute_force - 1.0) < 0.1);
      }
  }
}

TEST_CASE("the thesis's radius (1/8 of the RSM) misses much of a low receiver's light; the default does not") {
  // The reason the default radius changed: a receiver 0.5 above a 2 x 2 lit floor gets most of
  // its light from beyond 1/8 of the RSM (64 of 512 texels = 0.25 units).
  const int size = 512;
  const flat_rsm floor{size, 4.0 / (size * size)};
  const glm::dvec3 position(0.0, 0.5, 0.0), normal(0, -1, 0);
  const auto mean_gather = [&](const rsm_gather_preset<double>& preset) {
    rsm_gather_settings<double> settings = rsm_gather_settings_from(preset, glm::ivec2(size));
    settings.light_view = light_view();
    double mean = 0.0;
    for (unsigned i = 0; i < 128; ++i)
      mean += gather_rsm<rsm_pattern::radial, rsm_visibility::none>(
                  {position, normal, map_coordinate(floor.view_projection(), position, glm::ivec2(size)), glm::uvec2(i, 9u)}, floor, settings).x / 128.0;
    return mean;
  };
  // The floor's radiosity is 1 (flux 4 over area 4), so the receiver gets its form factor to the
  // 2 x 2 floor: four 1 x 1 rectangles with a corner below it (Howell B-3).
  const double whole_floor = 4.0 * closed_forms::parallel_rectangle(1.0, 1.0, 0.5);
  CHECK(mean_gather(thesis_rsm_gather_preset<double>()) < 0.35 * whole_floor);
  CHECK(mean_gather(default_rsm_gather_preset<double>()) == doctest::Approx(whole_floor).epsilon(0.1));
}

TEST_CASE("at the default settings, Alg. 6 removes most of the light a block hides and keeps the light it does not") {
  // The block scene of the test above, with the default settings of a 256^2 RSM instead of the
  // test's own: the stated shares are what the defaults must deliver on this configuration.
  synthetic_rsm scene;
  scene.block_x0 = 0.3;
  scene.block_x1 = 0.5;
  scene.block_height = 0.6;
  const synthetic_rsm open_floor;
  rsm_gather_settings<double> settings = default_rsm_gather_settings<double>(glm::ivec2(rsm_size));
  settings.light_view = light_view();
  double hidden = 0.0, hidden_kept = 0.0, seen = 0.0, seen_kept = 0.0;
  for (int i = 0; i < 32; ++i) {
    gather_receiver<double> receiver = receiver_at({0.0, 0.05, 0.01 * i - 0.16}, glm::uvec2(static_cast<unsigned>(i), 4u));
    receiver.normal = glm::dvec3(1, 0, 0);
    // The two regions: the floor beyond the block's near face (hidden) and in front of it
    // (seen), each alone carrying flux, the geometry (and so the buffer's verdicts) unchanged.
    const auto only = [&](bool beyond) {
      return [&, beyond](glm::ivec2 t) {
        rsm_texel<double> light = scene(t);
        const bool is_beyond = open_floor(t).position.x >= scene.block_x0;
        if (is_beyond != beyond || scene.in_block(light.position.x)) light.flux = glm::dvec3(0.0);
        return light;
      };
    };
    hidden += gather_rsm<rsm_pattern::radial, rsm_visibility::none>(receiver, only(true), settings).x;
    hidden_kept += gather_rsm<rsm_pattern::radial, rsm_visibility::alg6>(receiver, only(true), settings).x;
    seen += gather_rsm<rsm_pattern::radial, rsm_visibility::none>(receiver, only(false), settings).x;
    seen_kept += gather_rsm<rsm_pattern::radial, rsm_visibility::alg6>(receiver, only(false), settings).x;
  }
  MESSAGE("defaults: Alg. 6 keeps " << hidden_kept / hidden << " of the hidden light and " << seen_kept / seen << " of the seen light");
  REQUIRE(hidden > 0.0);
  REQUIRE(seen > 0.0);
  CHECK(hidden_kept / hidden < 0.2);
  CHECK(seen_kept / seen > 0.9);
}
