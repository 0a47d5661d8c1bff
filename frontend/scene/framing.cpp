#include "frontend/scene/framing.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "frontend/scene/pose.hpp"

namespace vplkit {

// A binary BVH over triangle bounds, split at the median centroid of the longest axis, at most
// 4 triangles per leaf.
struct mesh_ray_caster::tree {
  struct node {
    glm::vec3 minimum, maximum;
    std::uint32_t first = 0;  ///< leaf: first entry of `order`; inner: the right child (the left is next)
    std::uint32_t count = 0;  ///< leaf: its triangles; 0 for an inner node
  };
  std::vector<node> nodes;
  std::vector<std::uint32_t> order;  ///< triangle indices, leaves' runs
};

namespace {

constexpr std::uint32_t leaf_size = 4;

glm::vec3 corner_of(const mesh& geometry, std::size_t triangle, int k) {
  return geometry.vertices[geometry.indices[3 * triangle + static_cast<std::size_t>(k)]].position;
}

bool slab_hit(const glm::vec3& origin, const glm::vec3& inverse, const glm::vec3& minimum, const glm::vec3& maximum, float far) {
  const glm::vec3 t0 = (minimum - origin) * inverse, t1 = (maximum - origin) * inverse;
  const glm::vec3 low = glm::min(t0, t1), high = glm::max(t0, t1);
  const float enter = std::max({low.x, low.y, low.z, 0.0f}), leave = std::min({high.x, high.y, high.z, far});
  return enter <= leave;
}

}  // namespace

mesh_ray_caster::mesh_ray_caster(const mesh& geometry) : tree_(std::make_unique<tree>()), geometry_(geometry) {
  const std::size_t count = geometry.triangle_count();
  tree_->order.resize(count);
  std::iota(tree_->order.begin(), tree_->order.end(), 0u);
  if (count == 0) return;
  std::vector<glm::vec3> centroids(count);
  for (std::size_t t = 0; t < count; ++t) centroids[t] = (corner_of(geometry, t, 0) + corner_of(geometry, t, 1) + corner_of(geometry, t, 2)) / 3.0f;
  struct task {
    std::uint32_t node, begin, end;
  };
  std::vector<task> stack{{0, 0, static_cast<std::uint32_t>(count)}};
  tree_->nodes.push_back({});
  while (!stack.empty()) {
    const task current = stack.back();
    stack.pop_back();
    glm::vec3 low(std::numeric_limits<float>::max()), high(std::numeric_limits<float>::lowest());
    glm::vec3 centre_low = low, centre_high = high;
    for (std::uint32_t i = current.begin; i < current.end; ++i) {
      const std::uint32_t t = tree_->order[i];
      for (int k = 0; k < 3; ++k) {
        low = glm::min(low, corner_of(geometry, t, k));
        high = glm::max(high, corner_of(geometry, t, k));
      }
      centre_low = glm::min(centre_low, centroids[t]);
      centre_high = glm::max(centre_high, centroids[t]);
    }
    tree::node& made = tree_->nodes[current.node];
    made.minimum = low;
    made.maximum = high;
    const glm::vec3 spread = centre_high - centre_low;
    if (current.end - current.begin <= leaf_size || !(std::max({spread.x, spread.y, spread.z}) > 0.0f)) {
      made.first = current.begin;
      made.count = current.end - current.begin;
      continue;
    }
    const int axis = spread.x >= spread.y && spread.x >= spread.z ? 0 : spread.y >= spread.z ? 1 : 2;
    const std::uint32_t middle = current.begin + (current.end - current.begin) / 2;
    std::nth_element(tree_->order.begin() + current.begin, tree_->order.begin() + middle, tree_->order.begin() + current.end,
                     [&](std::uint32_t a, std::uint32_t b) { return centroids[a][axis] < centroids[b][axis]; });
    const auto left = static_cast<std::uint32_t>(tree_->nodes.size());
    tree_->nodes.push_back({});
    const auto right = static_cast<std::uint32_t>(tree_->nodes.size());
    tree_->nodes.push_back({});
    tree_->nodes[current.node].first = right;  // the left child is right - 1
    tree_->nodes[current.node].count = 0;
    stack.push_back({right, middle, current.end});
    stack.push_back({left, current.begin, middle});
  }
}

mesh_ray_caster::~mesh_ray_caster() = default;

mesh_ray_caster::hit mesh_ray_caster::intersect(const glm::vec3& origin, const glm::vec3& direction, float far) const {
  hit best;
  if (tree_->nodes.empty()) return best;
  const glm::vec3 inverse(1.0f / direction.x, 1.0f / direction.y, 1.0f / direction.z);
  float nearest = far;
  std::array<std::uint32_t, 128> stack{};
  std::size_t depth = 0;
  stack[depth++] = 0;
  while (depth > 0) {
    const tree::node& current = tree_->nodes[stack[--depth]];
    if (!slab_hit(origin, inverse, current.minimum, current.maximum, nearest)) continue;
    if (current.count == 0) {
      if (depth + 2 > stack.size()) continue;  // deeper than a median split of 2^64 triangles can be
      stack[depth++] = current.first;          // right
      stack[depth++] = current.first - 1;      // left
      continue;
    }
    for (std::uint32_t i = current.first; i < current.first + current.count; ++i) {
      const std::uint32_t t = tree_->order[i];
      // Moeller-Trumbore.
      const glm::vec3 a = corner_of(geometry_, t, 0), b = corner_of(geometry_, t, 1), c = corner_of(geometry_, t, 2);
      const glm::vec3 e1 = b - a, e2 = c - a, p = glm::cross(direction, e2);
      const float determinant = glm::dot(e1, p);
      if (!(std::fabs(determinant) > 0.0f)) continue;
      const float inverse_determinant = 1.0f / determinant;
      const glm::vec3 s = origin - a;
      const float u = glm::dot(s, p) * inverse_determinant;
      if (u < 0.0f || u > 1.0f) continue;
      const glm::vec3 q = glm::cross(s, e1);
      const float v = glm::dot(direction, q) * inverse_determinant;
      if (v < 0.0f || u + v > 1.0f) continue;
      const float t_hit = glm::dot(e2, q) * inverse_determinant;
      if (!(t_hit > 0.0f && t_hit < nearest)) continue;
      nearest = t_hit;
      best.found = true;
      best.distance = t_hit;
      best.triangle = t;
      const vertex& va = geometry_.vertices[geometry_.indices[3 * std::size_t{t}]];
      const vertex& vb = geometry_.vertices[geometry_.indices[3 * std::size_t{t} + 1]];
      const vertex& vc = geometry_.vertices[geometry_.indices[3 * std::size_t{t} + 2]];
      best.normal = (1.0f - u - v) * va.normal + u * vb.normal + v * vc.normal;
    }
  }
  return best;
}

enclosure measure_enclosure(const mesh_ray_caster& rays, const glm::vec3& point, int directions, float far) {
  enclosure result;
  if (directions < 1) return result;
  int hits = 0, facing = 0;
  std::vector<float> distances;
  const float golden = 2.39996322972865332f;  // pi (3 - sqrt 5)
  for (int i = 0; i < directions; ++i) {
    const float z = 1.0f - (2.0f * static_cast<float>(i) + 1.0f) / static_cast<float>(directions);
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z)), angle = golden * static_cast<float>(i);
    const glm::vec3 direction(r * std::cos(angle), z, r * std::sin(angle));
    const mesh_ray_caster::hit found = rays.intersect(point, direction, far);
    if (!found.found) continue;
    ++hits;
    distances.push_back(found.distance);
    if (glm::dot(found.normal, direction) < 0.0f) ++facing;
  }
  if (!distances.empty()) {
    std::nth_element(distances.begin(), distances.begin() + static_cast<std::ptrdiff_t>(distances.size() / 2), distances.end());
    result.median_distance = distances[distances.size() / 2];
  }
  result.hit_fraction = static_cast<float>(hits) / static_cast<float>(directions);
  result.facing_fraction = static_cast<float>(facing) / static_cast<float>(directions);
  return result;
}

namespace {

const glm::vec3 floor_albedo(0.73f);

std::string percent(float fraction) { return std::to_string(static_cast<int>(std::lround(100.0f * fraction))) + " %"; }

// The free distance from `origin` along `direction` (unit), or `otherwise` when nothing is hit.
float free_distance(const mesh_ray_caster& rays, const glm::vec3& origin, const glm::vec3& direction, float otherwise) {
  const mesh_ray_caster::hit found = rays.intersect(origin, direction, otherwise);
  return found.found ? found.distance : otherwise;
}

// Whether the mesh has a floor of its own at the bottom of its bounds: of a grid of rays cast
// straight down over the middle half of its footprint, nearly all meet an upward-facing surface
// at the lowest height (an added floor there would coincide with it and flicker).
bool has_own_floor(const mesh_ray_caster& rays, const bounding_box& box) {
  const glm::vec3 extent = box.maximum - box.minimum;
  const float tolerance = 1e-3f * std::max({extent.x, extent.y, extent.z, 1e-6f});
  int on_floor = 0;
  constexpr int side = 8;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j) {
      const glm::vec3 origin(box.minimum.x + extent.x * (0.25f + 0.5f * (static_cast<float>(i) + 0.5f) / side), box.maximum.y + tolerance,
                             box.minimum.z + extent.z * (0.25f + 0.5f * (static_cast<float>(j) + 0.5f) / side));
      // The lowest upward-facing surface below the point: step through what lies above it.
      glm::vec3 from = origin;
      for (int layer = 0; layer < 64; ++layer) {
        const mesh_ray_caster::hit found = rays.intersect(from, glm::vec3(0.0f, -1.0f, 0.0f), from.y - box.minimum.y + 2.0f * tolerance);
        if (!found.found) break;
        from.y -= found.distance;
        if (from.y <= box.minimum.y + tolerance) {
          on_floor += found.normal.y > 0.0f ? 1 : 0;
          break;
        }
        from.y -= tolerance;
      }
    }
  return on_floor >= (side * side * 9) / 10;
}

spot_light<float> aimed_spot(const glm::vec3& position, const glm::vec3& target, float intensity, float inner_degrees, float outer_degrees) {
  spot_light<float> light;
  light.position = position;
  light.direction = glm::normalize(target - position);
  light.intensity = glm::vec3(intensity);
  light.cos_inner = std::cos(glm::radians(inner_degrees));
  light.cos_outer = std::cos(glm::radians(outer_degrees));
  return light;
}

}  // namespace

scene frame_mesh(std::string name, mesh geometry, framing_needs needs) {
  scene s;
  s.name = std::move(name);
  const bounding_box box = bounds(geometry);
  const float radius = std::max(box.radius(), 1e-3f);
  const glm::vec3 c = box.centre(), extent = box.maximum - box.minimum;
  s.view.near_plane = 0.01f * radius;
  s.view.far_plane = 20.0f * radius;

  // Inside a closed room? The centre first, then points a quarter of the bounds around it (the
  // centre may be inside furniture); the first enclosed one, nearest the centre first.
  const mesh_ray_caster rays(geometry);
  const float far = 4.0f * radius;
  std::vector<glm::vec3> candidates{c};
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j)
      for (int k = -1; k <= 1; ++k)
        if (i != 0 || j != 0 || k != 0) candidates.push_back(c + 0.25f * extent * glm::vec3(static_cast<float>(i), static_cast<float>(j), static_cast<float>(k)));
  std::stable_sort(candidates.begin() + 1, candidates.end(), [&](const glm::vec3& a, const glm::vec3& b) { return glm::length(a - c) < glm::length(b - c); });
  const glm::vec3* inside = nullptr;
  enclosure measured = measure_enclosure(rays, c, 128, far);
  const enclosure at_centre = measured;
  for (const glm::vec3& candidate : candidates) {
    const enclosure e = &candidate == &candidates.front() ? at_centre : measure_enclosure(rays, candidate, 128, far);
    if (e.facing_fraction >= closed_room_facing_fraction && e.median_distance >= closed_room_median_distance * radius) {
      inside = &candidate;
      measured = e;
      break;
    }
  }

  std::string how;
  if (inside) {
    const glm::vec3 o = *inside;
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    const float floor_y = o.y - free_distance(rays, o, -up, o.y - box.minimum.y + 1e-3f * radius);
    const float ceiling_y = o.y + free_distance(rays, o, up, box.maximum.y - o.y + 1e-3f * radius);
    const float height = std::max(ceiling_y - floor_y, 1e-3f * radius);
    const glm::vec3 eye_level(o.x, floor_y + 0.6f * height, o.z);
    // The longest free horizontal direction from the eye level: the camera backs off against the
    // wall behind it and looks along it, across the room.
    glm::vec3 across(0.0f, 0.0f, -1.0f);
    float longest = -1.0f;
    for (int i = 0; i < 16; ++i) {
      const float angle = 3.14159265358979324f * static_cast<float>(i) / 16.0f;
      const glm::vec3 direction(std::sin(angle), 0.0f, -std::cos(angle));
      const float forwards = free_distance(rays, eye_level, direction, far), backwards = free_distance(rays, eye_level, -direction, far);
      if (forwards + backwards > longest) {
        longest = forwards + backwards;
        across = forwards >= backwards ? direction : -direction;
      }
    }
    const float behind = free_distance(rays, eye_level, -across, far), ahead = free_distance(rays, eye_level, across, far);
    const glm::vec3 camera_position = eye_level - across * (0.85f * behind);
    const glm::vec3 target = glm::vec3(o.x, floor_y + 0.3f * height, o.z) + across * (0.25f * ahead);
    if (needs.camera) {
      s.view.position = camera_position;
      s.view.target = target;
      s.view.vertical_fov_degrees = 60.0f;
      s.view.near_plane = std::max(1e-4f * radius, 0.05f * std::min(0.15f * behind + 1e-6f, 0.1f * height));
    }
    if (needs.light) {
      // Under the ceiling above the camera, pulled a little into the room, aimed where the camera
      // looks with a cone wider than the view: everything the camera sees faces the light's map.
      glm::vec3 light_position = glm::vec3(camera_position.x, floor_y + 0.9f * height, camera_position.z) + across * (0.1f * behind);
      const glm::vec3 towards = light_position - eye_level;
      const float free = free_distance(rays, eye_level, glm::normalize(towards), glm::length(towards) * 2.0f);
      if (free < glm::length(towards)) light_position = eye_level + glm::normalize(towards) * (0.8f * free);
      const float distance = glm::length(target - light_position);
      s.lights = {scene_light{light_kind::spot, aimed_spot(light_position, target, 1.5f * distance * distance, 50.0f, 70.0f), {}, {}}};
    }
    how = "a closed room (" + percent(measured.facing_fraction) + " of the rays from " + format_point(o) +
          " meet a surface facing it): " + std::string(needs.camera ? "the camera" : "") + (needs.camera && needs.light ? " and " : "") +
          (needs.light ? "a spot light" : "") + " placed inside, below the ceiling";
  } else {
    // A raised three-quarter view: 35 degrees around from +z, 25 degrees up, the bounding sphere
    // filling the view.
    const float azimuth = glm::radians(35.0f), elevation = glm::radians(25.0f);
    const glm::vec3 from(std::sin(azimuth) * std::cos(elevation), std::sin(elevation), std::cos(azimuth) * std::cos(elevation));
    const float fov = 40.0f;
    const float distance = 1.1f * radius / std::sin(glm::radians(0.5f * fov));
    if (needs.camera) {
      s.view.position = c + from * distance;
      s.view.target = c;
      s.view.vertical_fov_degrees = fov;
    }
    const float floor_y = box.minimum.y;
    // A floor under the mesh gives its light somewhere to bounce, unless it has its own.
    const bool own_floor = has_own_floor(rays, box);
    if (needs.light && !own_floor) {
      const float floor_extent = 3.0f * radius;
      // Grown by exactly the quad: push_back on a full vector doubles its capacity, and a mesh
      // of millions of vertices (a file's, read to its size) then kept that slack for the whole
      // run (a faceted 2^21-triangle OBJ: 553 MB of vertices instead of 277). The loaders leave
      // room for it (framing_floor_vertices), so that this reserves nothing new.
      geometry.vertices.reserve(geometry.vertices.size() + framing_floor_vertices);
      geometry.indices.reserve(geometry.indices.size() + framing_floor_indices);
      add_quad(geometry, {c.x - floor_extent, floor_y, c.z + floor_extent}, {c.x + floor_extent, floor_y, c.z + floor_extent},
               {c.x + floor_extent, floor_y, c.z - floor_extent}, {c.x - floor_extent, floor_y, c.z - floor_extent}, {0, 1, 0}, floor_albedo);
    }
    if (needs.light) {
      // From above, 70 degrees around from the camera, 55 degrees up, at 2.8 radii.
      const float light_azimuth = azimuth - glm::radians(70.0f), light_elevation = glm::radians(55.0f);
      const glm::vec3 light_from(std::sin(light_azimuth) * std::cos(light_elevation), std::sin(light_elevation),
                                 std::cos(light_azimuth) * std::cos(light_elevation));
      const glm::vec3 light_position = c + light_from * (2.8f * radius);
      const glm::vec3 aim(c.x, floor_y + 0.25f * (box.maximum.y - floor_y), c.z);
      const float d = glm::length(aim - light_position);
      s.lights = {scene_light{light_kind::spot, aimed_spot(light_position, aim, 0.9f * d * d, 35.0f, 50.0f), {}, {}}};
    }
    how = "an object or an open scene (" + percent(at_centre.facing_fraction) + " of the rays from its centre meet a surface facing it): " +
          std::string(needs.camera ? "a raised three-quarter view" : "") + (needs.camera && needs.light ? ", " : "") +
          (needs.light ? (own_floor ? "a spot light from above (the scene has its own floor)" : "a spot light from above and a floor") : "");
  }
  s.geometry = std::move(geometry);
  if (needs.camera || needs.light) {
    std::string arguments;
    if (needs.camera) arguments += "--camera " + format_pose(pose_of(s.view));
    if (needs.light) arguments += std::string(arguments.empty() ? "" : " ") + "--light " + format_pose(pose_of(s.lights.front()));
    s.notes.push_back("scene " + s.name + ": no " + (needs.camera && needs.light ? "camera or light" : needs.camera ? "camera" : "light") +
                      " of its own; framed as " + how + ": " + arguments);
  }
  return s;
}

}  // namespace vplkit
