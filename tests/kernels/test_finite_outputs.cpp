// Every kernel returns finite numbers (and in-range indices) for any finite input within the
// scene's range: 10^6 random inputs per kernel (the slow tier; the fast tier sets
// VPLKIT_PROPERTY_INPUTS to run the first 10^4 of the same sequence) in float and in double, drawn with log-uniform
// magnitudes from 1e-6 to 1e6 (huge and tiny distances), plus the degenerate inputs a renderer
// meets: zero vectors, coincident points, grazing angles. A NaN here would be a black or white
// pixel, or a poisoned sum, in an image.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <vplkit/vplkit.hpp>

using namespace vplkit;

namespace {

// 10^6, or $VPLKIT_PROPERTY_INPUTS (1 to 10^6) where it is set.
const int property_input_count = [] {
  const char* from_environment = std::getenv("VPLKIT_PROPERTY_INPUTS");
  const int count = from_environment ? std::atoi(from_environment) : 1000000;
  if (count < 1 || count > 1000000) throw std::runtime_error("VPLKIT_PROPERTY_INPUTS must be in [1, 1000000]");
  return count;
}();

template <typename T>
struct input_source {
  std::mt19937_64 engine{20261123};
  std::vector<glm::vec<3, T>> degenerate_vectors{glm::vec<3, T>(0), glm::vec<3, T>(1, 0, 0), glm::vec<3, T>(0, 0, -1),
                                                 glm::vec<3, T>(T(1e-6)), glm::vec<3, T>(T(-1e6), T(1e6), T(1e6))};
  int draw = 0;

  T uniform(T low, T high) { return std::uniform_real_distribution<T>(low, high)(engine); }
  // A magnitude from 1e-6 to 1e6, log-uniform, with a random sign.
  T magnitude() { return (uniform(0, 1) < T(0.5) ? T(-1) : T(1)) * std::pow(T(10), uniform(-6, 6)); }
  glm::vec<3, T> unit() {
    const T z = uniform(-1, 1), phi = uniform(0, T(6.283185307179586));
    const T r = std::sqrt(glm::max(T(0), T(1) - z * z));
    return glm::vec<3, T>(r * std::cos(phi), r * std::sin(phi), z);
  }
  // A point: mostly random, every 8th a degenerate one.
  glm::vec<3, T> point() {
    if (++draw % 8 == 0) return degenerate_vectors[static_cast<std::size_t>(draw / 8) % degenerate_vectors.size()];
    return glm::vec<3, T>(magnitude(), magnitude(), magnitude());
  }
  // A normal: unit, every 16th the zero vector (a degenerate mesh's).
  glm::vec<3, T> normal() { return ++draw % 16 == 0 ? glm::vec<3, T>(0) : unit(); }
  // Grazing: a unit vector perpendicular to `n` (when n is not zero).
  glm::vec<3, T> grazing(const glm::vec<3, T>& n) {
    const glm::vec<3, T> t = glm::cross(n, unit());
    const T length = glm::length(t);
    return length > T(0) ? t / length : unit();
  }
};

template <typename T, int L>
bool finite(const glm::vec<L, T>& v) {
  for (int i = 0; i < L; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}
template <typename T>
bool finite(T value) {
  return std::isfinite(value);
}

template <typename T, int L>
std::string text(const glm::vec<L, T>& v) {
  std::ostringstream out;
  out.precision(9);
  out << "(";
  for (int i = 0; i < L; ++i) out << (i ? ", " : "") << v[i];
  return out.str() + ")";
}

// Counts the failures and names the first, with its inputs.
struct failures {
  int count = 0;
  std::string first;
  void add(const std::string& what) {
    if (count++ == 0) first = what;
  }
};

#define VPLKIT_EXPECT_FINITE(kernel, value, inputs)                                            \
  do {                                                                                         \
    if (!finite(value)) found.add(std::string(kernel) + " is not finite for " + (inputs));      \
  } while (0)

}  // namespace

TEST_CASE_TEMPLATE("the light kernels (Eq. 3.2, the spot and directional lights) are finite", T, float, double) {
  input_source<T> in;
  failures found;
  const irradiance_settings<T> settings{T(0.1)};
  spot_light<T> spot;
  directional_light<T> sun;
  for (int i = 0; i < property_input_count; ++i) {
    const glm::vec<3, T> x = in.point(), n = in.normal();
    const glm::vec<3, T> xp = i % 5 == 0 ? x : in.point();  // coincident points
    const glm::vec<3, T> np = i % 7 == 0 ? in.grazing(n) : in.normal();
    const glm::vec<3, T> flux(in.uniform(0, 10));
    VPLKIT_EXPECT_FINITE("pixel_light_irradiance", pixel_light_irradiance(x, n, xp, np, flux, settings), text(x) + " " + text(n) + " " + text(xp) + " " + text(np));
    spot.position = xp;
    spot.direction = in.unit();
    VPLKIT_EXPECT_FINITE("spot_light_irradiance", spot_light_irradiance(x, n, spot, settings), text(x) + " " + text(n) + " " + text(xp));
    sun.direction = in.unit();
    VPLKIT_EXPECT_FINITE("directional_light_irradiance", directional_light_irradiance(n, sun), text(n));
  }
  CHECK_MESSAGE(found.count == 0, found.count, " failures, the first: ", found.first);
}

TEST_CASE_TEMPLATE("the form factors (point-to-point and polygon-to-point) are finite", T, float, double) {
  input_source<T> in;
  failures found;
  for (int i = 0; i < property_input_count; ++i) {
    const glm::vec<3, T> x = in.point(), n = in.normal();
    const glm::vec<3, T> y = i % 5 == 0 ? x : in.point(), ny = i % 7 == 0 ? in.grazing(n) : in.normal();
    VPLKIT_EXPECT_FINITE("point_form_factor", point_form_factor(x, n, y, ny), text(x) + " " + text(n) + " " + text(y) + " " + text(ny));
    // A quad around y, small or large; every 3rd has a corner at x, every 4th is collapsed to a point.
    const T size = std::fabs(in.magnitude());
    const glm::vec<3, T> u = in.grazing(ny) * size, v = glm::cross(ny, u);
    glm::vec<3, T> c0 = y - u - v, c1 = y + u - v, c2 = y + u + v, c3 = y - u + v;
    if (i % 3 == 0) c0 = x;
    if (i % 4 == 0) c0 = c1 = c2 = c3 = y;
    // The inputs' text only for a failure: formatting them for every input was most of the test's time.
    const auto quad = [&] { return text(x) + " " + text(n) + " " + text(c0) + " " + text(c1) + " " + text(c2) + " " + text(c3); };
    VPLKIT_EXPECT_FINITE("polygon_form_factor", polygon_form_factor(x, n, c0, c1, c2, c3), quad());
    VPLKIT_EXPECT_FINITE("polygon_form_factor_unclipped", polygon_form_factor_unclipped(x, n, c0, c1, c2, c3), quad());
  }
  CHECK_MESSAGE(found.count == 0, found.count, " failures, the first: ", found.first);
}

TEST_CASE_TEMPLATE("the Light Wave kernels (Eq. 4.5, the lobe, the faked shadows) are finite", T, float, double) {
  input_source<T> in;
  failures found;
  const lightwave_shading_settings<T> shading;
  for (int i = 0; i < property_input_count; ++i) {
    const glm::vec<3, T> x = in.point(), n = in.normal(), eye = i % 9 == 0 ? x : in.point();
    lightwave_vpl<T> vpl{i % 5 == 0 ? x : in.point(), i % 7 == 0 ? in.grazing(n) : in.unit(), in.uniform(0, 1)};
    const auto inputs = [&] { return text(x) + " " + text(n) + " eye " + text(eye) + " vpl " + text(vpl.position) + " " + text(vpl.normal); };
    VPLKIT_EXPECT_FINITE("lightwave_vpl_contribution", lightwave_vpl_contribution(x, n, glm::vec<3, T>(T(0.5)), eye, vpl, shading), inputs());
    VPLKIT_EXPECT_FINITE("lightwave_vpl_weight", lightwave_vpl_weight(x, n, vpl), inputs());
    VPLKIT_EXPECT_FINITE("lightwave_lobe", lightwave_lobe(in.uniform(-1, 1)), inputs());
    VPLKIT_EXPECT_FINITE("lightwave_faked_indirect", lightwave_faked_indirect(glm::vec<3, T>(std::fabs(in.magnitude())), in.uniform(0, 1), in.uniform(T(0.5), 4)),
                         inputs());
  }
  CHECK_MESSAGE(found.count == 0, found.count, " failures, the first: ", found.first);
}

TEST_CASE_TEMPLATE("the visibility kernels (elevation slots, Alg. 4, the bilateral weights) stay in range", T, float, double) {
  input_source<T> in;
  failures found;
  const elevation_slots<T> slots = make_elevation_slots<T>(8);
  const bilateral_settings<T> bilateral;
  const shadow_density_settings<T> shadow;
  const glm::ivec2 rsm_size(64, 64);
  for (int i = 0; i < property_input_count; ++i) {
    const glm::vec<3, T> x = in.point(), xp = i % 5 == 0 ? x : in.point();
    const int slot = elevation_bucket(x, xp, slots);
    if (slot < 0 || slot >= slots.count) found.add("elevation_bucket " + std::to_string(slot) + " for " + text(x) + " " + text(xp));
    const T centre_depth = i % 11 == 0 ? T(0) : in.magnitude(), tap_depth = i % 13 == 0 ? centre_depth : in.magnitude();
    const glm::vec<2, T> offset(in.uniform(-8, 8), in.uniform(-8, 8));
    const T weight = bilateral_weight(offset, centre_depth, tap_depth, in.normal(), in.normal(), bilateral);
    if (!(weight >= T(0) && weight <= T(1)))
      found.add("bilateral_weight " + std::to_string(weight) + " for depths " + std::to_string(centre_depth) + ", " + std::to_string(tap_depth));
    if (i % 16 == 0) {  // Alg. 4 reads kernel_size^2 texels
      const glm::vec<2, T> coordinate(in.uniform(-10, 74), in.uniform(-10, 74));
      const T depth = in.magnitude();
      const T density = shadow_density(coordinate, depth, glm::vec<2, T>(in.magnitude(), in.magnitude()),
                                       [&](const glm::ivec2&) { return in.magnitude(); }, rsm_size, shadow);
      if (!(density >= T(0) && density <= T(1))) found.add("shadow_density " + std::to_string(density));
    }
  }
  CHECK_MESSAGE(found.count == 0, found.count, " failures, the first: ", found.first);
}

TEST_CASE_TEMPLATE("the sampling kernels (radial and disk patterns, cube-map directions) are finite and in range", T, float, double) {
  input_source<T> in;
  failures found;
  const radial_pattern_constants<T> radial = make_radial_pattern_constants(radial_pattern_settings<T>{});
  disk_pattern_settings<T> disk;
  for (int i = 0; i < property_input_count; ++i) {
    const glm::uvec2 pixel(static_cast<unsigned>(in.engine()), static_cast<unsigned>(in.engine()));
    const pattern_sample<T> sample = radial_pattern_sample(i % 20, (i / 20) % 15, pixel, radial);
    if (!finite(sample.offset) || !finite(sample.weight) || !(sample.weight >= T(0))) found.add("radial_pattern_sample at pixel " + text(glm::vec<2, T>(pixel)));
    const pattern_sample<T> from_disk = rsm_disk_sample(i % 400, rsm_disk_pixel_shift(pixel, disk), disk);
    if (!finite(from_disk.offset) || !finite(from_disk.weight) || !(from_disk.weight >= T(0)) ||
        !(glm::length(from_disk.offset) <= disk.max_radius * T(1.0001)))
      found.add("rsm_disk_sample " + std::to_string(i % 400) + " at pixel " + text(glm::vec<2, T>(pixel)));
    VPLKIT_EXPECT_FINITE("direction_from_turns", direction_from_turns(in.magnitude()), "");
    const glm::vec<3, T> direction = i % 17 == 0 ? glm::vec<3, T>(0) : in.point();
    const glm::ivec3 texel = cube_texel_of(direction, 4);
    if (texel.x < 0 || texel.x > 5 || texel.y < 0 || texel.y > 3 || texel.z < 0 || texel.z > 3)
      found.add("cube_texel_of " + text(direction) + " gave face " + std::to_string(texel.x) + " texel " + std::to_string(texel.y) + ", " +
                std::to_string(texel.z));
  }
  CHECK_MESSAGE(found.count == 0, found.count, " failures, the first: ", found.first);
}

TEST_CASE_TEMPLATE("the gathers (RSM with Alg. 6, final gathering) are finite over hostile RSMs and cube maps", T, float, double) {
  // Fewer receivers: each gather reads hundreds of texels (2000 x 300 = 6 x 10^5 samples at 10^6
  // inputs; 200 receivers in the fast tier's 10^4).
  input_source<T> in;
  failures found;
  const glm::ivec2 rsm_size(64, 64);
  rsm_gather_settings<T> settings = default_rsm_gather_settings<T>(rsm_size);
  const auto fetch = [&](const glm::ivec2&) {
    rsm_texel<T> texel;
    texel.position = in.point();
    texel.position.z = -std::fabs(in.magnitude());
    texel.normal = in.normal();
    texel.flux = glm::vec<3, T>(std::fabs(in.magnitude()));
    return texel;
  };
  const auto cube_fetch = [&](int, int, int) { return glm::vec<4, T>(in.uniform(0, 10), in.uniform(0, 10), in.uniform(0, 10), std::fabs(in.magnitude())); };
  const int receivers = std::min(2000, std::max(1, property_input_count / 50));
  for (int i = 0; i < receivers; ++i) {
    gather_receiver<T> receiver{in.point(), in.normal(), glm::vec<2, T>(in.uniform(-4, 68), in.uniform(-4, 68)), glm::uvec2(i, i * 7)};
    receiver.position.z = -std::fabs(receiver.position.z);  // in front of the light
    VPLKIT_EXPECT_FINITE("gather_rsm (radial, Alg. 6)", (gather_rsm<rsm_pattern::radial, rsm_visibility::alg6>(receiver, fetch, settings)),
                         text(receiver.position) + " " + text(receiver.normal));
    const glm::vec<3, T> x = in.point(), n = in.normal(), o = i % 5 == 0 ? x : in.point();
    VPLKIT_EXPECT_FINITE("final_gather_irradiance (polygon)", (final_gather_irradiance<gather_form_factor::polygon>(x, n, o, 4, cube_fetch)),
                         text(x) + " " + text(n) + " " + text(o));
    VPLKIT_EXPECT_FINITE("final_gather_irradiance (point)", (final_gather_irradiance<gather_form_factor::point>(x, n, o, 4, cube_fetch)),
                         text(x) + " " + text(n) + " " + text(o));
  }
  CHECK_MESSAGE(found.count == 0, found.count, " failures, the first: ", found.first);
}
