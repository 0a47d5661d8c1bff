// Light Wave's planning (frontend/techniques/lightwave/lightwave_planning.hpp), without GL: the
// receivers' grids and uniform blocks, the shadow maps' memory, the VPLs that get shadow maps, the
// receivers and their sample points, the casters' groups and a ray's samples merged. In the kernel
// test binary: the planning library links no GL.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>

#include "frontend/core/error.hpp"
#include "frontend/techniques/lightwave/lightwave_planning.hpp"

using namespace vplkit;

namespace {

// The numbers the planning functions take, at lightwave_settings' defaults (the planning takes
// plain numbers: lightwave_settings lives beside the GL pipeline).
struct planning_settings {
  int angle_deg = 5;
  int per_ray = 5;
  int accurate_maps = 20;
  int integrated_maps = 5;
  std::uint32_t seed = 1;
  float receiver_spacing = 1.0f / 8.0f;
  int receiver_triangles = 32768;
};

}  // namespace

TEST_CASE("shadow-map memory: Eq. 5.4 and 5.5 for the thesis's configuration") {
  const double mib = 1024.0 * 1024.0;
  CHECK(static_cast<double>(lightwave_shadow_map_bytes(3840, 2160, 1)) / mib == doctest::Approx(31.640625));
  CHECK(static_cast<double>(lightwave_shadow_map_bytes(3840, 2160, 21)) / mib == doctest::Approx(664.453125));
}

TEST_CASE("Light Wave flux energy: the receivers' grid holds every receiver in rows of a multiple of 4, at most 1024 wide where they fit") {
  for (const int max_side : {16384, 64}) {
    for (const std::size_t count : {std::size_t{1}, std::size_t{3}, std::size_t{4}, std::size_t{1202}, std::size_t{4096}, std::size_t{4097},
                                    std::size_t{5279}, std::size_t{100000}, std::size_t{1} << 22}) {
      CAPTURE(max_side);
      CAPTURE(count);
      const glm::ivec2 grid = lightwave_receiver_grid(count, max_side);
      CHECK(grid.y % 4 == 0);
      CHECK(grid.x % 4 == 0);
      CHECK(grid.y <= max_side);
      const auto cells = static_cast<std::size_t>(grid.x) * static_cast<std::size_t>(grid.y);
      CHECK(cells >= count);
      if (static_cast<std::size_t>(max_side) * 1024 >= count) {
        CHECK(grid.x <= 1024);
        // The fewest rows of 4 that hold them: 4 rows fewer would not.
        CHECK((grid.y == 4 || static_cast<std::size_t>(grid.y - 4) * 1024 < count));
      } else {
        CHECK(grid.y == max_side);  // as many rows as a texture has, each wider
      }
      // No empty row of 4 blocks: the last block row holds a receiver.
      CHECK(cells - count < 4 * static_cast<std::size_t>(grid.y));
      // lightwave_sum_grid, the pipeline's: lightwave_sum_receivers bands of its grid stacked in one texture of
      // at most max_side rows hold every receiver.
      const std::size_t bands = lightwave_sum_receivers;
      const glm::ivec2 banded = lightwave_sum_grid(count, max_side);
      CHECK(static_cast<std::size_t>(banded.y) * bands <= static_cast<std::size_t>(max_side));
      CHECK(static_cast<std::size_t>(banded.x) * static_cast<std::size_t>(banded.y) * bands >= count);
      CHECK(banded.y % 4 == 0);
    }
  }
}

TEST_CASE("Light Wave flux energy: the VPLs' uniform blocks at a stride the GL's offset alignment asks for") {
  // 12 VPLs, 5 a pass, blocks of 240 bytes at a stride of 256 (an alignment of 256, as NVIDIA's):
  // VPL i in block i / 5, rows 3 (i % 5) .. +2; the padding and the last block's tail zero.
  std::vector<lightwave_flux_vpl<float>> vpls;
  for (int i = 0; i < 12; ++i) {
    const float f = static_cast<float>(i);
    vpls.push_back({glm::vec3(f, 1.0f, 2.0f), glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(0.1f * f, 0.2f, 0.3f), 0.01f + f});
  }
  const std::vector<glm::vec4> rows = lightwave_vpl_blocks(vpls, 5, 256);
  REQUIRE(rows.size() == 3 * 16);
  std::vector<bool> written(rows.size(), false);
  for (std::size_t i = 0; i < vpls.size(); ++i) {
    const std::size_t row = i / 5 * 16 + 3 * (i % 5);
    CHECK(rows[row] == glm::vec4(vpls[i].position, vpls[i].radius));
    CHECK(rows[row + 1] == glm::vec4(vpls[i].normal, 0.0f));
    CHECK(rows[row + 2] == glm::vec4(vpls[i].flux, 0.0f));
    written[row] = written[row + 1] = written[row + 2] = true;
  }
  for (std::size_t k = 0; k < rows.size(); ++k)
    if (!written[k]) CHECK(rows[k] == glm::vec4(0.0f));
  // No VPL: one block of zeros; a stride too small for a block: refused.
  CHECK(lightwave_vpl_blocks({}, 5, 256).size() == 16);
  CHECK_THROWS_AS(lightwave_vpl_blocks(vpls, 6, 256), error);
  CHECK_THROWS_AS(lightwave_vpl_blocks(vpls, 5, 250), error);
}

TEST_CASE("the VPLs that get shadow maps: reproducible random draws, and the innermost axis and ring") {
  planning_settings settings;
  const std::vector<int> drawn = lightwave_shadow_vpls(lightwave_mode::accurate, settings.angle_deg, settings.per_ray, settings.accurate_maps, settings.seed);
  CHECK(drawn.size() == 20u);
  CHECK(drawn == lightwave_shadow_vpls(lightwave_mode::accurate, settings.angle_deg, settings.per_ray, settings.accurate_maps, settings.seed));
  std::vector<int> sorted = drawn;
  std::sort(sorted.begin(), sorted.end());
  CHECK(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end());
  settings.seed = 2;
  CHECK(lightwave_shadow_vpls(lightwave_mode::accurate, settings.angle_deg, settings.per_ray, settings.accurate_maps, settings.seed) != drawn);
  // Integrated: the axis and four VPLs 45 degrees off it, a quarter turn apart, all innermost.
  settings = {};
  const std::vector<int> ring = lightwave_shadow_vpls(lightwave_mode::integrated, settings.angle_deg, settings.per_ray, settings.integrated_maps, settings.seed);
  REQUIRE(ring.size() == 5u);
  lightwave_layout_settings<double> layout;
  for (std::size_t k = 1; k < ring.size(); ++k) {
    const lightwave_vpl<double> vpl = lightwave_layout_vpl(ring[k], layout);
    CHECK(ring[k] < lightwave_ray_count(5));  // innermost hemisphere
    CHECK(glm::dot(vpl.normal, layout.light_direction) == doctest::Approx(std::cos(3.14159265358979 / 4)));
    const lightwave_vpl<double> next = lightwave_layout_vpl(ring[k % 4 + 1], layout);
    CHECK(glm::dot(vpl.normal - layout.light_direction * glm::dot(vpl.normal, layout.light_direction),
                   next.normal - layout.light_direction * glm::dot(next.normal, layout.light_direction)) == doctest::Approx(0.0).scale(1.0));
  }
}

TEST_CASE("lightwave_receivers and their samples: subdivided to the bound or the budget; samples in the tangent plane, inside a surface's border") {
  const scene boxes = make_boxes_scene();
  planning_settings settings;
  const mesh receivers = lightwave_receivers(boxes.geometry, settings.receiver_spacing, settings.receiver_triangles);
  const float bound = settings.receiver_spacing * bounds(boxes.geometry).radius();
  for (std::size_t t = 0; t < receivers.indices.size(); t += 3)
    for (int k = 0; k < 3; ++k)
      REQUIRE(glm::length(receivers.vertices[receivers.indices[t + static_cast<std::size_t>(k)]].position -
                          receivers.vertices[receivers.indices[t + static_cast<std::size_t>((k + 1) % 3)]].position) <= bound);
  settings.receiver_triangles = 500;
  CHECK(lightwave_receivers(boxes.geometry, settings.receiver_spacing, settings.receiver_triangles).triangle_count() <= 500u);
  // A unit square's corner sample moves inside, a third of its triangles in; all stay on the plane.
  mesh square_mesh;
  add_quad(square_mesh, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}, {0, 0, 0}, {0, 1, 0}, glm::vec3(0.5f));
  const std::vector<glm::vec3> samples = lightwave_receiver_samples(square_mesh);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    CHECK(samples[i].y == doctest::Approx(0.0));
    CHECK(samples[i].x > 0.1f);
    CHECK(samples[i].x < 0.9f);
    CHECK(samples[i].z > 0.1f);
    CHECK(samples[i].z < 0.9f);
  }
  // Inside a fine grid the sample is the vertex, near enough: within a tenth of the spacing.
  const std::optional<mesh> grid = subdivide_long_edges(square_mesh, 0.1f, 100000);
  REQUIRE(grid);
  const std::vector<glm::vec3> grid_samples = lightwave_receiver_samples(*grid);
  std::size_t interior = 0;
  for (std::size_t i = 0; i < grid_samples.size(); ++i) {
    const glm::vec3 p = grid->vertices[i].position;
    if (p.x < 0.2f || p.x > 0.8f || p.z < 0.2f || p.z > 0.8f) continue;
    ++interior;
    CHECK(glm::length(grid_samples[i] - p) < 0.035f);
  }
  CHECK(interior > 20u);
}

TEST_CASE("lightwave_cluster_casters: groups of about equal importance that partition the VPLs, compact, each map's VPL its group's medoid") {
  // VPLs on a floor and a wall, importance falling off from a corner.
  std::vector<lightwave_cluster_vpl> vpls;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j) {
      const bool wall = i >= 30;
      lightwave_cluster_vpl v;
      v.position = wall ? glm::vec3(3.0f, 0.1f * static_cast<float>(i - 30), 0.1f * static_cast<float>(j)) : glm::vec3(0.1f * static_cast<float>(i), 0.0f, 0.1f * static_cast<float>(j));
      v.normal = wall ? glm::vec3(-1, 0, 0) : glm::vec3(0, 1, 0);
      v.importance = (i + j) % 7 == 0 ? 0.0f : 1.0f / (1.0f + 0.1f * static_cast<float>(i + j));
      v.power = 1.0f;
      v.radius = 0.05f;
      vpls.push_back(v);
    }
  double total = 0.0;
  for (const lightwave_cluster_vpl& v : vpls) total += v.importance;
  const std::vector<lightwave_shadow_caster> groups = lightwave_cluster_casters(vpls, 20, 1.0f);
  REQUIRE(groups.size() == 20u);
  std::vector<int> group_of(vpls.size(), -1);
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const lightwave_shadow_caster& group = groups[g];
    double importance = 0.0;
    glm::dvec3 centre(0.0), facing(0.0);
    for (int i : group.members) {
      const lightwave_cluster_vpl& v = vpls[static_cast<std::size_t>(i)];
      REQUIRE(v.importance > 0.0f);
      REQUIRE(group_of[static_cast<std::size_t>(i)] == -1);  // in one group only
      group_of[static_cast<std::size_t>(i)] = static_cast<int>(g);
      importance += v.importance;
      centre += static_cast<double>(v.importance) * glm::dvec3(v.position);
      facing += static_cast<double>(v.importance) * glm::dvec3(v.normal);
    }
    // About equal importance: the k-d split halves at the median, within a VPL's importance.
    CHECK(importance == doctest::Approx(total / 20.0).epsilon(0.15));
    CHECK(group.radius < 1.2f);  // compact: the whole set spans 4 x 4
    CHECK(group.power == doctest::Approx(static_cast<float>(group.members.size())));
    // The map's VPL is the group's medoid: no member lies nearer its importance-weighted mean
    // position and normal (the normal scaled by 1, the normal_scale given).
    centre /= importance;
    facing /= importance;
    const auto distance = [&](int i) {
      const lightwave_cluster_vpl& v = vpls[static_cast<std::size_t>(i)];
      return glm::dot(glm::dvec3(v.position) - centre, glm::dvec3(v.position) - centre) + glm::dot(glm::dvec3(v.normal) - facing, glm::dvec3(v.normal) - facing);
    };
    for (int i : group.members) CHECK(distance(group.vpl) <= distance(i));
  }
  for (std::size_t i = 0; i < vpls.size(); ++i) CHECK((group_of[i] >= 0) == (vpls[i].importance > 0.0f));  // every VPL that lights something
  // Fewer VPLs than groups asked: one group each; none: no group.
  CHECK(lightwave_cluster_casters(std::vector<lightwave_cluster_vpl>(vpls.begin(), vpls.begin() + 3), 20, 1.0f).size() == 2u);  // one has no importance
  CHECK(lightwave_cluster_casters({}, 20, 1.0f).empty());
}

TEST_CASE("lightwave_merge_ray_samples: a ray's samples on one plane become one VPL of their flux; far away it lights as they do; planes stay apart") {
  // Ray 0: five samples on the floor (y = 0), spread over a patch of 0.1; ray 1: three on the floor
  // and two on a wall (x = 1). Layout index = sample * rays + ray with rays = 2.
  std::vector<lightwave_flux_vpl<float>> vpls;
  std::vector<int> layout;
  const glm::vec3 up(0, 1, 0), wall(-1, 0, 0);
  for (int sample = 0; sample < 5; ++sample) {
    vpls.push_back({glm::vec3(0.02f * static_cast<float>(sample), 0.0f, 0.01f * static_cast<float>(sample % 3)), up,
                    glm::vec3(0.1f + 0.05f * static_cast<float>(sample), 0.2f, 0.05f), 0.03f});
    layout.push_back(sample * 2);
    const bool on_wall = sample >= 3;
    vpls.push_back({on_wall ? glm::vec3(1.0f, 0.3f + 0.02f * static_cast<float>(sample), 0.0f) : glm::vec3(0.5f + 0.02f * static_cast<float>(sample), 0.0f, 0.2f),
                    on_wall ? wall : up, glm::vec3(0.3f), 0.04f});
    layout.push_back(sample * 2 + 1);
  }
  const std::vector<lightwave_flux_vpl<float>> merged = lightwave_merge_ray_samples(vpls, layout, 2, 1e-3f);
  REQUIRE(merged.size() == 3u);  // ray 0's floor, ray 1's floor, ray 1's wall
  // Flux is conserved, per merged VPL and in total; the radius is the joint patch's.
  glm::dvec3 total_in(0.0), total_out(0.0);
  for (const auto& v : vpls) total_in += glm::dvec3(v.flux);
  for (const auto& v : merged) total_out += glm::dvec3(v.flux);
  CHECK(total_out.x == doctest::Approx(total_in.x).epsilon(1e-6));
  CHECK(total_out.y == doctest::Approx(total_in.y).epsilon(1e-6));
  CHECK(merged[0].radius == doctest::Approx(0.03 * std::sqrt(5.0)).epsilon(1e-6));
  CHECK(merged[1].flux.x == doctest::Approx(0.9f));
  CHECK(merged[2].normal == wall);
  CHECK(merged[2].flux.x == doctest::Approx(0.6f));
  CHECK(merged[2].radius == doctest::Approx(0.04 * std::sqrt(2.0)).epsilon(1e-6));
  // Far from the patch (50x its size) the merged VPL gives the irradiance of its samples.
  for (const glm::vec3& receiver : {glm::vec3(3.0f, 4.0f, 1.0f), glm::vec3(-4.0f, 2.0f, -3.0f), glm::vec3(0.5f, 5.0f, 0.0f)}) {
    const glm::vec3 n = glm::normalize(-receiver);
    glm::dvec3 separate(0.0);
    for (int sample = 0; sample < 5; ++sample) separate += glm::dvec3(lightwave_bounce_irradiance(receiver, n, vpls[static_cast<std::size_t>(2 * sample)], 0.01f));
    const glm::vec3 together = lightwave_bounce_irradiance(receiver, n, merged[0], 0.01f);
    CAPTURE(receiver);
    CHECK(together.x == doctest::Approx(separate.x).epsilon(2e-3));
    CHECK(together.y == doctest::Approx(separate.y).epsilon(2e-3));
  }
  // A tolerance of 0 still merges samples exactly on one plane; mismatched inputs are refused.
  CHECK(lightwave_merge_ray_samples(vpls, layout, 2, 0.0f).size() == 3u);
  CHECK_THROWS_AS(lightwave_merge_ray_samples(vpls, std::vector<int>(3, 0), 2, 1e-3f), error);
}
