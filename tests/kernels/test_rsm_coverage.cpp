// Properties of the coverage's coarse lights (include/vplkit/rsm_coverage.hpp): the reduction of a
// block (closed forms of its centroid, normal, flux and extent), the coarse light's irradiance
// against the sum of its texels' Eq. 3.2 far away and against a uniform square's closed form near
// it. The gather's use of them is tested in test_rsm_gather.cpp.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include <vplkit/rsm_coverage.hpp>
#include <vplkit/rsm_gather.hpp>

#include "tests/closed_forms.hpp"

using namespace vplkit;

namespace {

using closed_forms::pi;

// A flat RSM in the light's eye space: texel (x, y) at (x h, y h, depth), facing the light, each
// with the same flux; texels with x >= `empty_from` are empty (eye depth 0).
struct flat_rsm {
  double h = 0.01;
  double depth = -3.0;
  glm::dvec3 flux{0.5, 0.25, 1.0};
  int empty_from = 1 << 30;
  rsm_texel<double> operator()(glm::ivec2 t) const {
    if (t.x >= empty_from) return {glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0)};
    return {glm::dvec3((t.x + 0.5) * h, (t.y + 0.5) * h, depth), glm::dvec3(0, 0, 1), flux};
  }
};

}  // namespace

TEST_CASE("reduce_rsm_block of a flat uniform block: its centroid, the plane's normal, the summed flux, a grid's mean squared radius") {
  const flat_rsm rsm;
  const glm::ivec2 size(64, 48);
  const int blocks = 8;  // blocks of 8 x 6 texels
  const glm::ivec2 side = coverage_block_side(size, blocks);
  REQUIRE(side == glm::ivec2(8, 6));
  for (const glm::ivec2 block : {glm::ivec2(0, 0), glm::ivec2(3, 5), glm::ivec2(7, 7)}) {
    const coarse_light<double> light = reduce_rsm_block<double>(block, blocks, size, rsm);
    const glm::dvec2 centre = (glm::dvec2(block * side) + 0.5 * glm::dvec2(side)) * rsm.h;
    CHECK(light.position.x == doctest::Approx(centre.x).epsilon(1e-12));
    CHECK(light.position.y == doctest::Approx(centre.y).epsilon(1e-12));
    CHECK(light.position.z == doctest::Approx(rsm.depth).epsilon(1e-12));
    CHECK(light.normal.z == doctest::Approx(1.0).epsilon(1e-12));
    CHECK(light.flux.y == doctest::Approx(48 * rsm.flux.y).epsilon(1e-12));
    // An n-point grid of spacing h has variance h^2 (n^2 - 1) / 12 per axis.
    const double extent = rsm.h * rsm.h * ((8.0 * 8.0 - 1.0) + (6.0 * 6.0 - 1.0)) / 12.0;
    CHECK(light.extent == doctest::Approx(extent).epsilon(1e-6));
  }
}

TEST_CASE("reduce_rsm_block weighs by flux, leaves the mean normal unnormalised and skips empty texels") {
  // Two lit texels of a block: one with flux 3 facing +z, one with flux 1 facing +x; the rest empty.
  const auto two = [](glm::ivec2 t) -> rsm_texel<double> {
    if (t == glm::ivec2(0, 0)) return {glm::dvec3(0.0, 0.0, -2.0), glm::dvec3(0, 0, 1), glm::dvec3(1.0)};
    if (t == glm::ivec2(3, 1)) return {glm::dvec3(1.0, 0.0, -2.0), glm::dvec3(1, 0, 0), glm::dvec3(1.0 / 3.0)};
    return {glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0)};
  };
  const coarse_light<double> light = reduce_rsm_block<double>(glm::ivec2(0), 1, glm::ivec2(4, 4), two);
  CHECK(light.position.x == doctest::Approx(0.25));
  CHECK(light.position.z == doctest::Approx(-2.0));
  CHECK(light.normal.x == doctest::Approx(0.25));
  CHECK(light.normal.z == doctest::Approx(0.75));
  CHECK(glm::length(light.normal) < 1.0);
  CHECK(light.flux.x == doctest::Approx(4.0 / 3.0));
  CHECK(light.extent == doctest::Approx(0.75 * 0.25 * 0.25 + 0.25 * 0.75 * 0.75));  // weighted variance of x
  // A block without light is all zeros, and lights nothing.
  flat_rsm dark;
  dark.empty_from = 0;
  const coarse_light<double> none = reduce_rsm_block<double>(glm::ivec2(1, 1), 4, glm::ivec2(16), dark);
  CHECK(none.flux == glm::dvec3(0.0));
  CHECK(none.extent == 0.0);
  CHECK(coarse_light_irradiance(glm::dvec3(0.0, 0.0, 1.0), glm::dvec3(0, 0, -1), none) == glm::dvec3(0.0));
}

TEST_CASE("a coarse light of one texel is Eq. 3.2; far from its block it is the sum of its texels' Eq. 3.2") {
  const flat_rsm rsm;
  const irradiance_settings<double> settings;
  const glm::dvec3 x(0.3, -0.2, 1.0), n = glm::normalize(glm::dvec3(0.1, 0.2, -1.0));
  const coarse_light<double> one = reduce_rsm_block<double>(glm::ivec2(5, 7), 64, glm::ivec2(64), rsm);
  const rsm_texel<double> texel = rsm(glm::ivec2(5, 7));
  CHECK(one.extent == doctest::Approx(0.0).epsilon(1e-12));
  const glm::dvec3 single = pixel_light_irradiance(x, n, texel.position, texel.normal, texel.flux, settings);
  CHECK(coarse_light_irradiance(x, n, one, settings).z == doctest::Approx(single.z).epsilon(1e-9));
  // A 16 x 16 block 0.16 across, seen from 4 units: within 0.1 %.
  for (const glm::dvec3 far : {glm::dvec3(0.1, 0.1, 1.0), glm::dvec3(2.0, -1.0, 0.5), glm::dvec3(-1.5, 0.5, 0.2)}) {
    const glm::dvec3 normal = glm::normalize(glm::dvec3(0.05, 0.0, 0.0) - far);
    const coarse_light<double> block = reduce_rsm_block<double>(glm::ivec2(0), 4, glm::ivec2(64), rsm);
    double sum = 0.0;
    for (int y = 0; y < 16; ++y)
      for (int t = 0; t < 16; ++t) {
        const rsm_texel<double> p = rsm(glm::ivec2(t, y));
        sum += pixel_light_irradiance(far, normal, p.position, p.normal, p.flux, settings).x;
      }
    CAPTURE(far.x);
    CHECK(coarse_light_irradiance(far, normal, block, settings).x == doctest::Approx(sum).epsilon(1e-3));
  }
}

TEST_CASE("near its block a coarse light is a uniform square's, bounded, not a point's") {
  // A receiver at height z above the centre of a uniform Lambertian square of side s and flux F
  // gets the square's exitance F / s^2 times its form factor (Howell B-3, four quarters). The
  // coarse light (with the gather's 1/pi) follows it within 5 % at every height and stays bounded
  // as z -> 0, where a point light's Eq. 3.2 grows like 1 / z^2 (and is a third too bright at z = s).
  flat_rsm rsm;
  rsm.depth = -5.0;
  rsm.h = 1.0 / 32.0;  // a 32 x 32 block of side 1
  rsm.flux = glm::dvec3(1.0 / 1024.0);
  const coarse_light<double> square = reduce_rsm_block<double>(glm::ivec2(0), 1, glm::ivec2(32), rsm);
  irradiance_settings<double> settings;
  settings.min_distance = 1e-4;
  for (const double z : {0.01, 0.1, 0.3, 1.0, 3.0}) {
    const glm::dvec3 x(0.5, 0.5, rsm.depth + z);
    const double exact = 4.0 * closed_forms::parallel_rectangle(0.5, 0.5, z);  // F = 1 over area 1
    const double coarse = coarse_light_irradiance(x, glm::dvec3(0, 0, -1), square, settings).x / pi;
    CAPTURE(z);
    CAPTURE(coarse / exact);
    CHECK(std::fabs(coarse / exact - 1.0) < 0.05);
    const double point = pixel_light_irradiance(x, glm::dvec3(0, 0, -1), square.position, square.normal, square.flux, settings).x / pi;
    if (z <= 1.0) CHECK(point / exact > 1.25);
  }
}

TEST_CASE("validate_coverage_blocks: 0 (off) to 64") {
  CHECK(validate_coverage_blocks(0) == nullptr);
  CHECK(validate_coverage_blocks(16) == nullptr);
  CHECK(validate_coverage_blocks(64) == nullptr);
  CHECK(validate_coverage_blocks(-1) != nullptr);
  CHECK(validate_coverage_blocks(65) != nullptr);
}

// Issue 38: a point light's coarse lights against its six depth maps
// (include/vplkit/rsm_coarse_visibility.hpp). The light sits at the origin of a cube of 64^2 faces;
// the scene is one axis-aligned wall, its depth maps computed in closed form per texel.
#include <vplkit/rsm_coarse_visibility.hpp>

#include <glm/gtc/matrix_transform.hpp>

namespace {

glm::mat4 face_view(int face) { return glm::lookAt(glm::vec3(0.0f), cube_face_axis<float>(face), cube_face_up<float>(face)); }

// The wall: the plane {p[axis] = at} (at > 0), within `half` of 0 on the other two axes.
struct wall_depths {
  int axis = 0;
  float at = 1.0f;
  float half = 1e30f;
  rsm_unprojection<float> unprojection = make_rsm_unprojection<float>(1.0f, true, glm::ivec2(64));
  float operator()(int face, glm::ivec2 texel) const {
    const glm::vec2 ray = unprojection.ray_origin + glm::vec2(texel) * unprojection.ray_step;
    const glm::vec3 d = glm::mat3(glm::inverse(face_view(face))) * glm::vec3(ray, -1.0f);  // world, per unit of eye depth
    if (!(d[axis] > 0.0f)) return 0.0f;
    const float s = at / d[axis];
    for (int other = 0; other < 3; ++other)
      if (other != axis && !(std::abs(d[other] * s) < half)) return 0.0f;
    return -s;  // the eye-space z of the hit
  }
};

// The coarse light and the receiver (world) seen from gathering face `face`: its eye space.
float cube_visibility(glm::vec3 receiver, glm::vec3 coarse, const wall_depths& wall, int face) {
  const glm::mat4 view = face_view(face), light_from_view = glm::inverse(view);
  cube_depth_frames<float> frames;
  frames.cube_from_light = light_from_view;
  return coarse_light_cube_visibility(transform_point(view, receiver), transform_point(view, coarse), frames, wall.unprojection, glm::ivec2(64), wall);
}

}  // namespace

TEST_CASE("coarse_light_cube_visibility: a coarse light behind a closed wall the light sees is hidden, from every gathering face") {
  // The wall x = 1 (face +x sees it everywhere); coarse lights in front of it, receivers behind,
  // the segments short enough that a sample falls within the slab behind it.
  const wall_depths wall{0, 1.0f};
  for (int face = 0; face < 6; ++face)
    for (glm::vec3 coarse : {glm::vec3(0.5f, 0.1f, 0.05f), glm::vec3(0.7f, -0.3f, 0.2f), glm::vec3(0.6f, 0.4f, -0.4f)})
      for (glm::vec3 receiver : {glm::vec3(1.3f, -0.1f, 0.1f), glm::vec3(1.5f, 0.2f, -0.3f), glm::vec3(1.4f, -0.4f, 0.3f)}) {
        CAPTURE(face);
        CHECK(cube_visibility(receiver, coarse, wall, face) == 0.0f);
      }
  // The same through a ceiling y = 1.5, seen by face +y.
  const wall_depths ceiling{1, 1.5f};
  CHECK(cube_visibility(glm::vec3(0.3f, 1.9f, 0.2f), glm::vec3(0.2f, 1.2f, -0.1f), ceiling, 4) == 0.0f);
}

TEST_CASE("coarse_light_cube_visibility: a coarse light in the open always counts") {
  // No surface at all, a wall beyond both ends, a wall behind the light.
  const wall_depths none{0, 1.0f, 0.0f};  // half 0: the wall is nowhere
  const wall_depths beyond{0, 3.0f};
  const wall_depths behind{2, 0.5f};  // the plane z = 0.5, the segments at z < 0
  for (int face = 0; face < 6; ++face)
    for (glm::vec3 coarse : {glm::vec3(0.5f, 0.1f, -0.05f), glm::vec3(-0.7f, -0.3f, -0.2f), glm::vec3(0.6f, 0.9f, -0.4f)})
      for (glm::vec3 receiver : {glm::vec3(1.3f, -0.1f, -0.1f), glm::vec3(-1.5f, 0.2f, -0.3f), glm::vec3(0.4f, -0.8f, -0.3f)}) {
        CAPTURE(face);
        CHECK(cube_visibility(receiver, coarse, none, face) == 1.0f);
        CHECK(cube_visibility(receiver, coarse, beyond, face) == 1.0f);
        CHECK(cube_visibility(receiver, coarse, behind, face) == 1.0f);
      }
}

TEST_CASE("coarse_light_cube_visibility: a receiver deep in the light's shadow still sees a coarse light beside the occluder") {
  // The wall x = 1 within |y|, |z| < 0.5 shadows the receiver at (2.5, 0, 0); the coarse light at
  // (2, 0, 1.5) is lit (its ray passes the wall's edge) and sees the receiver directly. Every
  // sample lies far behind the wall's depth, beyond the slab: "behind by more than a thickness"
  // would hide it, the slab does not.
  const wall_depths wall{0, 1.0f, 0.5f};
  CHECK(wall(0, glm::ivec2(32, 32)) < 0.0f);  // the receiver's direction sees the wall
  for (int face = 0; face < 6; ++face) {
    CAPTURE(face);
    CHECK(cube_visibility(glm::vec3(2.5f, 0.0f, 0.0f), glm::vec3(2.0f, 0.0f, 1.5f), wall, face) == 1.0f);
  }
}

TEST_CASE("cube_face_eye: the sign-and-swap finds the face and texel that the faces' view-projections render") {
  // The faces as make_light_frustum renders a point light's (rsm_pipeline.cpp): lookAt along
  // cube_face_axis with cube_face_up from a light off the origin, a 90-degree perspective. Every
  // random point is projected by the matrices; the face whose clip volume holds it must be
  // cube_face_eye's (or, within a texel of a face's edge, a neighbour that holds it too), the
  // texel the same within one at the edges, and -z the eye depth the face stores (its clip w).
  constexpr int size = 256;
  const glm::vec3 position(0.3f, 1.7f, -0.4f);
  std::array<glm::mat4, 6> views{}, view_projections{};
  for (int g = 0; g < 6; ++g) {
    views[static_cast<std::size_t>(g)] = glm::lookAt(position, position + cube_face_axis<float>(g), cube_face_up<float>(g));
    view_projections[static_cast<std::size_t>(g)] = glm::perspective(glm::radians(90.0f), 1.0f, 0.05f, 20.0f) * views[static_cast<std::size_t>(g)];
  }
  const rsm_unprojection<float> unprojection = make_rsm_unprojection<float>(1.0f, true, glm::ivec2(size));
  std::mt19937 random(38);
  std::uniform_real_distribution<float> coordinate(-4.0f, 4.0f);
  std::array<int, 6> per_face{};
  int exact_texels = 0;
  constexpr int points = 20000;
  for (int i = 0; i < points; ++i) {
    const glm::vec3 p = position + glm::vec3(coordinate(random), coordinate(random), coordinate(random));
    if (glm::length(p - position) < 0.1f) continue;
    int face = -1;
    const glm::vec3 q = cube_face_eye(p - position, face);
    REQUIRE(face >= 0);
    REQUIRE(face < 6);
    CHECK(face == cube_face_of(p - position));
    ++per_face[static_cast<std::size_t>(face)];
    const glm::vec4 clip = view_projections[static_cast<std::size_t>(face)] * glm::vec4(p, 1.0f);
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    CAPTURE(face);
    CAPTURE(p);
    // The face the kernel picks sees the point: inside its frustum, up to a texel's rounding.
    CHECK(clip.w > 0.0f);
    CHECK(std::abs(ndc.x) <= 1.0f + 1.0f / size);
    CHECK(std::abs(ndc.y) <= 1.0f + 1.0f / size);
    // The eye coordinates are the face's view, the depth the face stores.
    const glm::vec3 eye = glm::vec3(views[static_cast<std::size_t>(face)] * glm::vec4(p, 1.0f));
    CHECK(std::abs(q.x - eye.x) <= 1e-5f * (1.0f + std::abs(eye.z)));
    CHECK(std::abs(q.y - eye.y) <= 1e-5f * (1.0f + std::abs(eye.z)));
    CHECK(std::abs(q.z - eye.z) <= 1e-5f * (1.0f + std::abs(eye.z)));
    CHECK(std::abs(-q.z - clip.w) <= 1e-5f * clip.w);
    // The texel: the kernel's (behind_seen_surface's floor of the ray) against the rasterizer's
    // (the NDC's viewport position), within one.
    const glm::vec2 ray = glm::vec2(q.x, q.y) / -q.z;
    const glm::ivec2 texel = glm::ivec2(glm::floor((ray - unprojection.ray_origin) / unprojection.ray_step + 0.5f));
    const glm::ivec2 raster = glm::clamp(glm::ivec2(glm::floor((ndc * 0.5f + 0.5f) * float(size))), glm::ivec2(0), glm::ivec2(size - 1));
    CHECK(std::abs(texel.x - raster.x) <= 1);
    CHECK(std::abs(texel.y - raster.y) <= 1);
    exact_texels += texel == raster;
  }
  // Every face met, and away from the edges the texels agree exactly.
  for (int count : per_face) CHECK(count > points / 20);
  CHECK(exact_texels > points * 99 / 100);
  // A wrong sign or swap in one face would move its points across the face (ndc off by up to 2).
  int face = -1;
  CHECK(cube_face_eye(glm::vec3(1.0f, 0.5f, 0.25f), face) == glm::vec3(-0.25f, -0.5f, -1.0f));
  CHECK(face == 0);
  CHECK(cube_face_eye(glm::vec3(0.25f, -1.0f, 0.5f), face) == glm::vec3(0.25f, -0.5f, -1.0f));
  CHECK(face == 3);
}
