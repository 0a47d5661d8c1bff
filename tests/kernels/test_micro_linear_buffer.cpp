// Properties of the micro linear buffer (include/vplkit/micro_linear_buffer.hpp): the elevation
// bucket, Alg. 2, Alg. 3 and Alg. 6 of [RSMV], and the situations of Figures 3.3 and 3.4.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include <glm/glm.hpp>

#include <vplkit/micro_linear_buffer.hpp>

#include "tests/closed_forms.hpp"

using namespace vplkit;

namespace {

using closed_forms::pi;

// The definition of section 3.3, with atan: slot = floor((phi + pi/2) / pi * B).
int bucket_by_angle(const glm::dvec3& x, const glm::dvec3& xp, int slots) {
  const glm::dvec3 d = xp - x;
  const double phi = std::atan2(d.z, std::sqrt(d.x * d.x + d.y * d.y));
  return std::min(slots - 1, static_cast<int>(std::floor((phi + pi / 2) / pi * slots)));
}

// Distance in radians from phi to the nearest slot boundary.
double distance_to_boundary(const glm::dvec3& x, const glm::dvec3& xp, int slots) {
  const glm::dvec3 d = xp - x;
  const double phi = std::atan2(d.z, std::sqrt(d.x * d.x + d.y * d.y));
  const double position = (phi + pi / 2) / pi * slots;
  return std::fabs(position - std::round(position)) * pi / slots;
}

// A point of a path seen from the origin at horizontal distance `distance`, elevation `degrees`.
glm::vec3 at_elevation(float distance, float degrees) {
  return {distance, 0.0f, distance * std::tan(glm::radians(degrees))};
}

}  // namespace

TEST_CASE("elevation_bucket matches the atan definition away from slot boundaries") {
  std::mt19937 random(4);
  std::uniform_real_distribution<double> uniform(-3.0, 3.0);
  for (int slots = 1; slots <= micro_linear_buffer_max_slots; ++slots) {
    const elevation_slots<double> table = make_elevation_slots<double>(slots);
    for (int i = 0; i < 5000; ++i) {
      const glm::dvec3 x(uniform(random), uniform(random), uniform(random));
      const glm::dvec3 xp(uniform(random), uniform(random), uniform(random));
      if (distance_to_boundary(x, xp, slots) < 1e-9) continue;
      const int bucket = elevation_bucket(x, xp, table);
      REQUIRE(bucket >= 0);
      REQUIRE(bucket < slots);
      CAPTURE(slots);
      REQUIRE(bucket == bucket_by_angle(x, xp, slots));
    }
  }
}

TEST_CASE("elevation_bucket: straight up is the top slot, straight down the bottom, level the middle") {
  const glm::vec3 origin(0.0f);
  for (int slots : {1, 2, 5, 8, 16}) {
    CAPTURE(slots);
    CHECK(elevation_bucket(origin, glm::vec3(0, 0, 1), slots) == slots - 1);
    CHECK(elevation_bucket(origin, glm::vec3(0, 0, -1), slots) == 0);
    if (slots % 2 == 1) CHECK(elevation_bucket(origin, glm::vec3(1, 1, 0), slots) == slots / 2);
  }
  CHECK(elevation_bucket(origin, origin, 5) == 4);  // coincident: dz >= 0 = every threshold * 0
}

TEST_CASE("elevation_bucket is invariant under rotation about z, translation and scaling, and mirrors under z -> -z") {
  std::mt19937 random(5);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int i = 0; i < 5000; ++i) {
    const int slots = 1 + i % micro_linear_buffer_max_slots;
    const glm::dvec3 x(uniform(random), uniform(random), uniform(random));
    const glm::dvec3 xp(uniform(random), uniform(random), uniform(random));
    if (distance_to_boundary(x, xp, slots) < 1e-6) continue;
    const int bucket = elevation_bucket(x, xp, slots);
    const double angle = uniform(random) * pi;
    const auto rotate = [&](const glm::dvec3& p) {
      return glm::dvec3(std::cos(angle) * p.x - std::sin(angle) * p.y, std::sin(angle) * p.x + std::cos(angle) * p.y, p.z);
    };
    const glm::dvec3 shift(uniform(random), uniform(random), uniform(random));
    REQUIRE(elevation_bucket(rotate(x) + shift, rotate(xp) + shift, slots) == bucket);
    REQUIRE(elevation_bucket(3.0 * x, 3.0 * xp, slots) == bucket);
    const glm::dvec3 flip(1, 1, -1);
    REQUIRE(elevation_bucket(x * flip, xp * flip, slots) == slots - 1 - bucket);
  }
}

TEST_CASE("elevation_bucket_about: about +z it is elevation_bucket to the bit; about any axis, the elevation above that axis's plane") {
  std::mt19937 random(6);
  std::uniform_real_distribution<float> uniform(-2.0f, 2.0f);
  std::normal_distribution<double> normal;
  for (int i = 0; i < 20000; ++i) {
    const int slots = 1 + i % micro_linear_buffer_max_slots;
    const elevation_slots<float> table = make_elevation_slots<float>(slots);
    const glm::vec3 x(uniform(random), uniform(random), uniform(random)), xp(uniform(random), uniform(random), uniform(random));
    REQUIRE(elevation_bucket_about(x, xp, glm::vec3(0, 0, 1), table) == elevation_bucket(x, xp, table));
  }
  // About a unit axis u: the slot of the angle between d and u's plane, by atan, away from the
  // boundaries; rotating d and u together changes nothing.
  for (int i = 0; i < 5000; ++i) {
    const int slots = 1 + i % micro_linear_buffer_max_slots;
    const elevation_slots<double> table = make_elevation_slots<double>(slots);
    const glm::dvec3 up = glm::normalize(glm::dvec3(normal(random), normal(random), normal(random)));
    const glm::dvec3 d(normal(random), normal(random), normal(random));
    const double phi = std::asin(glm::clamp(glm::dot(d, up) / glm::length(d), -1.0, 1.0));
    const double position = (phi + pi / 2) / pi * slots;
    if (std::fabs(position - std::round(position)) < 1e-6) continue;
    const int expected = std::min(slots - 1, static_cast<int>(std::floor(position)));
    const glm::dvec3 x(normal(random), normal(random), normal(random));
    REQUIRE(elevation_bucket_about(x, x + d, up, table) == expected);
    // The frame that takes `up` to +z takes the bucket to elevation_bucket's.
    const glm::dvec3 a = glm::normalize(glm::cross(up, std::fabs(up.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
    const glm::dvec3 b = glm::cross(up, a);
    REQUIRE(elevation_bucket(glm::dvec3(0.0), glm::dvec3(glm::dot(d, a), glm::dot(d, b), glm::dot(d, up)), table) == expected);
  }
}

TEST_CASE("micro_linear_buffer_alg6_ray: on one surface facing the receiver it is Alg. 6; a predecessor seen from behind, or one the sample lies behind, passes no verdict on") {
  // Samples on the plane z = 0 facing a receiver above it: each predecessor faces the receiver and
  // every sample lies on its surface, so Alg. 3's same-slot rule always holds: Alg. 6's verdicts.
  std::mt19937 random(8);
  std::uniform_real_distribution<float> uniform(-3.0f, 3.0f);
  const glm::vec3 receiver(0.0f, 0.0f, 2.0f), up(0.0f, 0.0f, 1.0f);
  for (int path = 0; path < 20000; ++path) {
    micro_linear_buffer<float> thesis, variant;
    micro_linear_buffer_reset(thesis, 5);
    micro_linear_buffer_reset(variant, 5);
    for (int sample = 0; sample < 10; ++sample) {
      const int index = static_cast<int>(random() % 5u);
      const glm::vec3 position(uniform(random), uniform(random), 0.0f);
      REQUIRE(micro_linear_buffer_alg6_ray(variant, index, receiver, position, up) == micro_linear_buffer_alg6(thesis, index));
    }
  }
  // The far face of a wall (seen from behind) and then the ground beyond it in the same slot:
  // Alg. 6 passes "visible" on, alg6_ray lets the slot decide: occluded.
  {
    micro_linear_buffer<float> thesis, variant;
    micro_linear_buffer_reset(thesis, 8);
    micro_linear_buffer_reset(variant, 8);
    const glm::vec3 wall(3.0f, 0.0f, 1.0f), wall_normal(1.0f, 0.0f, 0.0f), ground(6.0f, 0.0f, -1.0f);
    CHECK(micro_linear_buffer_alg6_ray(variant, 3, receiver, wall, wall_normal) == 1.0f);
    CHECK(micro_linear_buffer_alg6(thesis, 3) == 1.0f);
    CHECK(micro_linear_buffer_alg6_ray(variant, 3, receiver, ground, up) <= 0.0f);
    CHECK(micro_linear_buffer_alg6(thesis, 3) == 1.0f);
  }
  // A panel facing the receiver, then the floor behind it (below the panel's plane), same slot: occluded.
  {
    micro_linear_buffer<float> variant;
    micro_linear_buffer_reset(variant, 8);
    const glm::vec3 panel(1.0f, 0.0f, 1.0f), panel_normal = glm::normalize(glm::vec3(-1.0f, 0.0f, 1.0f)), floor(3.0f, 0.0f, -1.0f);
    CHECK(micro_linear_buffer_alg6_ray(variant, 2, receiver, panel, panel_normal) == 1.0f);
    CHECK(micro_linear_buffer_alg6_ray(variant, 2, receiver, floor, up) <= 0.0f);
  }
  // A concave corner: the floor, then the wall rising from it in front of the floor's plane, same
  // slot: both visible, as in Alg. 3.
  {
    micro_linear_buffer<float> variant;
    micro_linear_buffer_reset(variant, 8);
    const glm::vec3 floor(2.9f, 0.0f, 0.0f), wall(3.0f, 0.0f, 0.2f), wall_normal(-1.0f, 0.0f, 0.0f);
    CHECK(micro_linear_buffer_alg6_ray(variant, 2, receiver, floor, up) == 1.0f);
    CHECK(micro_linear_buffer_alg6_ray(variant, 2, receiver, wall, wall_normal) == 1.0f);
  }
}

TEST_CASE("alg6_ray_in_front: in front of the receiver's tangent plane by more than a degree and the distance clamp") {
  const glm::vec3 x(0.0f), n(0.0f, 0.0f, 1.0f);
  CHECK(alg6_ray_in_front(x, n, glm::vec3(1.0f, 0.0f, 0.5f), 0.01f));
  CHECK_FALSE(alg6_ray_in_front(x, n, glm::vec3(1.0f, 0.0f, 0.0f), 0.01f));     // in the plane
  CHECK_FALSE(alg6_ray_in_front(x, n, glm::vec3(1.0f, 0.0f, 0.015f), 0.01f));   // within a degree of it
  CHECK_FALSE(alg6_ray_in_front(x, n, glm::vec3(1.0f, 0.0f, -0.5f), 0.01f));    // behind
  CHECK_FALSE(alg6_ray_in_front(x, n, glm::vec3(0.001f, 0.0f, 0.005f), 0.01f)); // within the distance clamp
}

TEST_CASE("make_elevation_slots: ascending, antisymmetric tangents; slot count validated") {
  for (int slots = 1; slots <= micro_linear_buffer_max_slots; ++slots) {
    const elevation_slots<float> table = make_elevation_slots<float>(slots);
    CHECK(table.count == slots);
    for (int k = 1; k < slots - 1; ++k) CHECK(table.boundary_tangent[k] > table.boundary_tangent[k - 1]);
    for (int k = 0; k < slots - 1; ++k) CHECK(table.boundary_tangent[k] == -table.boundary_tangent[slots - 2 - k]);
  }
  CHECK(static_cast<bool>(validate_slot_count(0)));
  CHECK(static_cast<bool>(validate_slot_count(17)));
  CHECK_FALSE(static_cast<bool>(validate_slot_count(5)));
}

namespace {

// Depth-first over every slot sequence: Alg. 6 (clamped) and Alg. 3 must agree after each step.
// Sharing prefixes, all 5^0 + ... + 5^10 = 12,207,031 sequences cost one step each.
struct equivalence_walk {
  int slots = 0;
  int max_length = 0;
  long sequences = 0;
  long disagreements = 0;
  std::vector<int> first_disagreement;
  std::vector<int> path;

  void visit(const micro_linear_buffer<float>& alg3, const micro_linear_buffer<float>& alg6, int depth) {
    ++sequences;
    if (depth == max_length) return;
    for (int index = 0; index < slots; ++index) {
      micro_linear_buffer<float> next3 = alg3, next6 = alg6;
      const float verdict3 = micro_linear_buffer_alg3(next3, index);
      const float verdict6 = glm::clamp(micro_linear_buffer_alg6(next6, index), 0.0f, 1.0f);
      path.push_back(index);
      if (verdict3 != verdict6) {
        if (disagreements++ == 0) first_disagreement = path;
      } else {
        visit(next3, next6, depth + 1);
      }
      path.pop_back();
    }
  }
};

}  // namespace

TEST_CASE("Alg. 6 gives the same verdicts as Alg. 3 on every sequence of up to 10 samples over 5 slots") {
  equivalence_walk walk;
  walk.slots = 5;
  walk.max_length = 10;
  micro_linear_buffer<float> alg3, alg6;
  micro_linear_buffer_reset(alg3, 5);
  micro_linear_buffer_reset(alg6, 5);
  walk.visit(alg3, alg6, 0);
  CAPTURE(walk.first_disagreement.size());
  CHECK(walk.sequences == 12207031);
  CHECK(walk.disagreements == 0);
}

TEST_CASE("Alg. 6 equals Alg. 3 for every slot count on 10^5 random paths of 10 samples") {
  std::mt19937 random(6);
  for (int slots = 1; slots <= micro_linear_buffer_max_slots; ++slots) {
    std::uniform_int_distribution<int> pick(0, slots - 1);
    for (int path = 0; path < 100000 / micro_linear_buffer_max_slots; ++path) {
      micro_linear_buffer<float> alg3, alg6;
      micro_linear_buffer_reset(alg3, slots);
      micro_linear_buffer_reset(alg6, slots);
      for (int sample = 0; sample < 10; ++sample) {
        const int index = pick(random);
        REQUIRE(micro_linear_buffer_alg3(alg3, index) == glm::clamp(micro_linear_buffer_alg6(alg6, index), 0.0f, 1.0f));
      }
    }
  }
}

TEST_CASE("Alg. 6 slot values are 1 - the number of claims, decremented once per run, saturating at -254") {
  micro_linear_buffer<float> buffer;
  micro_linear_buffer_reset(buffer, 16);
  // Alternating slots 15 and 3: every sample starts a new run, so each claims its slot.
  for (int claim = 0; claim < 5; ++claim) {
    CHECK(micro_linear_buffer_alg6(buffer, 15) == 1.0f - static_cast<float>(claim));
    CHECK(micro_linear_buffer_alg6(buffer, 3) == 1.0f - static_cast<float>(claim));
  }
  // A run repeats its predecessor's value and claims nothing more; slot 3 holds 1 - 5 now.
  CHECK(micro_linear_buffer_alg6(buffer, 3) == -3.0f);
  CHECK(micro_linear_buffer_alg6(buffer, 15) == -4.0f);
  // Saturation: after 255 claims the value stays at 1 - 255; the clamped verdict is 0 throughout.
  for (int claim = 0; claim < 600; ++claim) {
    REQUIRE(glm::clamp(micro_linear_buffer_alg6(buffer, claim % 2 == 0 ? 7 : 8), 0.0f, 1.0f) == (claim < 2 ? 1.0f : 0.0f));
  }
  CHECK(micro_linear_buffer_alg6(buffer, 7) == -254.0f);
  CHECK(micro_linear_buffer_alg6(buffer, 3) == -4.0f);  // other slots untouched
}

TEST_CASE("Alg. 2 and Alg. 3: the first sample of a slot is visible, a later one in another run is occluded") {
  micro_linear_buffer<double> buffer;
  micro_linear_buffer_reset(buffer, 5);
  CHECK(micro_linear_buffer_alg2(buffer, 1) == 1.0);
  CHECK(micro_linear_buffer_alg2(buffer, 3) == 1.0);
  CHECK(micro_linear_buffer_alg2(buffer, 1) == 0.0);
  micro_linear_buffer_reset(buffer, 5);  // a new path forgets the old one
  CHECK(micro_linear_buffer_alg2(buffer, 1) == 1.0);

  micro_linear_buffer_reset(buffer, 5);
  CHECK(micro_linear_buffer_alg3(buffer, 2) == 1.0);
  CHECK(micro_linear_buffer_alg3(buffer, 4) == 1.0);
  CHECK(micro_linear_buffer_alg3(buffer, 2) == 0.0);  // slot 2 was claimed, not by its predecessor
}

TEST_CASE("Figure 3.3: along one path, a nearer sample hides a farther one in the same elevation range") {
  // Eight slots of 22.5 degrees. The path climbs a terrain: samples at increasing distance and
  // elevations 10, 30, 50 (visible: each opens a new range), then a far point in a valley at
  // 12 degrees, which lies behind the first sample's range (slot 4, like the 10-degree sample),
  // and a far peak at 60 degrees, in the range of the 50-degree sample (slot 6).
  const int slots = 8;
  const elevation_slots<float> table = make_elevation_slots<float>(slots);
  const glm::vec3 shading_point(0.0f);
  const std::vector<std::pair<glm::vec3, float>> samples = {
      {at_elevation(0.5f, 10.0f), 1.0f}, {at_elevation(1.0f, 30.0f), 1.0f}, {at_elevation(1.5f, 50.0f), 1.0f},
      {at_elevation(3.0f, 12.0f), 0.0f}, {at_elevation(4.0f, 60.0f), 0.0f}};
  micro_linear_buffer<float> alg2, alg3, alg6;
  micro_linear_buffer_reset(alg2, slots);
  micro_linear_buffer_reset(alg3, slots);
  micro_linear_buffer_reset(alg6, slots);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    CAPTURE(i);
    const int index = elevation_bucket(shading_point, samples[i].first, table);
    CHECK(micro_linear_buffer_alg2(alg2, index) == samples[i].second);
    CHECK(micro_linear_buffer_alg3(alg3, index) == samples[i].second);
    CHECK(glm::clamp(micro_linear_buffer_alg6(alg6, index), 0.0f, 1.0f) == samples[i].second);
  }
}

TEST_CASE("Figure 3.4: neighbours on one smooth surface share a slot; Alg. 2 occludes them, Alg. 3 and 6 do not") {
  // A flat, slightly rising ground seen from a point on it: every sample falls into the same
  // range of elevation (Fig. 3.4a). Alg. 2 keeps only the first; Alg. 3 propagates the
  // predecessor's verdict (Fig. 3.4b), so the whole lit surface stays visible.
  const int slots = 5;
  const elevation_slots<float> table = make_elevation_slots<float>(slots);
  const glm::vec3 shading_point(0.0f);
  micro_linear_buffer<float> alg2, alg3, alg6;
  micro_linear_buffer_reset(alg2, slots);
  micro_linear_buffer_reset(alg3, slots);
  micro_linear_buffer_reset(alg6, slots);
  float visible2 = 0.0f, visible3 = 0.0f, visible6 = 0.0f;
  for (int i = 1; i <= 10; ++i) {
    const glm::vec3 sample = at_elevation(0.2f * static_cast<float>(i), 5.0f + 0.5f * static_cast<float>(i));
    const int index = elevation_bucket(shading_point, sample, table);
    REQUIRE(index == 2);
    visible2 += micro_linear_buffer_alg2(alg2, index);
    visible3 += micro_linear_buffer_alg3(alg3, index);
    visible6 += glm::clamp(micro_linear_buffer_alg6(alg6, index), 0.0f, 1.0f);
  }
  CHECK(visible2 == 1.0f);
  CHECK(visible3 == 10.0f);
  CHECK(visible6 == 10.0f);

  // ... but a run that leaves the slot and comes back is occluded in Alg. 3 as well: the
  // propagation covers neighbours only.
  micro_linear_buffer_reset(alg3, slots);
  CHECK(micro_linear_buffer_alg3(alg3, elevation_bucket(shading_point, at_elevation(0.5f, 5.0f), table)) == 1.0f);
  CHECK(micro_linear_buffer_alg3(alg3, elevation_bucket(shading_point, at_elevation(1.0f, 45.0f), table)) == 1.0f);
  CHECK(micro_linear_buffer_alg3(alg3, elevation_bucket(shading_point, at_elevation(2.0f, 6.0f), table)) == 0.0f);
}
