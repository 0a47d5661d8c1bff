// A scene's checks (the last gate before a pipeline or the ray tracer sees it) and its surface
// queries; the built-in scenes are in built_in_scenes.cpp, mesh building in mesh_building.cpp.
#include "frontend/scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "frontend/core/error.hpp"

namespace vplkit {

bounding_box bounds(const mesh& geometry) {
  bounding_box box;
  box.minimum = glm::vec3(std::numeric_limits<float>::max());
  box.maximum = glm::vec3(std::numeric_limits<float>::lowest());
  for (const vertex& v : geometry.vertices) {
    box.minimum = glm::min(box.minimum, v.position);
    box.maximum = glm::max(box.maximum, v.position);
  }
  if (geometry.vertices.empty()) box = {};
  return box;
}

float spot_light_frustum_half_angle(const spot_light<float>& light) {
  return glm::min(std::acos(glm::clamp(light.cos_outer, -1.0f, 1.0f)) + glm::radians(2.0f), glm::radians(85.0f));
}

namespace {

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string text_of(const glm::vec3& v) {
  // Built with += rather than "(" + string: GCC 12 gives a false -Wrestrict on the latter (bug 105329).
  std::string text = "(";
  text += std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) + ")";
  return text;
}

std::string power_limit_text() {
  char text[32];
  std::snprintf(text, sizeof text, "%g", static_cast<double>(max_light_power));
  return text;
}

}  // namespace

void check_mesh(const mesh& geometry, const std::string& name) {
  const auto fail = [&](const std::string& what) { throw error(name + ": " + what); };
  if (geometry.indices.empty() || geometry.indices.size() % 3 != 0) fail("no triangles, or an index count that is not a multiple of 3");
  for (std::size_t i = 0; i < geometry.vertices.size(); ++i) {
    const vertex& v = geometry.vertices[i];
    if (!finite(v.position) || glm::any(glm::greaterThan(glm::abs(v.position), glm::vec3(max_scene_coordinate))))
      fail("vertex " + std::to_string(i) + " at " + text_of(v.position) + " is not finite or beyond " +
           std::to_string(static_cast<long>(max_scene_coordinate)) + " (vplkit works in float; scale the scene down)");
    if (!finite(v.normal) || !finite(v.albedo)) fail("vertex " + std::to_string(i) + " has a non-finite normal or albedo");
    if (!std::isfinite(v.texcoord.x) || !std::isfinite(v.texcoord.y)) fail("vertex " + std::to_string(i) + " has a non-finite texture coordinate");
  }
  for (const std::uint32_t index : geometry.indices)
    if (index >= geometry.vertices.size()) fail("index " + std::to_string(index) + " is past the " + std::to_string(geometry.vertices.size()) + " vertices");
  check_materials(geometry, name);
}

bool has_alpha_cutouts(const mesh& geometry) {
  if (!geometry.materials) return false;
  for (const surface_material& material : geometry.materials->materials)
    if (material.alpha_mask) return true;
  return false;
}

bool has_emission(const mesh& geometry) {
  if (!geometry.materials) return false;
  for (const material_range& range : geometry.material_ranges)
    if (range.index_count > 0 && range.material < geometry.materials->materials.size() && emits(geometry.materials->materials[range.material])) return true;
  return false;
}

void check_materials(const mesh& geometry, const std::string& name) {
  const auto fail = [&](const std::string& what) { throw error(name + ": " + what); };
  if (geometry.material_ranges.empty()) return;
  if (!geometry.materials) fail("material ranges without materials");
  const material_library& library = *geometry.materials;
  std::uint64_t end = 0;
  for (std::size_t r = 0; r < geometry.material_ranges.size(); ++r) {
    const material_range& range = geometry.material_ranges[r];
    const std::string where = "material range " + std::to_string(r);
    if (range.first_index < end || range.first_index % 3 != 0 || range.index_count % 3 != 0 ||
        std::uint64_t{range.first_index} + range.index_count > geometry.indices.size())
      fail(where + " does not lie in order on whole triangles within the " + std::to_string(geometry.indices.size()) + " indices");
    end = std::uint64_t{range.first_index} + range.index_count;
    if (range.material >= library.materials.size()) fail(where + " names material " + std::to_string(range.material) + ", but there are " + std::to_string(library.materials.size()));
  }
  for (std::size_t m = 0; m < library.materials.size(); ++m) {
    const surface_material& material = library.materials[m];
    const std::string where = "material " + std::to_string(m) + " '" + material.name + "'";
    if (material.texture >= static_cast<int>(library.textures.size()) || material.texture < -1) fail(where + " names a texture that does not exist");
    const glm::vec4 matrix(material.texture_matrix[0], material.texture_matrix[1]);
    if (!finite(glm::vec3(matrix)) || !std::isfinite(matrix.w) || !std::isfinite(material.texture_offset.x) || !std::isfinite(material.texture_offset.y))
      fail(where + ": its texture transform is not finite");
    if (!(material.alpha_factor >= 0.0f && material.alpha_factor <= 1.0f) || !(material.alpha_cutoff >= 0.0f && material.alpha_cutoff <= 1.0f))
      fail(where + ": alpha factor and cutoff must be in [0, 1]");
    const glm::vec3& e = material.emission;
    if (!(e.r >= 0.0f && e.g >= 0.0f && e.b >= 0.0f && e.r <= max_emission && e.g <= max_emission && e.b <= max_emission))
      fail(where + ": its emission must be finite and in [0, " + std::to_string(static_cast<int>(max_emission)) + "] per channel");
    if (material.emission_texture >= static_cast<int>(library.textures.size()) || material.emission_texture < -1)
      fail(where + " names an emission texture that does not exist");
    const glm::vec4 emission_matrix(material.emission_texture_matrix[0], material.emission_texture_matrix[1]);
    if (!finite(glm::vec3(emission_matrix)) || !std::isfinite(emission_matrix.w) || !std::isfinite(material.emission_texture_offset.x) ||
        !std::isfinite(material.emission_texture_offset.y))
      fail(where + ": its emission texture transform is not finite");
  }
  for (const texture& t : library.textures) {
    bool consistent = !t.levels.empty();
    for (const texture_level& level : t.levels)
      consistent = consistent && level.width >= 1 && level.height >= 1 &&
                   level.rgba8.size() == static_cast<std::size_t>(level.width) * static_cast<std::size_t>(level.height) * 4;
    if (!consistent) fail("texture '" + t.name + "' has a level whose pixels do not match its size");
  }
}

const surface_material* material_of_triangle(const mesh& geometry, std::size_t triangle) {
  const std::vector<material_range>& ranges = geometry.material_ranges;
  if (ranges.empty() || !geometry.materials) return nullptr;
  const std::size_t first = 3 * triangle;
  // The last range starting at or before the triangle.
  auto after = std::upper_bound(ranges.begin(), ranges.end(), first, [](std::size_t index, const material_range& range) { return index < range.first_index; });
  if (after == ranges.begin()) return nullptr;
  const material_range& range = *(after - 1);
  if (first >= std::size_t{range.first_index} + range.index_count) return nullptr;
  return &geometry.materials->materials[range.material];
}

glm::vec4 surface_albedo_alpha(const mesh& geometry, std::size_t triangle, glm::vec2 barycentric, float lod) {
  const vertex& a = geometry.vertices[geometry.indices[3 * triangle]];
  const vertex& b = geometry.vertices[geometry.indices[3 * triangle + 1]];
  const vertex& c = geometry.vertices[geometry.indices[3 * triangle + 2]];
  const float u = barycentric.x, v = barycentric.y, w = 1.0f - u - v;
  const glm::vec3 factor = w * a.albedo + u * b.albedo + v * c.albedo;
  const surface_material* material = material_of_triangle(geometry, triangle);
  if (!material) return glm::vec4(factor, 1.0f);
  glm::vec4 texel(1.0f);
  if (material->texture >= 0) {
    const glm::vec2 uv = material_texture_coordinate(*material, w * a.texcoord + u * b.texcoord + v * c.texcoord);
    texel = sample_texture(geometry.materials->textures[static_cast<std::size_t>(material->texture)], material->sampler, uv, lod);
  }
  return glm::vec4(factor * glm::vec3(texel), material->alpha_factor * texel.a);
}

glm::vec3 surface_emission(const mesh& geometry, std::size_t triangle, glm::vec2 barycentric, float lod) {
  const surface_material* material = material_of_triangle(geometry, triangle);
  if (!material || !emits(*material)) return glm::vec3(0.0f);
  const vertex& a = geometry.vertices[geometry.indices[3 * triangle]];
  const vertex& b = geometry.vertices[geometry.indices[3 * triangle + 1]];
  const vertex& c = geometry.vertices[geometry.indices[3 * triangle + 2]];
  const float u = barycentric.x, v = barycentric.y, w = 1.0f - u - v;
  return material_emission(*geometry.materials, *material, w * a.texcoord + u * b.texcoord + v * c.texcoord, lod);
}

bool surface_cut_out(const mesh& geometry, std::size_t triangle, glm::vec2 barycentric, float lod) {
  const surface_material* material = material_of_triangle(geometry, triangle);
  return material && material->alpha_mask && surface_albedo_alpha(geometry, triangle, barycentric, lod).a < material->alpha_cutoff;
}

namespace {

// The light's power field, for a const or a mutable light (one choice of field for both).
template <typename Light>
auto& power_of(Light& light) {
  return light.kind == light_kind::spot ? light.spot.intensity : light.kind == light_kind::point ? light.point.intensity : light.directional.irradiance;
}

void check_intensity(float intensity) {
  if (!(intensity >= 0.0f && std::isfinite(intensity))) throw error("the light intensity must be finite and >= 0, got " + std::to_string(intensity));
}

}  // namespace

glm::vec3 light_power(const scene_light& light) { return power_of(light); }

void set_light_intensity(scene_light& light, float intensity) {
  check_intensity(intensity);
  glm::vec3& power = power_of(light);
  const float peak = std::max({power.r, power.g, power.b});
  power = (peak > 0.0f ? power / peak : glm::vec3(1.0f)) * intensity;
}

void scale_light_intensities(std::vector<scene_light>& lights, float intensity) {
  check_intensity(intensity);
  float peak = 0.0f;
  for (const scene_light& light : lights) peak = std::max({peak, power_of(light).r, power_of(light).g, power_of(light).b});
  for (scene_light& light : lights) power_of(light) = peak > 0.0f ? power_of(light) / peak * intensity : glm::vec3(intensity);  // as set_light_intensity rounds
}

void check_camera(const camera& view, const std::string& owner) {
  if (!finite(view.position) || !finite(view.target) || !finite(view.up) || !std::isfinite(view.vertical_fov_degrees) ||
      !(view.near_plane > 0.0f) || !(view.far_plane > view.near_plane) || !std::isfinite(view.far_plane))
    throw error(owner + ": the camera has a non-finite value or bad near/far planes");
  if (!(view.vertical_fov_degrees > 0.0f && view.vertical_fov_degrees < 180.0f))
    throw error(owner + ": the camera's vertical field of view must be in (0, 180) degrees");
  const glm::vec3 forward = view.target - view.position;
  if (!(glm::dot(forward, forward) > 0.0f)) throw error(owner + ": the camera's position and target are the same point");
  if (!(glm::length(glm::cross(forward, view.up)) > 1e-6f * glm::length(forward) * glm::length(view.up)))
    throw error(owner + ": the camera looks along its up vector");
}

void check_light(const scene_light& light, const std::string& owner) {
  if (light.kind == light_kind::spot) {
    const spot_light<float>& spot = light.spot;
    if (!finite(spot.position) || !finite(spot.direction) || !finite(spot.intensity)) throw error(owner + ": the spot light has a non-finite value");
    if (glm::any(glm::greaterThan(glm::abs(spot.intensity), glm::vec3(max_light_power))))
      throw error(owner + ": the spot light's intensity is beyond " + power_limit_text() + " (vplkit's outputs must stay finite)");
    if (const setting_problem problem = validate(spot)) throw error(owner + ": " + problem.message());
  } else if (light.kind == light_kind::point) {
    const point_light<float>& bulb = light.point;
    if (!finite(bulb.position) || !finite(bulb.intensity)) throw error(owner + ": the point light has a non-finite value");
    if (glm::any(glm::greaterThan(glm::abs(bulb.intensity), glm::vec3(max_light_power))))
      throw error(owner + ": the point light's intensity is beyond " + power_limit_text() + " (vplkit's outputs must stay finite)");
    if (const setting_problem problem = validate(bulb)) throw error(owner + ": " + problem.message());
  } else {
    const directional_light<float>& sun = light.directional;
    if (!finite(sun.direction) || !finite(sun.irradiance)) throw error(owner + ": the directional light has a non-finite value");
    if (glm::any(glm::greaterThan(glm::abs(sun.irradiance), glm::vec3(max_light_power))))
      throw error(owner + ": the directional light's irradiance is beyond " + power_limit_text() + " (vplkit's outputs must stay finite)");
    if (const setting_problem problem = validate(sun)) throw error(owner + ": " + problem.message());
  }
}

const char* light_kind_name(light_kind kind) {
  switch (kind) {
    case light_kind::spot: return "spot";
    case light_kind::directional: return "directional";
    case light_kind::point: return "point";
  }
  return "unknown";
}

const scene_light& single_light(const scene& s, const std::string& what) {
  if (s.lights.size() != 1)
    throw error("scene " + s.name + ": " + what + " draws one light, the scene has " + std::to_string(s.lights.size()) +
                " (choose one with --lights k)");
  return s.lights.front();
}

void check_lights(const std::vector<scene_light>& lights, const std::string& owner) {
  if (lights.size() > max_scene_lights)
    throw error(owner + ": " + std::to_string(lights.size()) + " lights, at most " + std::to_string(max_scene_lights) +
                " are rendered (choose some with --lights)");
  for (std::size_t k = 0; k < lights.size(); ++k) check_light(lights[k], owner + ", light " + std::to_string(k));
}

void check_scene(const scene& s) {
  check_mesh(s.geometry, "scene " + s.name);
  check_camera(s.view, "scene " + s.name);
  check_lights(s.lights, "scene " + s.name);
}

}  // namespace vplkit
