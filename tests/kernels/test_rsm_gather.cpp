// Properties of the RSM gather (include/vplkit/rsm_gather.hpp) on synthetic RSMs
// (tests/kernels/synthetic_rsm.hpp): closed forms, visibility that never adds light, and the
// share of the light the defaults find and remove.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/bilateral.hpp>
#include <vplkit/direct_light.hpp>
#include <vplkit/rsm_gather.hpp>
#include <vplkit/shadow.hpp>

#include "tests/closed_forms.hpp"
#include "tests/kernels/synthetic_rsm.hpp"

using namespace vplkit;
using namespace vplkit::testing;


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

TEST_CASE("the gather's light eye space changes nothing of Eq. 3.2: make_gather_receiver is a rigid move") {
  // The gather runs in the light's eye space; the light's view is a rigid motion, so every
  // distance and cosine of Eq. 3.2, and so the irradiance, is what it was in the world.
  const glm::dmat4 view = glm::lookAt(glm::dvec3(0.4, 3.0, 1.2), glm::dvec3(-0.2, 0.0, 0.1), glm::dvec3(0, 0, -1));
  const glm::dmat4 view_projection = glm::perspective(1.3, 1.0, 0.05, 20.0) * view;
  const irradiance_settings<double> settings;
  for (int i = 0; i < 200; ++i) {
    const double t = 0.37 * i;
    const glm::dvec3 x(std::sin(t), 0.1 * i / 200.0, std::cos(1.3 * t)), n = glm::normalize(glm::dvec3(std::sin(2 * t), 1.0, 0.3));
    const glm::dvec3 xp(std::cos(0.7 * t), 0.8, std::sin(1.9 * t)), np = glm::normalize(glm::dvec3(0.2, std::cos(t), std::sin(t)));
    const gather_receiver<double> receiver = make_gather_receiver(x, n, view, view_projection, glm::ivec2(512), glm::uvec2(0u));
    const rsm_texel<double> light{transform_point(view, xp), transform_direction(view, np), glm::dvec3(1.0)};
    const glm::dvec3 world = pixel_light_irradiance(x, n, xp, np, glm::dvec3(1.0), settings);
    const glm::dvec3 eye = pixel_light_irradiance(receiver.position, receiver.normal, light.position, light.normal, light.flux, settings);
    REQUIRE(std::fabs(eye.x - world.x) <= 1e-12 * std::max(1.0, world.x));
    REQUIRE(glm::length(receiver.normal) == doctest::Approx(1.0).epsilon(1e-12));
    REQUIRE(receiver.rsm_coordinate == map_coordinate(view_projection, x, glm::ivec2(512)));
  }
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

namespace {

// The coarse lights of a synthetic RSM, 16 x 16 blocks, and the brute force: every texel's Eq. 3.2.
struct coverage_of {
  std::vector<coarse_light<double>> lights;
  int blocks = 16;
  template <typename Rsm>
  explicit coverage_of(const Rsm& rsm) {
    for (int y = 0; y < blocks; ++y)
      for (int x = 0; x < blocks; ++x) lights.push_back(reduce_rsm_block<double>(glm::ivec2(x, y), blocks, glm::ivec2(rsm_size), rsm));
  }
  coarse_light<double> operator()(glm::ivec2 block) const { return lights[static_cast<std::size_t>(block.y * blocks + block.x)]; }
};

template <typename Rsm>
double brute_force(const Rsm& rsm, const gather_receiver<double>& receiver) {
  double sum = 0.0;
  for (int y = 0; y < rsm_size; ++y)
    for (int x = 0; x < rsm_size; ++x) {
      const rsm_texel<double> light = rsm(glm::ivec2(x, y));
      sum += pixel_light_irradiance(receiver.position, receiver.normal, light.position, light.normal, light.flux, irradiance_settings<double>{}).x;
    }
  return sum / 3.14159265358979323846;
}

}  // namespace

TEST_CASE("with coverage a receiver behind the light gets the light of the whole RSM; without, nothing") {
  const synthetic_rsm floor;
  const coverage_of coarse(floor);
  rsm_gather_settings<double> settings = gather_settings();
  settings.coverage_blocks = coarse.blocks;
  for (const glm::dvec3 where : {glm::dvec3(0.2, light_height + 1.0, 0.1), glm::dvec3(-1.5, light_height + 0.2, 2.0)}) {
    const gather_receiver<double> above = receiver_at(where, glm::uvec2(1, 1));
    REQUIRE(!(above.position.z < 0.0));
    const double covered = gather_rsm<rsm_pattern::radial, rsm_visibility::alg6>(above, floor, coarse, settings).x;
    CAPTURE(where.x);
    CHECK(covered == doctest::Approx(brute_force(floor, above)).epsilon(0.01));
    // The same settings without a coarse fetch, or with coverage off: the pattern alone, nothing.
    CHECK(gather_rsm<rsm_pattern::radial, rsm_visibility::alg6>(above, floor, settings) == glm::dvec3(0.0));
    settings.coverage_blocks = 0;
    CHECK(gather_rsm<rsm_pattern::radial, rsm_visibility::alg6>(above, floor, coarse, settings) == glm::dvec3(0.0));
    settings.coverage_blocks = coarse.blocks;
  }
}

namespace {

// The coverage of `coarse` with the lights on one side (x_c.x > 0, light eye space) dark.
struct coverage_without_right_half {
  const coverage_of& coarse;
  coarse_light<double> operator()(glm::ivec2 block) const {
    coarse_light<double> light = coarse(block);
    if (light.position.x > 0.0) light.flux = glm::dvec3(0.0);
    return light;
  }
};

template <rsm_pattern Pattern, rsm_visibility Visibility>
void check_coarse_visibility_taken() {
  const synthetic_rsm floor;
  const coverage_of coarse(floor);
  rsm_gather_settings<double> settings = gather_settings();
  settings.coverage_blocks = coarse.blocks;
  const gather_receiver<double> above = receiver_at({-1.5, light_height + 0.2, 2.0}, glm::uvec2(1, 1));
  REQUIRE(!(above.position.z < 0.0));  // the coverage alone
  int calls = 0;
  // Hides the coarse lights right of the light, and sees exactly the receiver's and the light's positions.
  const auto right_half_hidden = [&](const glm::dvec3& x, const glm::dvec3& x_c) {
    ++calls;
    CHECK(x == above.position);
    return x_c.x > 0.0 ? 0.0 : 1.0;
  };
  const glm::dvec3 seen = gather_rsm<Pattern, Visibility>(above, floor, coarse, right_half_hidden, settings);
  const glm::dvec3 open = gather_rsm<Pattern, Visibility>(above, floor, coarse, settings);
  const glm::dvec3 left_only = gather_rsm<Pattern, Visibility>(above, floor, coverage_without_right_half{coarse}, settings);
  REQUIRE(left_only.x < 0.9 * open.x);  // the hidden half carries light here
  CHECK(calls > 0);
  CHECK(seen.x == doctest::Approx(left_only.x).epsilon(1e-12));
  // Unoccluded, the coarse lights keep all their light: the weight is the visibility's alone.
  CHECK(gather_rsm<Pattern, Visibility>(above, floor, coarse, unoccluded_coarse_lights{}, settings) == open);
}

}  // namespace

TEST_CASE("gather_rsm's coarse visibility weighs the coarse lights for every visibility and both patterns (rsm-original to rsm-alg6-ray)") {
  // The coarse lights are vplkit's coverage, not the thesis's pattern: a point light's cube hides
  // them whatever visibility the pattern's samples get (errata RSMV-14); only rsm-voxel, whose grid
  // judges them, goes through gather_rsm_with instead.
  check_coarse_visibility_taken<rsm_pattern::disk, rsm_visibility::none>();
  check_coarse_visibility_taken<rsm_pattern::radial, rsm_visibility::none>();
  check_coarse_visibility_taken<rsm_pattern::radial, rsm_visibility::alg2>();
  check_coarse_visibility_taken<rsm_pattern::radial, rsm_visibility::alg3>();
  check_coarse_visibility_taken<rsm_pattern::radial, rsm_visibility::alg6>();
  check_coarse_visibility_taken<rsm_pattern::radial, rsm_visibility::alg6_ray>();
  for (const rsm_visibility visibility :
       {rsm_visibility::none, rsm_visibility::alg2, rsm_visibility::alg3, rsm_visibility::alg6, rsm_visibility::alg6_ray})
    CHECK(judges_coarse_lights_by_segment(visibility));
  CHECK_FALSE(judges_coarse_lights_by_segment(rsm_visibility::voxel));
}

TEST_CASE("the coverage interleaved over s x s pixels: the tile's mean is the whole coverage, each pixel a part of it") {
  // A receiver behind the light (the coverage alone) at every pixel of an s x s tile: each gathers
  // the blocks of its lattice times s^2, and the s^2 of them together every block once.
  const synthetic_rsm floor;
  const coverage_of coarse(floor);
  rsm_gather_settings<double> settings = gather_settings();
  settings.coverage_blocks = coarse.blocks;
  const glm::dvec3 where(0.2, light_height + 1.0, 0.1);
  const double whole = gather_rsm<rsm_pattern::radial, rsm_visibility::alg6>(receiver_at(where, glm::uvec2(5, 7)), floor, coarse, settings).x;
  REQUIRE(whole > 0.0);
  for (const int side : {2, 3, 4}) {
    CAPTURE(side);
    settings.coverage_interleave = side;
    double mean = 0.0, farthest = 0.0;
    for (unsigned y = 0; y < static_cast<unsigned>(side); ++y)
      for (unsigned x = 0; x < static_cast<unsigned>(side); ++x) {
        // Pixels of a tile far from the origin: the phase is the pixel modulo the side.
        const glm::uvec2 pixel(40u * static_cast<unsigned>(side) + x, 9u * static_cast<unsigned>(side) + y);
        const double part = gather_rsm<rsm_pattern::radial, rsm_visibility::alg6>(receiver_at(where, pixel), floor, coarse, settings).x;
        mean += part / static_cast<double>(side * side);
        farthest = std::max(farthest, std::abs(part - whole) / whole);
      }
    CHECK(mean == doctest::Approx(whole).epsilon(1e-12));
    CHECK(farthest > 1e-3);  // a pixel gathers a part, not the whole
  }
  settings.coverage_interleave = 1;
  CHECK(gather_rsm<rsm_pattern::radial, rsm_visibility::alg6>(receiver_at(where, glm::uvec2(1, 2)), floor, coarse, settings).x == whole);
  CHECK(validate_coverage_interleave(1) == nullptr);
  CHECK(validate_coverage_interleave(8) == nullptr);
  CHECK(validate_coverage_interleave(0) != nullptr);
  CHECK(validate_coverage_interleave(9) != nullptr);
  // An interleave wider than the blocks leaves some receivers' lattices empty: the settings refuse it.
  settings.coverage_blocks = 4;
  settings.coverage_interleave = 5;
  CHECK(std::string(validate(settings).message()).find("coverage_interleave must not exceed coverage_blocks") != std::string::npos);
  settings.coverage_interleave = 4;
  CHECK(!validate(settings));
  settings.coverage_blocks = 0;  // no coverage: no lattice to fill
  settings.coverage_interleave = 8;
  CHECK(!validate(settings));
}

TEST_CASE("with coverage a receiver off the map gets what the pattern reaches plus the blocks beyond it: the whole RSM's light") {
  // Receivers beside the RSM (eye x beyond its edge), facing it, at 0.4 above the floor: the
  // pattern reaches the near part of the map, the blocks beyond its radius add the rest. The mean
  // over 64 receivers' patterns matches the brute force within 5 %, four times nearer than the
  // pattern alone (which misses 10 % at 12 texels off the map, more farther out). Inside the map
  // the coverage changes nothing.
  const synthetic_rsm floor;
  const coverage_of coarse(floor);
  rsm_gather_settings<double> settings = gather_settings();
  settings.coverage_blocks = coarse.blocks;
  for (const double x : {2.8, 4.0}) {
    double with = 0.0, without = 0.0, exact = 0.0;
    for (unsigned i = 0; i < 64; ++i) {
      const gather_receiver<double> beside = receiver_at({x, 0.4, 0.03 * i - 1.0}, glm::uvec2(i, 3), glm::normalize(glm::dvec3(-1.0, -0.3, 0.0)));
      REQUIRE(beside.rsm_coordinate.x > rsm_size);
      with += gather_rsm<rsm_pattern::radial, rsm_visibility::none>(beside, floor, coarse, settings).x;
      without += gather_rsm<rsm_pattern::radial, rsm_visibility::none>(beside, floor, settings).x;
      if (i % 16 == 0) exact += 16.0 * brute_force(floor, beside);
    }
    CAPTURE(x);
    CAPTURE(with / exact);
    CAPTURE(without / exact);
    CHECK(std::fabs(with / exact - 1.0) < 0.05);
    CHECK(std::fabs(with / exact - 1.0) < 0.25 * std::fabs(without / exact - 1.0));
    // Interleaved over 3 x 3 pixels, the same receivers on pixels that cycle through the nine
    // lattices: the blocks beyond the reach still add up to the whole, within the same 5 %.
    rsm_gather_settings<double> interleaved = settings;
    interleaved.coverage_interleave = 3;
    double with_lattices = 0.0;
    for (unsigned i = 0; i < 64; ++i) {
      const gather_receiver<double> beside =
          receiver_at({x, 0.4, 0.03 * i - 1.0}, glm::uvec2(i, 3 + i / 3), glm::normalize(glm::dvec3(-1.0, -0.3, 0.0)));
      with_lattices += gather_rsm<rsm_pattern::radial, rsm_visibility::none>(beside, floor, coarse, interleaved).x;
    }
    CAPTURE(with_lattices / exact);
    CHECK(std::fabs(with_lattices / exact - 1.0) < 0.05);
  }
  const gather_receiver<double> inside = receiver_at({2.4, 0.4, 0.0}, glm::uvec2(5, 3), glm::normalize(glm::dvec3(-1.0, -0.3, 0.0)));
  CHECK(gather_rsm<rsm_pattern::radial, rsm_visibility::alg6>(inside, floor, coarse, settings) ==
        gather_rsm<rsm_pattern::radial, rsm_visibility::alg6>(inside, floor, settings));
}

namespace {

// A spot light at the eye-space origin looking down -z (tan of its half field of view `t`) into
// the corner of a floor (z = -2, facing the light) and a wall (x = 1, facing -x): every texel's
// pixel light where its centre ray first meets them, flux 1. No surface hides another from a
// receiver on the wall: exact visibility keeps everything.
struct corner_rsm {
  int size = 256;
  double t = std::tan(80.0 * 3.14159265358979323846 / 180.0);
  glm::dvec3 ray(glm::dvec2 texel) const { return {(texel.x / size * 2.0 - 1.0) * t, (texel.y / size * 2.0 - 1.0) * t, -1.0}; }
  rsm_texel<double> operator()(glm::ivec2 texel) const {
    const glm::dvec3 r = ray(glm::dvec2(texel) + 0.5);
    const double to_floor = 2.0, to_wall = r.x > 0.0 ? 1.0 / r.x : 1e30;
    if (to_wall < to_floor) return {r * to_wall, glm::dvec3(-1, 0, 0), glm::dvec3(1.0)};
    return {r * to_floor, glm::dvec3(0, 0, 1), glm::dvec3(1.0)};
  }
  gather_receiver<double> receiver(const glm::dvec3& position, glm::uvec2 pixel) const {
    const glm::dvec2 ndc = glm::dvec2(position.x, position.y) / -position.z / t;
    return {position, glm::dvec3(-1, 0, 0), (ndc * 0.5 + 0.5) * double(size), pixel};
  }
};

}  // namespace

TEST_CASE("near a spot light, on a wall that sees the RSM at grazing angles, Alg. 6 removes light nothing hides; alg6_ray keeps it") {
  // Receivers on the wall 0.2 to 0.6 below the light, where its elevation in the light's eye
  // space is far from the elevation within the paths' planes (docs/errata.md RSMV-12): the mean
  // over 64 receivers' patterns of each visibility against no visibility (which here is exact).
  const corner_rsm corner;
  rsm_gather_settings<double> settings = default_rsm_gather_settings<double>(glm::ivec2(corner.size));
  settings.perspective = 1;
  for (const double depth : {-0.2, -0.4, -0.6}) {
    double none = 0.0, alg6 = 0.0, ray = 0.0;
    for (unsigned i = 0; i < 64; ++i) {
      const gather_receiver<double> receiver = corner.receiver({1.0, 0.02 * i - 0.6, depth}, glm::uvec2(i, 11));
      REQUIRE(receiver.rsm_coordinate.x < corner.size);
      none += gather_rsm<rsm_pattern::radial, rsm_visibility::none>(receiver, corner, settings).x;
      alg6 += gather_rsm<rsm_pattern::radial, rsm_visibility::alg6>(receiver, corner, settings).x;
      ray += gather_rsm<rsm_pattern::radial, rsm_visibility::alg6_ray>(receiver, corner, settings).x;
    }
    CAPTURE(depth);
    CAPTURE(alg6 / none);
    CAPTURE(ray / none);
    CHECK(alg6 / none < 0.9);
    CHECK(ray / none > 0.99);
  }
}

TEST_CASE("alg6_ray: with an orthographic light and no sample in the receiver's tangent plane it is Alg. 6; it never adds light") {
  // Orthographic: `up` is +z, elevation_bucket_about is elevation_bucket; receivers facing the floor
  // from above see every sample in front of their tangent plane.
  const synthetic_rsm floor;
  rsm_gather_settings<double> settings = gather_settings();
  settings.perspective = 0;
  for (unsigned i = 0; i < 16; ++i) {
    const gather_receiver<double> receiver = receiver_at({0.1 * i - 0.8, 0.3, 0.05 * i}, glm::uvec2(i, 5));
    REQUIRE(gather_rsm<rsm_pattern::radial, rsm_visibility::alg6_ray>(receiver, floor, settings) ==
            gather_rsm<rsm_pattern::radial, rsm_visibility::alg6>(receiver, floor, settings));
  }
  synthetic_rsm scene;
  scene.block_x0 = 0.2;
  scene.block_x1 = 0.6;
  scene.block_height = 0.8;
  for (unsigned i = 0; i < 64; ++i) {
    const gather_receiver<double> receiver = receiver_at({0.03 * i - 1.0, 0.1 + 0.01 * i, 0.02 * i - 0.5}, glm::uvec2(i, 2), glm::dvec3(0.6, 0.8, 0.0));
    REQUIRE(gather_rsm<rsm_pattern::radial, rsm_visibility::alg6_ray>(receiver, scene, settings).x <=
            gather_rsm<rsm_pattern::radial, rsm_visibility::none>(receiver, scene, settings).x);
  }
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
    const gather_receiver<double> receiver =
        receiver_at({0.0, 0.05, 0.01 * i - 0.16}, glm::uvec2(static_cast<unsigned>(i), 3u), glm::dvec3(1, 0, 0));
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

namespace {

// A flat floor lit uniformly, seen by an orthographic light from straight above, covering
// [-1, 1]^2 with `size`^2 texels of flux `flux_per_texel` each.
struct flat_rsm {
  int size;
  double flux_per_texel;
  double texel() const { return 2.0 / size; }
  glm::dvec3 world_of(glm::ivec2 t) const { return {(t.x + 0.5) * texel() - 1.0, 0.0, 1.0 - (t.y + 0.5) * texel()}; }
  rsm_texel<double> operator()(glm::ivec2 t) const { return light_space_texel(world_of(t), glm::dvec3(0, 1, 0), glm::dvec3(flux_per_texel)); }
  glm::dmat4 view_projection() const { return glm::ortho(-1.0, 1.0, -1.0, 1.0, 0.1, 20.0) * light_view(); }
  gather_receiver<double> receiver(const glm::dvec3& position, const glm::dvec3& normal, glm::uvec2 pixel) const {
    return make_gather_receiver(position, normal, light_view(), view_projection(), glm::ivec2(size), pixel);
  }
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
    for (double height : {0.1, 0.5})
      for (glm::dvec2 where : {glm::dvec2(0.05, -0.1), glm::dvec2(-0.7, 0.65)}) {
        const glm::dvec3 position(where.x, height, where.y), normal(0, -1, 0);
        const gather_receiver<double> at = floor.receiver(position, normal, glm::uvec2(0u));
        double brute_force = 0.0;
        for (int y = 0; y < size; ++y)
          for (int x = 0; x < size; ++x) {
            const rsm_texel<double> light = floor(glm::ivec2(x, y));
            brute_force += pixel_light_irradiance(at.position, at.normal, light.position, light.normal, light.flux, settings.irradiance).x;
          }
        brute_force /= 3.14159265358979323846;
        double mean = 0.0;
        const int receivers = 256;
        for (int i = 0; i < receivers; ++i) {
          mean += gather_rsm<rsm_pattern::radial, rsm_visibility::none>(floor.receiver(position, normal, glm::uvec2(static_cast<unsigned>(i), 7u)),
                                                                        floor, settings).x / receivers;
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
    double mean = 0.0;
    for (unsigned i = 0; i < 128; ++i)
      mean += gather_rsm<rsm_pattern::radial, rsm_visibility::none>(floor.receiver(position, normal, glm::uvec2(i, 9u)), floor, settings).x / 128.0;
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
  rsm_gather_settings<double> ortho = settings;  // the synthetic light is orthographic
  ortho.perspective = 0;
  double hidden = 0.0, hidden_kept = 0.0, seen = 0.0, seen_kept = 0.0, ray_hidden_kept = 0.0, ray_seen_kept = 0.0;
  for (int i = 0; i < 32; ++i) {
    const gather_receiver<double> receiver =
        receiver_at({0.0, 0.05, 0.01 * i - 0.16}, glm::uvec2(static_cast<unsigned>(i), 4u), glm::dvec3(1, 0, 0));
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
    ray_hidden_kept += gather_rsm<rsm_pattern::radial, rsm_visibility::alg6_ray>(receiver, only(true), ortho).x;
    seen += gather_rsm<rsm_pattern::radial, rsm_visibility::none>(receiver, only(false), settings).x;
    seen_kept += gather_rsm<rsm_pattern::radial, rsm_visibility::alg6>(receiver, only(false), settings).x;
    ray_seen_kept += gather_rsm<rsm_pattern::radial, rsm_visibility::alg6_ray>(receiver, only(false), ortho).x;
  }
  MESSAGE("defaults: Alg. 6 keeps " << hidden_kept / hidden << " of the hidden light and " << seen_kept / seen << " of the seen light; alg6_ray "
                                    << ray_hidden_kept / hidden << " and " << ray_seen_kept / seen);
  REQUIRE(hidden > 0.0);
  REQUIRE(seen > 0.0);
  CHECK(hidden_kept / hidden < 0.2);
  CHECK(seen_kept / seen > 0.9);
  CHECK(ray_hidden_kept / hidden < 0.2);
  CHECK(ray_seen_kept / seen > 0.9);
}
