#include "frontend/techniques/lightwave/lightwave_planning.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/cube_map.hpp>
#include <vplkit/hash.hpp>

#include "frontend/core/error.hpp"
#include "frontend/core/parallel.hpp"

namespace vplkit {

std::uint64_t lightwave_shadow_map_bytes(int width, int height, int maps) {
  return static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height) * static_cast<std::uint64_t>(maps) * 4u;
}


std::vector<int> lightwave_shadow_vpls(lightwave_mode mode, int angle_deg, int per_ray, int maps, std::uint32_t seed) {
  const int count = lightwave_vpl_count(angle_deg, per_ray);
  std::vector<int> chosen;
  if (mode == lightwave_mode::accurate) {
    // A partial Fisher-Yates shuffle driven by the shared hash: reproducible for a seed.
    std::vector<int> indices(static_cast<std::size_t>(count));
    for (int i = 0; i < count; ++i) indices[static_cast<std::size_t>(i)] = i;
    for (int i = 0; i < maps; ++i) {
      const auto span = static_cast<std::uint32_t>(count - i);
      const int j = i + static_cast<int>(hash_combine(seed, static_cast<std::uint32_t>(i)) % span);
      std::swap(indices[static_cast<std::size_t>(i)], indices[static_cast<std::size_t>(j)]);
      chosen.push_back(indices[static_cast<std::size_t>(i)]);
    }
  } else if (mode == lightwave_mode::integrated) {
    const int azimuths = 360 / angle_deg;
    const int polar_step = std::max(1, static_cast<int>(std::lround(45.0 / angle_deg)));
    chosen.push_back(0);  // the axis
    const int ring = maps - 1;
    for (int k = 0; k < ring; ++k) chosen.push_back(1 + (polar_step - 1) * azimuths + (k * azimuths) / ring);
  }
  return chosen;
}

namespace {

// One group of lightwave_cluster_casters: its members (indices into the VPLs) and its map's VPL.
lightwave_shadow_caster make_group(const std::vector<lightwave_cluster_vpl>& vpls, const std::vector<int>& members, float normal_scale) {
  lightwave_shadow_caster group;
  double importance = 0.0, power = 0.0;
  glm::dvec3 position(0.0), normal(0.0);
  for (int i : members) {
    const lightwave_cluster_vpl& vpl = vpls[static_cast<std::size_t>(i)];
    importance += vpl.importance;
    power += vpl.power;
    position += static_cast<double>(vpl.power) * glm::dvec3(vpl.position);
    normal += static_cast<double>(vpl.power) * glm::dvec3(vpl.normal);
  }
  if (power > 0.0) position /= power;
  double spread = 0.0;
  for (int i : members) {
    const lightwave_cluster_vpl& vpl = vpls[static_cast<std::size_t>(i)];
    spread += static_cast<double>(vpl.power) *
              (glm::dot(glm::dvec3(vpl.position) - position, glm::dvec3(vpl.position) - position) + static_cast<double>(vpl.radius) * vpl.radius);
  }
  group.position = glm::vec3(position);
  group.normal = glm::length(normal) > 0.0 ? glm::vec3(glm::normalize(normal)) : vpls[static_cast<std::size_t>(members.front())].normal;
  group.radius = static_cast<float>(power > 0.0 ? std::sqrt(spread / power) : 0.0);
  group.power = static_cast<float>(power);
  group.members = members;
  // The map's VPL: the member nearest the group's importance-weighted centre (position, and the
  // normal scaled to scene units), the one point whose view stands best for the group's.
  glm::dvec3 centre(0.0), facing(0.0);
  for (int i : members) {
    const lightwave_cluster_vpl& vpl = vpls[static_cast<std::size_t>(i)];
    centre += static_cast<double>(vpl.importance) * glm::dvec3(vpl.position);
    facing += static_cast<double>(vpl.importance) * glm::dvec3(vpl.normal);
  }
  centre /= importance;
  facing /= importance;
  double nearest = std::numeric_limits<double>::max();
  for (int i : members) {
    const lightwave_cluster_vpl& vpl = vpls[static_cast<std::size_t>(i)];
    const glm::dvec3 d = glm::dvec3(vpl.position) - centre, e = (glm::dvec3(vpl.normal) - facing) * static_cast<double>(normal_scale);
    const double distance = glm::dot(d, d) + glm::dot(e, e);
    if (distance < nearest) nearest = distance, group.vpl = i;
  }
  return group;
}

}  // namespace

std::vector<lightwave_shadow_caster> lightwave_cluster_casters(const std::vector<lightwave_cluster_vpl>& vpls, int count, float normal_scale) {
  std::vector<int> order;
  for (std::size_t i = 0; i < vpls.size(); ++i)
    if (vpls[i].importance > 0.0f) order.push_back(static_cast<int>(i));
  std::vector<lightwave_shadow_caster> groups;
  if (order.empty() || count < 1) return groups;
  // The coordinate a split sorts by: position, or the normal scaled to scene units.
  const auto coordinate = [&](int i, int axis) {
    const lightwave_cluster_vpl& vpl = vpls[static_cast<std::size_t>(i)];
    return axis < 3 ? vpl.position[axis] : normal_scale * vpl.normal[axis - 3];
  };
  // Splits order[begin, end) into k groups, appended in a fixed order (depth first, low side first).
  const auto split = [&](const auto& self, std::size_t begin, std::size_t end, int k) -> void {
    if (k <= 1 || end - begin <= 1) {
      const std::vector<int> members(order.begin() + static_cast<std::ptrdiff_t>(begin), order.begin() + static_cast<std::ptrdiff_t>(end));
      groups.push_back(make_group(vpls, members, normal_scale));
      return;
    }
    int widest = 0;
    float extent = -1.0f;
    for (int axis = 0; axis < 6; ++axis) {
      float low = coordinate(order[begin], axis), high = low;
      for (std::size_t j = begin; j < end; ++j) {
        low = std::min(low, coordinate(order[j], axis));
        high = std::max(high, coordinate(order[j], axis));
      }
      if (high - low > extent) extent = high - low, widest = axis;
    }
    std::sort(order.begin() + static_cast<std::ptrdiff_t>(begin), order.begin() + static_cast<std::ptrdiff_t>(end), [&](int a, int b) {
      const float ca = coordinate(a, widest), cb = coordinate(b, widest);
      return ca < cb || (ca == cb && a < b);
    });
    double total = 0.0;
    for (std::size_t j = begin; j < end; ++j) total += vpls[static_cast<std::size_t>(order[j])].importance;
    const int low_groups = k / 2;
    const double target = total * low_groups / k;
    std::size_t middle = begin;
    double cumulative = 0.0;
    while (middle < end && cumulative + 0.5 * vpls[static_cast<std::size_t>(order[middle])].importance < target)
      cumulative += vpls[static_cast<std::size_t>(order[middle++])].importance;
    middle = std::clamp(middle, begin + 1, end - 1);
    const int low = std::min(low_groups, static_cast<int>(middle - begin));
    self(self, begin, middle, low);
    self(self, middle, end, std::min(k - low, static_cast<int>(end - middle)));
  };
  split(split, 0, order.size(), std::min(count, static_cast<int>(order.size())));
  return groups;
}

glm::mat4 lightwave_look_along(const glm::vec3& position, const glm::vec3& direction) {
  const glm::vec3 up = std::abs(direction.y) > 0.99f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
  return glm::lookAt(position, position + direction, up);
}

std::vector<lightwave_receiver_point> lightwave_surface_points(const mesh& geometry, const camera* view, float aspect, int count) {
  const glm::mat4 view_projection = view ? camera_projection_matrix(*view, aspect) * camera_view_matrix(*view) : glm::mat4(1.0f);
  std::vector<double> cumulative;
  double total = 0.0;
  for (std::size_t t = 0; t + 2 < geometry.indices.size(); t += 3) {
    const glm::vec3 a = geometry.vertices[geometry.indices[t]].position, b = geometry.vertices[geometry.indices[t + 1]].position,
                    c = geometry.vertices[geometry.indices[t + 2]].position;
    total += 0.5 * static_cast<double>(glm::length(glm::cross(b - a, c - a)));
    cumulative.push_back(total);
  }
  std::vector<lightwave_receiver_point> points;
  if (!(total > 0.0)) return points;
  for (int k = 0; k < count; ++k) {
    const double target = (k + 0.5) / count * total;
    const std::size_t t = static_cast<std::size_t>(std::lower_bound(cumulative.begin(), cumulative.end(), target) - cumulative.begin());
    const std::size_t base = 3 * std::min(t, cumulative.size() - 1);
    float u = uniform_float_from_bits(hash_combine(0x51edu, static_cast<std::uint32_t>(k)));
    float v = uniform_float_from_bits(hash_uint32(hash_combine(0x51edu, static_cast<std::uint32_t>(k))));
    if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
    const vertex& a = geometry.vertices[geometry.indices[base]];
    const vertex& b = geometry.vertices[geometry.indices[base + 1]];
    const vertex& c = geometry.vertices[geometry.indices[base + 2]];
    const glm::vec3 normal = (1.0f - u - v) * a.normal + u * b.normal + v * c.normal;
    if (!(glm::length(normal) > 0.0f)) continue;
    const glm::vec3 position = (1.0f - u - v) * a.position + u * b.position + v * c.position;
    if (view) {
      const glm::vec4 clip = view_projection * glm::vec4(position, 1.0f);
      const bool in_view = clip.w > 0.0f && std::abs(clip.x) <= clip.w && std::abs(clip.y) <= clip.w;
      if (!in_view || !(glm::dot(normal, view->position - position) > 0.0f)) continue;
    }
    points.push_back({position, glm::normalize(normal)});
  }
  return points;
}

glm::mat4 lightwave_aimed_shadow_matrix(const glm::vec3& eye, const glm::vec3& fallback_direction, const std::vector<lightwave_receiver_point>& points,
                                        const std::vector<float>& weights, float near_plane, float far_plane, float aspect, float fallback_fov_degrees) {
  glm::vec3 mean(0.0f);
  std::vector<glm::vec3> lit;  // the points of weight > 0
  for (std::size_t i = 0; i < points.size() && i < weights.size(); ++i) {
    if (!(weights[i] > 0.0f)) continue;
    const glm::vec3 offset = points[i].position - eye;
    if (!(glm::dot(offset, offset) > 0.0f)) continue;
    mean += weights[i] * glm::normalize(offset);
    lit.push_back(points[i].position);
  }
  if (!(glm::length(mean) > 1e-6f))
    return glm::perspective(glm::radians(fallback_fov_degrees), aspect, near_plane, far_plane) * lightwave_look_along(eye, fallback_direction);
  const glm::vec3 axis = glm::normalize(mean);
  const glm::mat4 view = lightwave_look_along(eye, axis);
  // The half-angles that hold every lit point, across and up the map, plus 2 degrees.
  float tan_x = 0.0f, tan_y = 0.0f;
  for (const glm::vec3& position : lit) {
    const glm::vec3 in_view = glm::vec3(view * glm::vec4(position, 1.0f));
    const float depth = std::max(-in_view.z, 1e-4f);
    tan_x = std::max(tan_x, std::abs(in_view.x) / depth);
    tan_y = std::max(tan_y, std::abs(in_view.y) / depth);
  }
  const float max_half = glm::radians(80.0f), margin = glm::radians(2.0f);
  const float half_y = std::min(max_half, std::max(std::atan(tan_y), std::atan(tan_x / aspect)) + margin);
  return glm::perspective(2.0f * half_y, aspect, near_plane, far_plane) * view;
}

mesh lightwave_receivers(const mesh& geometry, float spacing, int max_triangles) {
  // The edge bound grows by half until the subdivision fits the budget (a scene already that
  // fine, or finer, stays as it is).
  float max_edge = spacing * std::max(bounds(geometry).radius(), 1e-3f);
  for (int attempt = 0; attempt < 64; ++attempt, max_edge *= 1.5f)
    if (std::optional<mesh> subdivided = subdivide_long_edges(geometry, max_edge, static_cast<std::size_t>(max_triangles)))
      return *subdivided;
  return geometry;
}

glm::ivec2 lightwave_receiver_grid(std::size_t receivers, int max_side) {
  const std::size_t count = std::max<std::size_t>(receivers, 1);
  const auto up4 = [](std::size_t n) { return (n + 3) / 4 * 4; };
  const std::size_t max_rows = std::max<std::size_t>(4, static_cast<std::size_t>(std::max(max_side, 0)) / 4 * 4);
  // As few rows of up to 1024 as hold them, or wider rows where that many would not fit.
  const std::size_t rows = std::min(up4((count + 1023) / 1024), max_rows);
  const std::size_t width = up4((count + rows - 1) / rows);
  return {static_cast<int>(std::min<std::size_t>(width, std::size_t{1} << 30)), static_cast<int>(rows)};
}

glm::ivec2 lightwave_sum_grid(std::size_t receivers, int max_texture_side) {
  constexpr auto bands = static_cast<std::size_t>(lightwave_sum_receivers);
  return lightwave_receiver_grid((receivers + bands - 1) / bands, max_texture_side / lightwave_sum_receivers);
}

int lightwave_vpl_pass_count(std::size_t vpls, int per_pass) {
  const auto per = static_cast<std::size_t>(std::max(per_pass, 1));
  return static_cast<int>(std::max<std::size_t>(1, (vpls + per - 1) / per));
}

std::vector<glm::vec4> lightwave_vpl_blocks(const std::vector<lightwave_flux_vpl<float>>& vpls, int per_pass, std::size_t stride_bytes) {
  const auto per = static_cast<std::size_t>(std::max(per_pass, 1));
  if (stride_bytes % sizeof(glm::vec4) != 0 || stride_bytes < per * 3 * sizeof(glm::vec4))
    throw error("lightwave_vpl_blocks: a stride of " + std::to_string(stride_bytes) + " bytes cannot hold " + std::to_string(per) + " VPLs in 16-byte rows");
  const auto blocks = static_cast<std::size_t>(lightwave_vpl_pass_count(vpls.size(), per_pass));
  const std::size_t stride = stride_bytes / sizeof(glm::vec4);
  std::vector<glm::vec4> rows(blocks * stride, glm::vec4(0.0f));
  for (std::size_t i = 0; i < vpls.size(); ++i) {
    glm::vec4* row = &rows[i / per * stride + 3 * (i % per)];
    row[0] = glm::vec4(vpls[i].position, vpls[i].radius);
    row[1] = glm::vec4(vpls[i].normal, 0.0f);
    row[2] = glm::vec4(vpls[i].flux, 0.0f);
  }
  return rows;
}

std::vector<glm::vec3> lightwave_receiver_samples(const mesh& receivers) {
  std::vector<glm::dvec3> sums(receivers.vertices.size(), glm::dvec3(0.0));
  std::vector<int> counts(receivers.vertices.size(), 0);
  for (std::size_t t = 0; t + 2 < receivers.indices.size(); t += 3) {
    const glm::dvec3 centroid = (glm::dvec3(receivers.vertices[receivers.indices[t]].position) + glm::dvec3(receivers.vertices[receivers.indices[t + 1]].position) +
                                 glm::dvec3(receivers.vertices[receivers.indices[t + 2]].position)) /
                                3.0;
    for (std::size_t k = 0; k < 3; ++k) {
      sums[receivers.indices[t + k]] += centroid;
      ++counts[receivers.indices[t + k]];
    }
  }
  std::vector<glm::vec3> samples(receivers.vertices.size());
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const vertex& v = receivers.vertices[i];
    if (counts[i] == 0) {
      samples[i] = v.position;
      continue;
    }
    const glm::dvec3 offset = sums[i] / static_cast<double>(counts[i]) - glm::dvec3(v.position);
    const double length = glm::length(glm::dvec3(v.normal));
    const glm::dvec3 n = length > 0.0 ? glm::dvec3(v.normal) / length : glm::dvec3(0.0);
    samples[i] = glm::vec3(glm::dvec3(v.position) + offset - n * glm::dot(offset, n));
  }
  return samples;
}

std::vector<lightwave_flux_vpl<float>> lightwave_merge_ray_samples(const std::vector<lightwave_flux_vpl<float>>& vpls, const std::vector<int>& layout_index,
                                                                   int rays, float plane_tolerance, std::vector<int>* merged_index) {
  if (layout_index.size() != vpls.size() || rays < 1) throw error("lightwave_merge_ray_samples: one layout index per VPL and at least one ray");
  if (merged_index) merged_index->assign(vpls.size(), 0);
  struct merged {
    glm::dvec3 weighted_position{0.0}, flux{0.0};
    double weight = 0.0, radius_squared = 0.0;
    glm::vec3 first_position{0.0f}, normal{0.0f};
  };
  std::vector<merged> out;
  std::vector<std::vector<std::size_t>> of_ray(static_cast<std::size_t>(rays));  // indices into `out`
  for (std::size_t i = 0; i < vpls.size(); ++i) {
    const lightwave_flux_vpl<float>& v = vpls[i];
    std::vector<std::size_t>& candidates = of_ray[static_cast<std::size_t>(layout_index[i] % rays)];
    merged* target = nullptr;
    for (std::size_t k : candidates)
      if (glm::dot(out[k].normal, v.normal) > 0.999f && std::abs(glm::dot(v.position - out[k].first_position, out[k].normal)) <= plane_tolerance) {
        target = &out[k];
        if (merged_index) (*merged_index)[i] = static_cast<int>(k);
        break;
      }
    if (!target) {
      if (merged_index) (*merged_index)[i] = static_cast<int>(out.size());
      candidates.push_back(out.size());
      out.push_back({});
      target = &out.back();
      target->first_position = v.position;
      target->normal = v.normal;
    }
    const double weight = static_cast<double>(v.flux.x) + v.flux.y + v.flux.z;
    target->weighted_position += weight * glm::dvec3(v.position);
    target->weight += weight;
    target->flux += glm::dvec3(v.flux);
    target->radius_squared += static_cast<double>(v.radius) * v.radius;
  }
  std::vector<lightwave_flux_vpl<float>> result;
  result.reserve(out.size());
  for (const merged& m : out)
    result.push_back({m.weight > 0.0 ? glm::vec3(m.weighted_position / m.weight) : m.first_position, m.normal, glm::vec3(m.flux),
                      static_cast<float>(std::sqrt(m.radius_squared))});
  return result;
}


namespace {

// The VPL where the ray from `origin` along unit `direction` meets the surface the map holds at
// the ray's texel, reflecting `flux` (a function of the texel's albedo and normal; 0: none);
// `measure` is the sample's solid angle (a perspective map) or its cross-section's area
// (`parallel`: an orthographic map), for the patch's radius.
template <typename Flux>
std::optional<lightwave_flux_vpl<float>> flux_vpl_on_map(const glm::vec3& origin, const glm::vec3& direction, float measure, bool parallel, Flux&& flux_of,
                                                         const lightwave_surface_map& map) {
  const int side = map.positions->width;
  const glm::vec4 clip = map.view_projection * glm::vec4(origin + direction, 1.0f);
  if (!(clip.w > 0.0f)) return std::nullopt;
  const glm::ivec2 texel =
      glm::clamp(glm::ivec2(glm::floor((glm::vec2(clip) / clip.w * 0.5f + 0.5f) * static_cast<float>(side))), glm::ivec2(0), glm::ivec2(side - 1));
  const glm::vec4 surface = map.positions->at(texel);
  if (!(surface.w > 0.5f)) return std::nullopt;  // the ray leaves the scene
  const glm::vec3 normal(map.normals->at(texel)), albedo(map.albedos->at(texel));
  const glm::vec3 flux = flux_of(albedo, normal);
  if (!(flux.x + flux.y + flux.z > 0.0f)) return std::nullopt;  // black, the back of a surface, or outside the cone
  // The texel holds the surface at its centre's ray; the ray's own point lies on that surface's
  // plane (unless the texel straddles an edge: then the texel's point, at its distance).
  const glm::vec3 texel_point(surface);
  // (Along a parallel ray its depth; from a light's position, its distance.)
  const float texel_distance = parallel ? glm::dot(texel_point - origin, direction) : glm::length(texel_point - origin);
  const float facing = glm::dot(direction, normal);
  float distance = glm::dot(texel_point - origin, normal) / facing;
  if (!(distance > 0.5f * texel_distance && distance < 2.0f * texel_distance)) distance = texel_distance;
  const glm::vec3 position = origin + direction * distance;
  // An orthographic map's rays are parallel: the patch's area does not grow with the distance.
  const float radius = parallel ? lightwave_patch_radius(measure, 1.0f, facing) : lightwave_patch_radius(measure, distance, facing);
  return lightwave_flux_vpl<float>{position, normal, flux, radius};
}

}  // namespace

std::vector<lightwave_flux_vpl<float>> lightwave_flux_vpls_from_map(const spot_light<float>& light, const lightwave_cone_settings<float>& cone,
                                                                   const glm::mat4& light_view_projection, const image& positions, const image& normals,
                                                                   const image& albedos, std::vector<int>& layout_index) {
  std::vector<lightwave_flux_vpl<float>> vpls;
  layout_index.clear();
  const lightwave_surface_map map{light_view_projection, &positions, &normals, &albedos};
  const int count = lightwave_vpl_count(cone.angle_deg, cone.per_ray);
  for (int index = 0; index < count; ++index) {
    const glm::vec4 sample = lightwave_cone_sample(index, cone);
    const glm::vec3 direction(sample);
    const auto flux = [&](const glm::vec3& albedo, const glm::vec3& normal) { return lightwave_ray_flux(light, direction, sample.w, albedo, normal); };
    if (const auto vpl = flux_vpl_on_map(light.position, direction, sample.w, false, flux, map)) {
      vpls.push_back(*vpl);
      layout_index.push_back(index);
    }
  }
  return vpls;
}

std::vector<lightwave_flux_vpl<float>> lightwave_point_flux_vpls(const point_light<float>& light, const lightwave_cone_settings<float>& cone,
                                                                 const std::array<lightwave_surface_map, 6>& faces, std::vector<int>& layout_index) {
  std::vector<lightwave_flux_vpl<float>> vpls;
  layout_index.clear();
  const int count = lightwave_sphere_sample_count(cone.angle_deg, cone.per_ray);
  for (int index = 0; index < count; ++index) {
    const glm::vec4 sample = lightwave_sphere_sample(index, cone);
    const glm::vec3 direction(sample);
    const auto flux = [&](const glm::vec3& albedo, const glm::vec3& normal) { return lightwave_ray_flux(light, direction, sample.w, albedo, normal); };
    // The one face whose frustum holds the direction (the direct light's shadow reads the same).
    const lightwave_surface_map& face = faces[static_cast<std::size_t>(cube_face_of(direction))];
    if (const auto vpl = flux_vpl_on_map(light.position, direction, sample.w, false, flux, face)) {
      vpls.push_back(*vpl);
      layout_index.push_back(index);
    }
  }
  return vpls;
}

std::vector<lightwave_flux_vpl<float>> lightwave_sun_flux_vpls(const directional_light<float>& light, int angle_deg, int per_ray,
                                                               const glm::vec3& view_origin, const glm::vec3& right, const glm::vec3& up, float half_extent,
                                                               const lightwave_surface_map& map, std::vector<int>& layout_index) {
  std::vector<lightwave_flux_vpl<float>> vpls;
  layout_index.clear();
  const int count = lightwave_parallel_sample_count(angle_deg, per_ray);
  const glm::vec3 direction = light.direction;
  for (int index = 0; index < count; ++index) {
    const glm::vec3 sample = lightwave_parallel_sample<float>(index, angle_deg, per_ray);
    const float area = sample.z * half_extent * half_extent;
    const glm::vec3 origin = view_origin + (sample.x * right + sample.y * up) * half_extent;
    const auto flux = [&](const glm::vec3& albedo, const glm::vec3& normal) { return lightwave_ray_flux(light, direction, area, albedo, normal); };
    if (const auto vpl = flux_vpl_on_map(origin, direction, area, true, flux, map)) {
      vpls.push_back(*vpl);
      layout_index.push_back(index);
    }
  }
  return vpls;
}

std::vector<int> lightwave_sample_rays(light_kind kind, int angle_deg, int per_ray, const std::vector<int>& layout_index, int& rays) {
  std::vector<int> result(layout_index.size());
  if (kind == light_kind::directional) {
    rays = lightwave_parallel_side(angle_deg) * lightwave_parallel_side(angle_deg);
    for (std::size_t i = 0; i < result.size(); ++i) result[i] = layout_index[i] % rays;
    return result;
  }
  const int hemisphere_rays = lightwave_ray_count(angle_deg), half = lightwave_vpl_count(angle_deg, per_ray);
  rays = kind == light_kind::point ? 2 * hemisphere_rays : hemisphere_rays;
  for (std::size_t i = 0; i < result.size(); ++i)
    result[i] = layout_index[i] % hemisphere_rays + (kind == light_kind::point && layout_index[i] >= half ? hemisphere_rays : 0);
  return result;
}

std::vector<lightwave_shadow_caster> lightwave_importance_casters(const lightwave_vpl_view& view, const std::vector<lightwave_receiver_point>& points,
                                                                  const std::vector<lightwave_flux_vpl<float>>* merged, const std::vector<int>& merged_of,
                                                                  int maps, float normal_scale) {
  const bool by_merged = merged && merged_of.size() == view.size();
  const std::size_t sums = by_merged ? merged->size() : view.size();
  std::vector<double> importance_of(sums, 0.0);
  parallel_for(static_cast<int>(sums), hardware_threads(), [&](int k) {
    const auto i = static_cast<std::size_t>(k);
    double importance_sum = 0.0;
    for (const lightwave_receiver_point& point : points) {
      if (!by_merged) {
        importance_sum += view.weight(i, point);
        continue;
      }
      const lightwave_flux_vpl<float>& vpl = (*merged)[i];
      // Nothing for a point it does not face (its weight is exactly 0 there).
      if (lightwave_flux_vpl_faces(point.position, point.normal, vpl.position, vpl.normal))
        importance_sum += lightwave_bounce_weight(point.position, point.normal, vpl, view.min_distance);
    }
    importance_of[i] = importance_sum;
  });
  std::vector<lightwave_cluster_vpl> candidates(view.size());
  for (std::size_t i = 0; i < view.size(); ++i) {
    double light_on_points = importance_of[by_merged ? static_cast<std::size_t>(merged_of[i]) : i];
    if (by_merged) {
      const glm::vec3& whole = (*merged)[static_cast<std::size_t>(merged_of[i])].flux;
      light_on_points *= static_cast<double>(view.power(i)) * 3.0 / std::max(static_cast<double>(whole.x) + whole.y + whole.z, 1e-30);
    }
    candidates[i] = {view.position(i), view.normal(i), static_cast<float>(light_on_points), view.power(i), view.radius(i)};
  }
  return lightwave_cluster_casters(candidates, maps, normal_scale);
}

std::vector<lightwave_shadow_caster> lightwave_layout_casters(const std::vector<int>& layout_indices, const std::vector<int>* flux_layout_index) {
  std::vector<lightwave_shadow_caster> casters;
  for (int index : layout_indices) {
    // The flux energy keeps only the VPLs that carry light: the layout's index, if it does.
    std::size_t i = static_cast<std::size_t>(index);
    if (flux_layout_index) {
      const auto found = std::lower_bound(flux_layout_index->begin(), flux_layout_index->end(), index);
      if (found == flux_layout_index->end() || *found != index) continue;
      i = static_cast<std::size_t>(found - flux_layout_index->begin());
    }
    lightwave_shadow_caster caster;
    caster.vpl = static_cast<int>(i);
    casters.push_back(caster);
  }
  return casters;
}

}  // namespace vplkit
