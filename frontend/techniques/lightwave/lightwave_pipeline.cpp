#include "frontend/techniques/lightwave/lightwave_pipeline.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <limits>
#include <numeric>
#include <sstream>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/hash.hpp>
#include <vplkit/lightwave.hpp>
#include <vplkit/gl/settings_uniforms.hpp>

#include "frontend/gl/debug_output.hpp"
#include "frontend/core/error.hpp"
#include "frontend/core/named_table.hpp"
#include "frontend/core/parallel.hpp"
#include "frontend/scene/camera.hpp"

namespace vplkit {

const std::vector<lightwave_technique>& lightwave_techniques() {
  static const std::vector<lightwave_technique> techniques = {
      {"lightwave-direct", lightwave_mode::direct, "direct light only, shadow-mapped"},
      {"lightwave-faked", lightwave_mode::faked, "faked indirect light (Eq. 5.2, --faked-multiplier)"},
      {"lightwave-unshadowed", lightwave_mode::unshadowed, "VPL indirect light without indirect shadows"},
      {"lightwave-accurate", lightwave_mode::accurate, "VPL indirect light, accurate indirect shadows (--shadow-maps)"},
      {"lightwave-integrated", lightwave_mode::integrated, "VPL indirect light, integrated indirect shadows (--integrated-steps)"},
  };
  return techniques;
}

const lightwave_technique& find_lightwave_technique(const std::string& name) { return find_by_name(lightwave_techniques(), name, "Light Wave technique"); }

std::uint64_t lightwave_shadow_map_bytes(int width, int height, int maps) {
  return static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height) * static_cast<std::uint64_t>(maps) * 4u;
}

namespace {

glm::ivec2 shadow_map_size(const lightwave_settings& settings) {
  return glm::ivec2(static_cast<int>(std::lround(settings.shadow_map_scale * static_cast<float>(settings.width))),
                    static_cast<int>(std::lround(settings.shadow_map_scale * static_cast<float>(settings.height))));
}

int indirect_maps(lightwave_mode mode, const lightwave_settings& settings) {
  if (mode == lightwave_mode::accurate) return settings.accurate_maps;
  if (mode == lightwave_mode::integrated) return settings.integrated_maps;
  return 0;
}

}  // namespace

const std::vector<setting<lightwave_settings, lightwave_technique>>& lightwave_settings_table() {
  using entry = setting<lightwave_settings, lightwave_technique>;
  const auto modes = [](std::vector<lightwave_mode> any) {
    return [any](const lightwave_technique& t) { return std::find(any.begin(), any.end(), t.mode) != any.end(); };
  };
  const auto vpl_light = modes({lightwave_mode::unshadowed, lightwave_mode::accurate, lightwave_mode::integrated});
  const auto shadow_maps = modes({lightwave_mode::accurate, lightwave_mode::integrated});
  std::vector<int> ray_angles;
  for (int angle = 1; angle <= 90; ++angle)
    if (lightwave_ray_angle_divides(angle)) ray_angles.push_back(angle);
  static const std::vector<entry> table = {
      entry::custom("size", setting_type::size, "pixels", "final image size, N or WxH (the thesis: 1280x720)",
                    [](const lightwave_settings& s) { return s.width == s.height ? std::to_string(s.width) : std::to_string(s.width) + "x" + std::to_string(s.height); },
                    [](lightwave_settings& s, const std::string& text) { std::tie(s.width, s.height) = *parse_extent(text); })
          .within(closed_range(1, max_image_side))
          .not_live(),
      entry::choice("format", [](auto& s) -> auto& { return s.format; }, {{"rgba16f", texel_format::rgba16f}, {"rgba32f", texel_format::rgba32f}},
                    "float format of the render targets"),
      entry::number("min-distance", [](auto& s) -> auto& { return s.irradiance.min_distance; }, describe_field(&irradiance_settings<float>::min_distance))
          .feeds("lightwave.frag: irradiance.min_distance; lightwave_capture.frag: irradiance.min_distance"),
      entry::number("seed", [](auto& s) -> auto& { return s.seed; }, closed_range(0, 4294967295.0), "",
                    "seed of the VPL draw of the accurate shadows' thesis variant (the importance variant has none)")
          .read_by(modes({lightwave_mode::accurate}), "the accurate shadows"),
      entry::choice("vpl-energy", [](auto& s) -> auto& { return s.energy; }, {{"flux", lightwave_energy::flux}, {"thesis", lightwave_energy::thesis}},
                    "flux (each VPL reflects the flux its patch of the spot's cone brings, with a diffuse bounce's falloff) or thesis "
                    "(Eq. 4.5's VPLs on hemispheres, without flux: the Tables 5.x)")
          .read_by(vpl_light, "the VPL light")
          .feeds("lightwave.frag: VPLKIT_LIGHTWAVE_ENERGY; lightwave.vert: VPLKIT_LIGHTWAVE_ENERGY"),
      entry::number("ray-angle", [](auto& s) -> auto& { return s.angle_deg; }, describe_field(&lightwave_layout_settings<float>::angle_deg))
          .allowing(ray_angles)
          .read_by(vpl_light, "the VPL light")
          .feeds("lightwave.vert: vpl_texture; lightwave.vert: vpl_count; lightwave_capture.frag: pass_vpl_count"),
      entry::number("vpls-per-ray", [](auto& s) -> auto& { return s.per_ray; }, describe_field(&lightwave_layout_settings<float>::per_ray))
          .read_by(vpl_light, "the VPL light")
          .feeds("lightwave.vert: vpl_texture; lightwave.vert: vpl_count; lightwave_capture.frag: pass_vpl_count"),
      entry::number("vpl-max-distance", [](auto& s) -> auto& { return s.max_distance; }, closed_range(0, max_scene_coordinate), "scene units",
                    "thesis energy: the distance the hemispheres approach (0: from the scene's size)")
          .read_by(vpl_light, "the VPL light")
          .feeds("lightwave.vert: vpl_texture"),
      entry::number("shadow-maps", [](auto& s) -> auto& { return s.accurate_maps; }, closed_range(0, lightwave_max_shadow_maps), "",
                    "VPL shadow maps of the accurate shadows (0: none)")
          .read_by(modes({lightwave_mode::accurate}), "the accurate shadows")
          .feeds("lightwave.frag: indirect_maps; lightwave.frag: shadow_matrix"),
      entry::choice("shadow-variant", [](auto& s) -> auto& { return s.shadow_variant; },
                    {{"importance", lightwave_shadow_variant::importance}, {"thesis", lightwave_shadow_variant::thesis}},
                    "importance (the VPLs split into groups of equal light on the visible scene, one map per group from its medoid aimed at "
                    "what it lights, each map shadowing its group's share; no seed) or thesis (uniform VPLs, maps along their normals, the plain mean)")
          .read_by(modes({lightwave_mode::accurate}), "the accurate shadows")
          .feeds("lightwave.frag: VPLKIT_LIGHTWAVE_SHADOW_VARIANT"),
      entry::number("integrated-maps", [](auto& s) -> auto& { return s.integrated_maps; }, closed_range(2, lightwave_max_shadow_maps), "",
                    "shadow maps of the integrated shadows: the axis VPL and a ring of the innermost hemisphere")
          .read_by(modes({lightwave_mode::integrated}), "the integrated shadows")
          .feeds("lightwave.frag: indirect_maps; lightwave.frag: shadow_matrix"),
      entry::number("integrated-steps", [](auto& s) -> auto& { return s.integrated_steps; }, closed_range(0, 64), "",
                    "in-between lookups per pair of maps (the thesis: 2, 4, 6, 10)")
          .read_by(modes({lightwave_mode::integrated}), "the integrated shadows")
          .feeds("lightwave.frag: integrated_steps"),
      entry::number("shadow-map-scale", [](auto& s) -> auto& { return s.shadow_map_scale; }, open_closed_range(0, 16), "screens",
                    "shadow map size in screens (the thesis: 3)")
          .feeds("lightwave.frag: shadow_maps"),
      entry::number("vpl-field-of-view", [](auto& s) -> auto& { return s.vpl_field_of_view; }, {1, 179, true, true}, "degrees",
                    "field of view of a VPL's shadow map where it looks along the VPL's normal (thesis variant, integrated shadows)")
          .read_by(shadow_maps, "the indirect shadows")
          .feeds("lightwave.frag: shadow_matrix"),
      entry::number("faked-multiplier", [](auto& s) -> auto& { return s.faked_multiplier; }, closed_range(0.5, 4), "Eq. 5.2",
                    "m of Eq. 5.2 (the thesis uses 1.1 to 1.5)")
          .read_by(modes({lightwave_mode::faked}), "the faked indirect light")
          .feeds("lightwave.frag: faked_multiplier"),
      entry::number("specular-strength", [](auto& s) -> auto& { return s.shading.specular_strength; },
                    describe_field(&lightwave_shading_settings<float>::specular_strength))
          .read_by(vpl_light, "the VPL light")
          .feeds("lightwave.vert: shading.specular_strength"),
      entry::number("specular-exponent", [](auto& s) -> auto& { return s.shading.specular_exponent; },
                    describe_field(&lightwave_shading_settings<float>::specular_exponent))
          .read_by(vpl_light, "the VPL light")
          .feeds("lightwave.vert: shading.specular_exponent"),
  };
  return table;
}

std::string validate(const lightwave_settings& settings) {
  try {
    find_lightwave_technique(settings.technique);
  } catch (const error& failure) {
    return failure.what();
  }
  if (const std::string problem = check_settings(lightwave_settings_table(), settings); !problem.empty()) return problem;
  for (const setting_problem& problem : {validate_lightwave_layout(settings.angle_deg, settings.per_ray), validate(settings.shading), validate(settings.irradiance)})
    if (problem) return problem.message();
  // A size derived from settings names them (the texture would fail with a size alone).
  const long shadow_side = std::lround(static_cast<double>(settings.shadow_map_scale) * std::max(settings.width, settings.height));
  if (shadow_side > max_image_side) {
    std::ostringstream scale;
    scale << settings.shadow_map_scale;
    return "shadow-map-scale " + scale.str() + " with a " + std::to_string(settings.width) + "x" +
           std::to_string(settings.height) + " image (size) makes shadow maps of " + std::to_string(shadow_side) + " texels per side, more than " +
           std::to_string(max_image_side);
  }
  const int vpls = lightwave_vpl_count(settings.angle_deg, settings.per_ray);
  // The thesis energy's vertex stage loops over every VPL (the flux energy's passes over at most
  // vpls_per_pass), and llvmpipe ends a loop after 65535 iterations.
  if (vpls > 65535) return "at most 65535 VPLs (the per-vertex loop; llvmpipe stops loops there), got " + std::to_string(vpls);
  // The flux energy puts its VPLs where its rays meet the scene: no hemispheres to place.
  if (settings.energy == lightwave_energy::flux && settings.max_distance != 0.0f)
    return "vpl-max-distance places the thesis's hemispheres and is read with vpl-energy thesis; the flux energy puts its VPLs where its rays "
           "meet the scene (leave vpl-max-distance at 0)";
  if (!(settings.receiver_spacing > 0.0f && settings.receiver_spacing <= 4.0f)) return "receiver spacing must be in (0, 4] (a fraction of the scene's bounding radius)";
  if (settings.receiver_triangles < 1 || settings.receiver_triangles > (1 << 22)) return "receiver triangles must be in [1, 4194304]";
  if (settings.vpls_per_pass < 0 || settings.vpls_per_pass > 65535) return "VPLs per pass must be 0 (a uniform block's worth) or in [1, 65535]";
  if (settings.accurate_maps > vpls)
    return "more accurate shadow maps (" + std::to_string(settings.accurate_maps) + ") than VPLs (" + std::to_string(vpls) + ")";
  const int ring = 360 / settings.angle_deg;
  if (settings.integrated_maps > 1 + ring)
    return "integrated-maps must be at most " + std::to_string(1 + ring) + " (the axis VPL and a ring of the innermost hemisphere at " +
           std::to_string(settings.angle_deg) + " degrees), got " + std::to_string(settings.integrated_maps);
  return {};
}

std::vector<int> lightwave_shadow_vpls(lightwave_mode mode, const lightwave_settings& settings) {
  const int count = lightwave_vpl_count(settings.angle_deg, settings.per_ray);
  std::vector<int> chosen;
  if (mode == lightwave_mode::accurate) {
    // A partial Fisher-Yates shuffle driven by the shared hash: reproducible for a seed.
    std::vector<int> indices(static_cast<std::size_t>(count));
    for (int i = 0; i < count; ++i) indices[static_cast<std::size_t>(i)] = i;
    for (int i = 0; i < settings.accurate_maps; ++i) {
      const auto span = static_cast<std::uint32_t>(count - i);
      const int j = i + static_cast<int>(hash_combine(settings.seed, static_cast<std::uint32_t>(i)) % span);
      std::swap(indices[static_cast<std::size_t>(i)], indices[static_cast<std::size_t>(j)]);
      chosen.push_back(indices[static_cast<std::size_t>(i)]);
    }
  } else if (mode == lightwave_mode::integrated) {
    const int azimuths = 360 / settings.angle_deg;
    const int polar_step = std::max(1, static_cast<int>(std::lround(45.0 / settings.angle_deg)));
    chosen.push_back(0);  // the axis
    const int ring = settings.integrated_maps - 1;
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

namespace {

glm::mat4 look_along(const glm::vec3& position, const glm::vec3& direction) {
  const glm::vec3 up = std::abs(direction.y) > 0.99f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
  return glm::lookAt(position, position + direction, up);
}

// Points spread over the scene's surface in proportion to area (systematic over the triangles'
// cumulative areas, barycentric coordinates from the hash), with a camera kept when it can see
// them (inside its frustum, facing it): what the shadow casters are chosen and aimed for. Vertices
// alone would weigh a 36-triangle box scene by its corners; for the thesis energy, without the
// camera test the underside of the floor would draw VPLs below it.
std::vector<lightwave_receiver_point> surface_points(const mesh& geometry, const camera* view, float aspect, int count) {
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

}  // namespace

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
    return glm::perspective(glm::radians(fallback_fov_degrees), aspect, near_plane, far_plane) * look_along(eye, fallback_direction);
  const glm::vec3 axis = glm::normalize(mean);
  const glm::mat4 view = look_along(eye, axis);
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

mesh lightwave_receivers(const mesh& geometry, const lightwave_settings& settings) {
  // The edge bound grows by half until the subdivision fits the budget (a scene already that
  // fine, or finer, stays as it is).
  float max_edge = settings.receiver_spacing * std::max(bounds(geometry).radius(), 1e-3f);
  for (int attempt = 0; attempt < 64; ++attempt, max_edge *= 1.5f)
    if (std::optional<mesh> subdivided = subdivide_long_edges(geometry, max_edge, static_cast<std::size_t>(settings.receiver_triangles)))
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

namespace {

const lightwave_settings& checked(const lightwave_settings& settings) {
  if (const std::string problem = validate(settings); !problem.empty()) throw error("Light Wave settings: " + problem);
  return settings;
}

}  // namespace

lightwave_pipeline::lightwave_pipeline(const shader_library& shaders, const scene& source, const lightwave_settings& settings)
    : scene_(source),
      settings_(checked(settings)),
      technique_(find_lightwave_technique(settings.technique)),
      mesh_(source.geometry),
      depth_program_(load_program(shaders, "scene.vert", "depth_only.frag",
                                  has_alpha_cutouts(source.geometry) ? shader_defines{} : shader_defines{{"VPLKIT_MATERIAL_NO_ALPHA_TEST", "1"}})),
      shadow_framebuffer_(generate_framebuffer()),
      target_(settings.width, settings.height, {settings.format, settings.format, settings.format}, true) {
  if (source.light.kind != light_kind::spot) throw error("Light Wave needs a spot light; scene " + source.name + " has a directional one");
  if (const setting_problem problem = validate(source.light.spot)) throw error("scene " + source.name + ": " + problem.message());
  const std::string energy = std::to_string(static_cast<int>(settings_.energy));
  // The flux energy's indirect light: from a screen buffer the receivers fill (indirect_target_),
  // so that the main pass runs on the scene's own triangles, with their materials (the receivers
  // have none) and, with indirect shadows, its heavy fragment stage on few large triangles.
  const bool indirect_buffer = settings_.energy == lightwave_energy::flux && technique_.mode >= lightwave_mode::unshadowed;
  const shader_defines defines = {{"VPLKIT_LIGHTWAVE_MODE", std::to_string(static_cast<int>(technique_.mode))},
                                  {"VPLKIT_LIGHTWAVE_INDIRECT_BUFFER", indirect_buffer ? "1" : "0"},
                                  {"VPLKIT_LIGHTWAVE_SHADOW_VARIANT", std::to_string(static_cast<int>(settings_.shadow_variant))},
                                  {"VPLKIT_LIGHTWAVE_ENERGY", energy},
                                  {"VPLKIT_LIGHTWAVE_INDIRECT", technique_.mode >= lightwave_mode::unshadowed ? "1" : "0"},
                                  {"VPLKIT_MAX_SHADOW_MAPS", std::to_string(lightwave_max_shadow_maps)}};
  shader_defines main_defines = defines;
  if (depth_prepass()) main_defines.emplace_back("VPLKIT_MATERIAL_NO_ALPHA_TEST", "1");
  main_program_ = load_program(shaders, "lightwave.vert", "lightwave.frag", main_defines);
  if (settings_.energy == lightwave_energy::thesis)
    capture_program_ = link_program(
        "lightwave.vert (transform feedback)",
        {{shader_stage::vertex, shaders.expand_file("lightwave.vert", {{"VPLKIT_LIGHTWAVE_INDIRECT", "1"}, {"VPLKIT_LIGHTWAVE_ENERGY", "0"}, {"VPLKIT_LIGHTWAVE_CAPTURE", "1"}})}},
        {"vertex_indirect"});
  // Direct light alone and the faked indirect light use no VPLs.
  if (settings_.energy == lightwave_energy::flux && technique_.mode >= lightwave_mode::unshadowed) {
    surface_program_ = load_program(shaders, "scene.vert", "lightwave_surfaces.frag");
    surfaces_.emplace(lightwave_surface_map_size, lightwave_surface_map_size,
                      std::vector<texel_format>{texel_format::rgba32f, texel_format::rgba32f, texel_format::rgba32f}, true);
    receivers_ = lightwave_receivers(source.geometry, settings_);
    receiver_samples_ = lightwave_receiver_samples(receivers_);
    receiver_buffers_.emplace(receivers_);
    // The sum at the receivers, lightwave_sum_receivers per texel of a grid (lightwave_capture.frag):
    // receiver r is cell t = r % cells of band k = r / cells, read at texel (t % width, k x rows +
    // t / width) of three textures (its sample point, normal and albedo), its sum written to
    // attachment k of the sums' target at texel (t % width, t / width).
    constexpr auto bands = static_cast<std::size_t>(lightwave_sum_receivers);
    const std::size_t count = receivers_.vertices.size();
    GLint max_side = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_side);
    const glm::ivec2 grid = lightwave_sum_grid(count, max_side);
    check_texture_size(grid.x, grid.y * lightwave_sum_receivers, "the Light Wave receivers' grid (" + std::to_string(count) + " receivers)");
    const std::size_t cells = static_cast<std::size_t>(grid.x) * static_cast<std::size_t>(grid.y);
    // Empty texels get a unit normal, so that their lanes compute no NaN (their sums are written as zero anyway).
    std::vector<glm::vec4> points(bands * cells, glm::vec4(0.0f)), normals(bands * cells, glm::vec4(0.0f, 0.0f, 1.0f, 0.0f)),
        albedos(bands * cells, glm::vec4(0.0f));
    for (std::size_t i = 0; i < count; ++i) {
      points[i] = glm::vec4(receiver_samples_[i], 0.0f);
      normals[i] = glm::vec4(receivers_.vertices[i].normal, 0.0f);
      albedos[i] = glm::vec4(receivers_.vertices[i].albedo, 0.0f);
    }
    for (const std::vector<glm::vec4>* texels : {&points, &normals, &albedos})
      receiver_textures_.emplace_back(grid.x, grid.y * lightwave_sum_receivers, texel_format::rgba32f, texels->data());
    // The sums land in the main pass's attribute buffer band after band, each the grid's texels in
    // RGBA floats (the copy a plain memcpy on any GL), read as a vec3 attribute.
    indirect_buffer_ = gl_buffer(generate_buffer());
    glBindBuffer(GL_ARRAY_BUFFER, indirect_buffer_.get());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(bands * cells * sizeof(glm::vec4)), nullptr, GL_DYNAMIC_COPY);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    receiver_buffers_->attach_vec4_attribute(3, indirect_buffer_.get());
    for (int k = 0; k < 2; ++k) receiver_sum_targets_.emplace_back(grid.x, grid.y, std::vector<texel_format>(bands, texel_format::rgba32f), false);
    // The VPLs of a pass in one uniform block: three vec4 each (std140), the blocks of successive
    // passes at offsets the GL accepts.
    GLint block_bytes = 0, offset_alignment = 0;
    glGetIntegerv(GL_MAX_UNIFORM_BLOCK_SIZE, &block_bytes);
    glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &offset_alignment);
    constexpr int bytes_per_vpl = 3 * static_cast<int>(sizeof(glm::vec4));
    const int block_vpls = block_bytes / bytes_per_vpl;
    // By default a 64 KiB block's worth (GL 3.3 guarantees 16 KiB; some drivers report blocks far
    // larger than a shader should declare).
    vpls_per_pass_ = settings_.vpls_per_pass == 0 ? std::min(block_vpls, 65536 / bytes_per_vpl) : settings_.vpls_per_pass;
    if (vpls_per_pass_ < 1 || vpls_per_pass_ > block_vpls)
      throw error("Light Wave: " + std::to_string(vpls_per_pass_) + " VPLs per pass need a uniform block of " + std::to_string(vpls_per_pass_ * bytes_per_vpl) +
                  " bytes; this GL allows " + std::to_string(block_bytes) + " (at most " + std::to_string(block_vpls) + " VPLs per pass)");
    const std::size_t alignment = std::lcm(static_cast<std::size_t>(std::max(offset_alignment, 1)), sizeof(glm::vec4));
    const std::size_t block_size = static_cast<std::size_t>(vpls_per_pass_) * bytes_per_vpl;
    vpl_block_stride_ = (block_size + alignment - 1) / alignment * alignment;
    vpl_block_buffer_ = gl_buffer(generate_buffer());
    receiver_sum_program_ = load_program(shaders, "fullscreen.vert", "lightwave_capture.frag",
                                         {{"VPLKIT_LIGHTWAVE_PASS_VPLS", std::to_string(vpls_per_pass_)},
                                          {"VPLKIT_LIGHTWAVE_SUM_RECEIVERS", std::to_string(lightwave_sum_receivers)}});
    glUniformBlockBinding(receiver_sum_program_.id(), glGetUniformBlockIndex(receiver_sum_program_.id(), "lightwave_pass_vpls"), 0);
    empty_vertex_array_ = gl_vertex_array(generate_vertex_array());
    if (indirect_buffer) {
      // Without cut-outs its fragments need no material (no discard: the depth is tested first).
      shader_defines indirect_defines = defines;
      if (!has_alpha_cutouts(source.geometry)) indirect_defines.emplace_back("VPLKIT_MATERIAL_NO_ALPHA_TEST", "1");
      indirect_program_ = load_program(shaders, "lightwave.vert", "lightwave_indirect.frag", indirect_defines);
      // In the output's format (half floats by default, a relative step of 2^-11, as the image's):
      // half the bytes to clear and write cost a software rasteriser about 2 ms less of the boxes'
      // 1280x720 frame.
      indirect_target_.emplace(settings_.width, settings_.height, std::vector<texel_format>{settings_.format}, true);
    }
  }

  // The shadow maps: layer 0 for the light, then one per chosen VPL.
  shadow_size_ = shadow_map_size(settings_);
  shadow_layers_ = 1 + indirect_maps(technique_.mode, settings_);
  check_texture_size(shadow_size_.x, shadow_size_.y, "Light Wave shadow maps (" + std::to_string(settings_.shadow_map_scale) + " x the screen)");
  GLint max_layers = 0;
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &max_layers);
  if (shadow_layers_ > max_layers)
    throw error("Light Wave: " + std::to_string(shadow_layers_) + " shadow maps exceed GL_MAX_ARRAY_TEXTURE_LAYERS (" + std::to_string(max_layers) + ")");
  shadow_maps_ = gl_texture(generate_texture());
  glBindTexture(GL_TEXTURE_2D_ARRAY, shadow_maps_.get());
  glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_DEPTH_COMPONENT32F, shadow_size_.x, shadow_size_.y, shadow_layers_, 0, GL_DEPTH_COMPONENT, GL_FLOAT, nullptr);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  check_gl("allocating " + std::to_string(shadow_layers_) + " Light Wave shadow maps of " + std::to_string(shadow_size_.x) + "x" +
           std::to_string(shadow_size_.y) + " (" + std::to_string(shadow_map_bytes() / (1024 * 1024)) + " MiB)");
}

std::uint64_t lightwave_pipeline::shadow_map_bytes() const { return lightwave_shadow_map_bytes(shadow_size_.x, shadow_size_.y, shadow_layers_); }

void lightwave_pipeline::set_light(const scene_light& light) {
  if (light.kind != light_kind::spot) throw error("Light Wave needs a spot light; make a new pipeline for a scene with a directional one");
  check_light(light, "Light Wave scene " + scene_.name);
  scene_.light.spot = light.spot;
  vpls_dirty_ = shadows_dirty_ = true;
  view_valid_ = false;
}

const texture_2d* lightwave_pipeline::indirect_shadow_output() const {
  const bool shadowed = technique_.mode == lightwave_mode::accurate || technique_.mode == lightwave_mode::integrated;
  return shadowed ? &target_.colour(1) : nullptr;
}

std::string lightwave_pipeline::draw_counts() const {
  return "VPLs and shadow maps " + std::to_string(rebuilds_) + ", main pass " + std::to_string(main_draws_);
}

std::string lightwave_pipeline::describe() const {
  std::ostringstream out;
  out << "scene " << scene_.name << " (" << scene_.geometry.triangle_count() << " triangles), technique " << settings_.technique << ", " << settings_.width
      << "x" << settings_.height << ", " << vpl_count() << " VPLs (" << settings_.angle_deg << " degrees, " << settings_.per_ray << " per ray"
      << (settings_.energy == lightwave_energy::flux && technique_.mode >= lightwave_mode::unshadowed
              ? ", flux energy: " + std::to_string(lit_vpl_count()) + " carry light"
              : std::string())
      << "), shadow maps: "
      << std::fixed << std::setprecision(2) << static_cast<double>(shadow_map_bytes()) / (1024.0 * 1024.0) << " MB (Eq. 5.4/5.5)";
  return out.str();
}

int lightwave_pipeline::lit_vpl_count() const {
  return static_cast<int>(settings_.energy == lightwave_energy::flux ? flux_vpls_.size() : vpls_.size());
}

int lightwave_pipeline::summed_vpl_count() const {
  return static_cast<int>(settings_.energy == lightwave_energy::flux ? receiver_vpls_.size() : vpls_.size());
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

void lightwave_pipeline::build_flux_vpls(const glm::mat4& light_view_projection) {
  const spot_light<float>& light = scene_.light.spot;
  // What the light sees: world position (w = 1 where a surface is), normal and albedo per texel.
  surfaces_->bind();
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  surface_program_.use();
  surface_program_.set("view_projection", light_view_projection);
  mesh_.draw(surface_program_);
  // Into the same host memory at every light move.
  surfaces_->colour(0).read_image_into(surface_texels_[0]);
  surfaces_->colour(1).read_image_into(surface_texels_[1]);
  surfaces_->colour(2).read_image_into(surface_texels_[2]);
  const image &positions = surface_texels_[0], &normals = surface_texels_[1], &albedos = surface_texels_[2];
  // The rays cover the cone up to its outer edge, inside the map's frustum (2 degrees of margin).
  cone_.light_direction = light.direction;
  cone_.angle_deg = settings_.angle_deg;
  cone_.per_ray = settings_.per_ray;
  cone_.half_angle_deg = glm::degrees(spot_light_frustum_half_angle(light)) - 2.0f;
  flux_vpls_.clear();
  flux_layout_index_.clear();
  const int count = lightwave_vpl_count(settings_.angle_deg, settings_.per_ray);
  const int side = lightwave_surface_map_size;
  for (int index = 0; index < count; ++index) {
    const glm::vec4 sample = lightwave_cone_sample(index, cone_);
    const glm::vec3 direction(sample);
    const glm::vec4 clip = light_view_projection * glm::vec4(light.position + direction, 1.0f);
    if (!(clip.w > 0.0f)) continue;
    const glm::ivec2 texel = glm::clamp(glm::ivec2(glm::floor((glm::vec2(clip) / clip.w * 0.5f + 0.5f) * static_cast<float>(side))), glm::ivec2(0),
                                        glm::ivec2(side - 1));
    const glm::vec4 surface = positions.at(texel);
    if (!(surface.w > 0.5f)) continue;  // the ray leaves the scene
    const glm::vec3 normal(normals.at(texel)), albedo(albedos.at(texel));
    const glm::vec3 flux = lightwave_ray_flux(light, direction, sample.w, albedo, normal);
    if (!(flux.x + flux.y + flux.z > 0.0f)) continue;  // black, the back of a surface, or outside the cone
    // The texel holds the surface at its centre's ray; the ray's own point lies on that surface's
    // plane (unless the texel straddles an edge: then the texel's point).
    const glm::vec3 texel_point(surface);
    const float texel_distance = glm::length(texel_point - light.position);
    const float facing = glm::dot(direction, normal);
    float distance = glm::dot(texel_point - light.position, normal) / facing;
    if (!(distance > 0.5f * texel_distance && distance < 2.0f * texel_distance)) distance = texel_distance;
    flux_vpls_.push_back({light.position + direction * distance, normal, flux, lightwave_patch_radius(sample.w, distance, facing)});
    flux_layout_index_.push_back(index);
  }
}

namespace {

// What the shadow casters need of every VPL of either energy: where it is, its normal, and its
// weight (the light it gives) at a point.
struct vpl_view {
  const std::vector<lightwave_vpl<float>>* thesis = nullptr;
  const std::vector<lightwave_flux_vpl<float>>* flux = nullptr;
  float min_distance = 0.01f;
  std::size_t size() const { return thesis ? thesis->size() : flux->size(); }
  glm::vec3 position(std::size_t i) const { return thesis ? (*thesis)[i].position : (*flux)[i].position; }
  glm::vec3 normal(std::size_t i) const { return thesis ? (*thesis)[i].normal : (*flux)[i].normal; }
  float weight(std::size_t i, const lightwave_receiver_point& point) const {
    return thesis ? lightwave_vpl_weight(point.position, point.normal, (*thesis)[i])
                  : lightwave_bounce_weight(point.position, point.normal, (*flux)[i], min_distance);
  }
  float power(std::size_t i) const {
    if (thesis) return std::max(0.0f, 1.0f - (*thesis)[i].attenuation);
    const glm::vec3& f = (*flux)[i].flux;
    return (f.x + f.y + f.z) / 3.0f;
  }
  float radius(std::size_t i) const { return thesis ? 0.0f : (*flux)[i].radius; }
};

vpl_view view_of(const lightwave_settings& settings, const std::vector<lightwave_vpl<float>>& thesis,
                 const std::vector<lightwave_flux_vpl<float>>& flux) {
  vpl_view view;
  if (settings.energy == lightwave_energy::thesis) view.thesis = &thesis;
  else view.flux = &flux;
  view.min_distance = settings.irradiance.min_distance;
  return view;
}

}  // namespace

lightwave_pipeline::frame_geometry lightwave_pipeline::geometry() const {
  const spot_light<float>& light = scene_.light.spot;
  const bounding_box box = bounds(scene_.geometry);
  frame_geometry g;
  g.radius = std::max(box.radius(), 1e-3f);
  g.near_plane = 0.01f * g.radius;
  g.far_plane = glm::length(light.position - box.centre()) + 2.0f * g.radius;
  g.light_view = look_along(light.position, light.direction);
  return g;
}

void lightwave_pipeline::build_vpls() {
  const spot_light<float>& light = scene_.light.spot;
  const bounding_box box = bounds(scene_.geometry);
  const frame_geometry g = geometry();
  float max_distance = settings_.max_distance;
  vpls_.clear();
  flux_vpls_.clear();
  flux_layout_index_.clear();
  receiver_vpls_.clear();
  receiver_vpl_of_.clear();
  if (settings_.energy == lightwave_energy::thesis) {
    if (max_distance == 0.0f)
      for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p((corner & 1) ? box.maximum.x : box.minimum.x, (corner & 2) ? box.maximum.y : box.minimum.y,
                          (corner & 4) ? box.maximum.z : box.minimum.z);
        max_distance = std::max(max_distance, glm::length(p - light.position));
      }
    layout_ = {light.position, light.direction, settings_.angle_deg, settings_.per_ray, max_distance};
    lightwave_layout(layout_, std::back_inserter(vpls_));
  } else {
    layout_ = {light.position, light.direction, settings_.angle_deg, settings_.per_ray, 0.0f};
    build_flux_vpls(glm::perspective(2.0f * spot_light_frustum_half_angle(light), 1.0f, g.near_plane, g.far_plane) * g.light_view);
    // The receivers sum a ray's samples on one plane as one VPL (a thousandth of the scene's
    // radius: one plane); the shadow casters keep every sample.
    receiver_vpls_ = lightwave_merge_ray_samples(flux_vpls_, flux_layout_index_, lightwave_ray_count(settings_.angle_deg), 1e-3f * g.radius, &receiver_vpl_of_);
  }
  layout_.max_distance = max_distance;

  if (settings_.energy == lightwave_energy::thesis) {
    // The VPL texture the vertex stage reads every frame, a row per VPL: [position | attenuation],
    // [normal | 0]. At least one row.
    const std::size_t rows = std::max<std::size_t>(vpls_.size(), 1);
    std::vector<glm::vec4> texels(2 * rows, glm::vec4(0.0f));
    for (std::size_t i = 0; i < vpls_.size(); ++i) {
      texels[2 * i] = glm::vec4(vpls_[i].position, vpls_[i].attenuation);
      texels[2 * i + 1] = glm::vec4(vpls_[i].normal, 0.0f);
    }
    check_texture_size(2, static_cast<int>(rows), "the Light Wave VPL texture");
    vpl_texture_ = gl_texture(generate_texture());
    glBindTexture(GL_TEXTURE_2D, vpl_texture_.get());
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, 2, static_cast<GLsizei>(rows), 0, GL_RGBA, GL_FLOAT, texels.data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  } else if (receiver_buffers_) {
    // The receivers' VPLs, a uniform block per pass: [position | radius], [normal | 0], [flux | 0].
    // The flux energy's indirect light does not depend on the camera: summed once per light, at
    // the receivers' vertices, into the buffer the main pass reads.
    const std::vector<glm::vec4> rows = lightwave_vpl_blocks(receiver_vpls_, vpls_per_pass_, vpl_block_stride_);
    glBindBuffer(GL_UNIFORM_BUFFER, vpl_block_buffer_.get());
    glBufferData(GL_UNIFORM_BUFFER, static_cast<GLsizeiptr>(rows.size() * sizeof(glm::vec4)), rows.data(), GL_DYNAMIC_DRAW);
    glBindBuffer(GL_UNIFORM_BUFFER, 0);
    sum_at_receivers();
  }
  check_gl("building the Light Wave VPLs");
}

void lightwave_pipeline::build_shadow_maps() {
  const spot_light<float>& light = scene_.light.spot;
  const frame_geometry g = geometry();
  const float radius = g.radius, near_plane = g.near_plane, far_plane = g.far_plane;
  const float aspect = static_cast<float>(shadow_size_.x) / static_cast<float>(shadow_size_.y);
  const vpl_view view = view_of(settings_, vpls_, flux_vpls_);
  // Shadow matrices: the spot light's frustum, then each chosen VPL's.
  const float map_far = far_plane + layout_.max_distance;
  shadow_matrices_.clear();
  shadow_matrices_.push_back(glm::perspective(2.0f * spot_light_frustum_half_angle(light), aspect, near_plane, far_plane) * g.light_view);
  // The shadow casters: groups by importance (accurate), drawn uniformly (the thesis variant),
  // the fixed ring (integrated). The integrated shadows keep the thesis's maps (along the VPLs'
  // normals, one field of view): their in-between lookups interpolate a fragment's coordinates
  // between two maps, which stands for an in-between light only when the maps share their
  // projection; aimed maps of different fields of view darkened an empty plane (lowest factor
  // 0.72, measured).
  const bool importance = casters_by_importance();
  casters_.clear();
  // A flux VPL sits on its surface: its map's eye is lifted off it, so that the surface does not
  // shadow what it lights.
  const auto eye_of = [&](std::size_t i) { return view.position(i) + (view.thesis ? 0.0f : 1e-3f * radius) * view.normal(i); };
  if (importance) {
    const std::vector<lightwave_receiver_point> points =
        surface_points(scene_.geometry, casters_follow_camera() ? &scene_.view : nullptr, static_cast<float>(settings_.width) / static_cast<float>(settings_.height),
                       4096);
    // A VPL's importance: its light on the points. Thousands of VPLs times thousands of points, on
    // every core (each sum on its own, in the same order: the result does not depend on the
    // threads). The flux energy sums it for the receivers' VPLs (a ray's samples on one plane
    // merged) and gives each sample its share by flux: the samples of a patch light a distant
    // point alike, and the sum costs per_ray times less.
    const bool merged = view.flux && receiver_vpl_of_.size() == view.size();
    const std::size_t sums = merged ? receiver_vpls_.size() : view.size();
    std::vector<double> importance_of(sums, 0.0);
    parallel_for(static_cast<int>(sums), hardware_threads(), [&](int k) {
      const auto i = static_cast<std::size_t>(k);
      double importance_sum = 0.0;
      for (const lightwave_receiver_point& point : points) {
        if (!merged) {
          importance_sum += view.weight(i, point);
          continue;
        }
        const lightwave_flux_vpl<float>& vpl = receiver_vpls_[i];
        // Nothing for a point it does not face (its weight is exactly 0 there).
        if (lightwave_flux_vpl_faces(point.position, point.normal, vpl.position, vpl.normal))
          importance_sum += lightwave_bounce_weight(point.position, point.normal, vpl, view.min_distance);
      }
      importance_of[i] = importance_sum;
    });
    std::vector<lightwave_cluster_vpl> candidates(view.size());
    for (std::size_t i = 0; i < view.size(); ++i) {
      double light_on_points = importance_of[merged ? static_cast<std::size_t>(receiver_vpl_of_[i]) : i];
      if (merged) {
        const glm::vec3& whole = receiver_vpls_[static_cast<std::size_t>(receiver_vpl_of_[i])].flux;
        light_on_points *= static_cast<double>(view.power(i)) * 3.0 / std::max(static_cast<double>(whole.x) + whole.y + whole.z, 1e-30);
      }
      candidates[i] = {view.position(i), view.normal(i), static_cast<float>(light_on_points), view.power(i), view.radius(i)};
    }
    casters_ = lightwave_cluster_casters(candidates, settings_.accurate_maps, 0.25f * radius);
    std::vector<float> weights(points.size());
    for (const lightwave_shadow_caster& caster : casters_) {
      const auto i = static_cast<std::size_t>(caster.vpl);
      for (std::size_t k = 0; k < points.size(); ++k) weights[k] = view.weight(i, points[k]);
      shadow_matrices_.push_back(
          lightwave_aimed_shadow_matrix(eye_of(i), view.normal(i), points, weights, near_plane, map_far, aspect, settings_.vpl_field_of_view));
    }
  } else {
    for (int index : lightwave_shadow_vpls(technique_.mode, settings_)) {
      // The flux energy keeps only the VPLs that carry light: the layout's index, if it does.
      std::size_t i = static_cast<std::size_t>(index);
      if (view.flux) {
        const auto found = std::lower_bound(flux_layout_index_.begin(), flux_layout_index_.end(), index);
        if (found == flux_layout_index_.end() || *found != index) continue;
        i = static_cast<std::size_t>(found - flux_layout_index_.begin());
      }
      lightwave_shadow_caster caster;
      caster.vpl = static_cast<int>(i);
      casters_.push_back(caster);
      shadow_matrices_.push_back(glm::perspective(glm::radians(settings_.vpl_field_of_view), aspect, near_plane, map_far) *
                                 look_along(eye_of(i), view.normal(i)));
    }
  }

  // Depth passes into the layers.
  glBindFramebuffer(GL_FRAMEBUFFER, shadow_framebuffer_.get());
  glDrawBuffer(GL_NONE);
  glReadBuffer(GL_NONE);
  glViewport(0, 0, shadow_size_.x, shadow_size_.y);
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(2.0f, 4.0f);  // slope-scaled bias against shadow acne
  depth_program_.use();
  for (std::size_t layer = 0; layer < shadow_matrices_.size(); ++layer) {
    glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, shadow_maps_.get(), 0, static_cast<GLint>(layer));
    if (layer == 0 && glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw error("Light Wave shadow map framebuffer is incomplete");
    glClear(GL_DEPTH_BUFFER_BIT);
    depth_program_.set("view_projection", shadow_matrices_[layer]);
    mesh_.draw(depth_program_);
  }
  glDisable(GL_POLYGON_OFFSET_FILL);

  const program& p = main_program_;
  for (std::size_t i = 0; i < shadow_matrices_.size(); ++i) {
    p.set("shadow_matrix[" + std::to_string(i) + "]", shadow_matrices_[i]);
  }
  // Each caster's VPL (whether it lights a fragment decides whether its map votes there) and,
  // with importance, its group as one light (the share of the fragment's light the map stands for).
  for (std::size_t i = 0; i < casters_.size(); ++i) {
    const std::string index = std::to_string(i);
    const auto vpl = static_cast<std::size_t>(casters_[i].vpl);
    p.set("caster_position[" + index + "]", glm::vec4(view.position(vpl), view.thesis ? vpls_[vpl].attenuation : flux_vpls_[vpl].radius));
    p.set("caster_normal[" + index + "]", glm::vec4(view.normal(vpl), 0.0f));
    p.set("group_position_radius[" + index + "]", glm::vec4(casters_[i].position, casters_[i].radius));
    p.set("group_normal_power[" + index + "]", glm::vec4(casters_[i].normal, casters_[i].power));
  }
  check_gl("building the Light Wave shadow maps");
}

void lightwave_pipeline::rebuild() {
  if (vpls_dirty_ && technique_.mode >= lightwave_mode::unshadowed) {
    timer_.begin("VPLs");
    build_vpls();
    timer_.end();
  }
  if (shadows_dirty_) {
    timer_.begin("shadow maps");
    build_shadow_maps();
    timer_.end();
  }
  vpls_dirty_ = shadows_dirty_ = false;
  ++rebuilds_;
}

void lightwave_pipeline::set_camera(const camera& view) {
  check_camera(view, "Light Wave scene " + scene_.name);
  scene_.view = view;
  if (casters_follow_camera()) shadows_dirty_ = true;
  view_valid_ = false;
}

lightwave_frame lightwave_pipeline::render() {
  draw();
  lightwave_frame frame;
  frame.radiance = target_.read_image(0);
  frame.indirect_shadow = target_.read_image(1);
  frame.indirect = target_.read_image(2);
  frame.pass_times = timer_.collect();
  return frame;
}

void lightwave_pipeline::draw() {
  vpls_dirty_ = shadows_dirty_ = true;
  draw_changed();
}

void lightwave_pipeline::draw_changed() {
  if (vpls_dirty_ || shadows_dirty_) {
    rebuild();
    view_valid_ = false;
  }
  if (!view_valid_) draw_main_pass();
}

void lightwave_pipeline::draw_main_pass() {
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  if (indirect_target_) {
    timer_.begin("indirect buffer");
    // Flux energy: the receivers' indirect light into the screen buffer the main pass reads.
    indirect_target_->bind();
    glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    set_vertex_uniforms(indirect_program_);
    indirect_program_.use();
    receiver_buffers_->draw(indirect_program_);
    main_program_.set("indirect_buffer", 2);
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D, indirect_target_->colour(0).id());
    timer_.end();
  }
  timer_.begin("main pass");
  target_.bind();
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  const GLfloat unshadowed[4] = {1.0f, 0.0f, 0.0f, 1.0f};  // the factor where no surface is
  glClearBufferfv(GL_COLOR, 1, unshadowed);
  set_vertex_uniforms(main_program_);
  main_program_.set("shadow_maps", 1);
  set_uniforms(main_program_, "light", scene_.light.spot);
  set_uniforms(main_program_, "irradiance", settings_.irradiance);
  main_program_.set("indirect_maps", static_cast<int>(casters_.size()));
  main_program_.set("integrated_steps", settings_.integrated_steps);
  main_program_.set("faked_multiplier", settings_.faked_multiplier);
  // The normal offset and slope-scaled bias of include/vplkit/shadow.hpp in every map; the
  // constant part stays the raster state's polygon offset.
  shadow_density_settings<float> bias;
  bias.depth_bias = 0.0f;
  set_uniforms(main_program_, "shadow_bias", bias);
  main_program_.set("shadow_map_width", shadow_size_.x);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, vpl_texture_.get());
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D_ARRAY, shadow_maps_.get());
  if (depth_prepass()) {
    // The shadowed pass's fragments are the costly part of the frame: a depth pre-pass first, so
    // that only the visible one of each pixel runs them (its shader has no discard, so its depth
    // is tested before it runs; the pre-pass did the alpha test).
    depth_program_.use();
    depth_program_.set("view_projection", camera_view_projection());
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    mesh_.draw(depth_program_);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthFunc(GL_EQUAL);
    glDepthMask(GL_FALSE);
    main_program_.use();
  }
  mesh_.draw(main_program_);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  timer_.end();
  check_gl("rendering scene " + scene_.name + " with " + technique_.name);
  view_valid_ = true;
  ++main_draws_;
}

glm::mat4 lightwave_pipeline::camera_view_projection() const {
  return camera_projection_matrix(scene_.view, static_cast<float>(settings_.width) / static_cast<float>(settings_.height)) * camera_view_matrix(scene_.view);
}

void lightwave_pipeline::set_vertex_uniforms(const program& target) const {
  target.set("view_projection", camera_view_projection());
  target.set("eye", scene_.view.position);
  target.set("vpl_texture", 0);
  target.set("vpl_count", summed_vpl_count());
  set_uniforms(target, "shading", settings_.shading);
  set_uniforms(target, "irradiance", settings_.irradiance);
}

void lightwave_pipeline::capture_into(GLuint buffer, const mesh_buffers& vertices) {
  set_vertex_uniforms(capture_program_);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, buffer);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, vpl_texture_.get());
  // Nothing is rasterised, but a draw needs a complete framebuffer (a surfaceless EGL context
  // has no default one).
  target_.bind();
  capture_program_.use();
  glEnable(GL_RASTERIZER_DISCARD);
  glBeginTransformFeedback(GL_POINTS);
  vertices.draw_points();
  glEndTransformFeedback();
  glDisable(GL_RASTERIZER_DISCARD);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
  check_gl("capturing the Light Wave vertex stage");
}

void lightwave_pipeline::sum_at_receivers() {
  static_assert(lightwave_sum_receivers == 4, "lightwave_capture.frag reads the previous pass's sums from four samplers, partial_sum0..3");
  // The first pass continues from zero.
  receiver_sum_targets_[1].bind();
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  const program& p = receiver_sum_program_;
  p.use();
  p.set("receiver_points", 0);
  p.set("receiver_normals", 1);
  p.set("receiver_albedos", 2);
  for (int k = 0; k < lightwave_sum_receivers; ++k) p.set("partial_sum" + std::to_string(k), 3 + k);
  p.set("receiver_count", static_cast<int>(receivers_.vertices.size()));
  set_uniforms(p, "irradiance", settings_.irradiance);
  for (std::size_t k = 0; k < receiver_textures_.size(); ++k) receiver_textures_[k].bind(static_cast<int>(k));
  glBindVertexArray(empty_vertex_array_.get());
  const int passes = lightwave_vpl_pass_count(receiver_vpls_.size(), vpls_per_pass_), count = static_cast<int>(receiver_vpls_.size());
  for (int pass = 0; pass < passes; ++pass) {
    const framebuffer& target = receiver_sum_targets_[static_cast<std::size_t>(pass % 2)];
    target.bind();
    const framebuffer& previous = receiver_sum_targets_[static_cast<std::size_t>((pass + 1) % 2)];
    for (int k = 0; k < lightwave_sum_receivers; ++k) previous.colour(static_cast<std::size_t>(k)).bind(3 + k);
    glBindBufferRange(GL_UNIFORM_BUFFER, 0, vpl_block_buffer_.get(), static_cast<GLintptr>(static_cast<std::size_t>(pass) * vpl_block_stride_),
                      static_cast<GLsizeiptr>(static_cast<std::size_t>(vpls_per_pass_) * 3 * sizeof(glm::vec4)));
    p.set("pass_vpl_count", std::min(vpls_per_pass_, count - pass * vpls_per_pass_));
    p.set("last_pass", pass + 1 == passes ? 1 : 0);
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  glBindVertexArray(0);
  glBindBufferBase(GL_UNIFORM_BUFFER, 0, 0);
  // Into the main pass's attribute buffer without a trip through host memory, band after band.
  const framebuffer& result = receiver_sum_targets_[static_cast<std::size_t>((passes - 1) % 2)];
  const std::size_t band_bytes = static_cast<std::size_t>(result.width()) * static_cast<std::size_t>(result.height()) * sizeof(glm::vec4);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, indirect_buffer_.get());
  for (int k = 0; k < lightwave_sum_receivers; ++k) {
    result.bind_for_reading(static_cast<std::size_t>(k));
    glReadPixels(0, 0, result.width(), result.height(), GL_RGBA, GL_FLOAT, reinterpret_cast<void*>(static_cast<std::uintptr_t>(k) * band_bytes));
  }
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  check_gl("summing the Light Wave VPLs at the receivers");
}

std::vector<glm::vec3> lightwave_pipeline::capture_vertex_indirect() {
  if (settings_.energy == lightwave_energy::flux && !receiver_buffers_)
    throw error(std::string("Light Wave technique ") + technique_.name + " sums no VPLs: no vertex indirect light to capture");
  if (vpls_dirty_ || shadows_dirty_) {
    rebuild();
    timer_.collect();  // not a frame's passes
  }
  // Flux energy: the buffer the main pass reads, captured at the last build.
  const std::size_t count = receiver_buffers_ ? receivers_.vertices.size() : scene_.geometry.vertices.size();
  gl_buffer captured(generate_buffer());
  if (!receiver_buffers_) {
    glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, captured.get());
    glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER, static_cast<GLsizeiptr>(count * sizeof(glm::vec3)), nullptr, GL_STATIC_READ);
    capture_into(captured.get(), mesh_);
  }
  std::vector<glm::vec3> result(count);
  if (receiver_buffers_) {
    std::vector<glm::vec4> texels(count);
    glBindBuffer(GL_ARRAY_BUFFER, indirect_buffer_.get());
    glGetBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(count * sizeof(glm::vec4)), texels.data());
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    for (std::size_t i = 0; i < count; ++i) result[i] = glm::vec3(texels[i]);
  } else {
    glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, captured.get());
    glGetBufferSubData(GL_TRANSFORM_FEEDBACK_BUFFER, 0, static_cast<GLsizeiptr>(count * sizeof(glm::vec3)), result.data());
    glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, 0);
  }
  check_gl("reading the Light Wave vertex stage back");
  return result;
}

}  // namespace vplkit
