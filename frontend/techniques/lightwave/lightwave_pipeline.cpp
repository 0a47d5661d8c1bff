#include "frontend/techniques/lightwave/lightwave_pipeline.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/hash.hpp>
#include <vplkit/lightwave.hpp>
#include <vplkit/gl/settings_uniforms.hpp>

#include "frontend/gl/debug_output.hpp"
#include "frontend/core/error.hpp"
#include "frontend/core/named_table.hpp"
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
          .feeds("lightwave.frag: irradiance.min_distance"),
      entry::number("seed", [](auto& s) -> auto& { return s.seed; }, closed_range(0, 4294967295.0), "", "seed of the accurate shadows' VPL draw")
          .read_by(modes({lightwave_mode::accurate}), "the accurate shadows"),
      entry::number("ray-angle", [](auto& s) -> auto& { return s.angle_deg; }, describe_field(&lightwave_layout_settings<float>::angle_deg))
          .allowing(ray_angles)
          .read_by(vpl_light, "the VPL light")
          .feeds("lightwave.vert: vpl_texture; lightwave.vert: vpl_count"),
      entry::number("vpls-per-ray", [](auto& s) -> auto& { return s.per_ray; }, describe_field(&lightwave_layout_settings<float>::per_ray))
          .read_by(vpl_light, "the VPL light")
          .feeds("lightwave.vert: vpl_texture; lightwave.vert: vpl_count"),
      entry::number("vpl-max-distance", [](auto& s) -> auto& { return s.max_distance; }, closed_range(0, max_scene_coordinate), "scene units",
                    "the distance the hemispheres approach (0: from the scene's size)")
          .read_by(vpl_light, "the VPL light")
          .feeds("lightwave.vert: vpl_texture"),
      entry::number("shadow-maps", [](auto& s) -> auto& { return s.accurate_maps; }, closed_range(0, lightwave_max_shadow_maps), "",
                    "VPL shadow maps of the accurate shadows (0: none)")
          .read_by(modes({lightwave_mode::accurate}), "the accurate shadows")
          .feeds("lightwave.frag: indirect_maps; lightwave.frag: shadow_matrix"),
      entry::choice("shadow-variant", [](auto& s) -> auto& { return s.shadow_variant; },
                    {{"importance", lightwave_shadow_variant::importance}, {"thesis", lightwave_shadow_variant::thesis}},
                    "importance (VPLs drawn by their light on the scene, maps aimed at it, lookups weighted by each VPL's light) or thesis "
                    "(uniform VPLs, maps along their normals, the plain mean)")
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
  const int vpls = lightwave_vpl_count(settings.angle_deg, settings.per_ray);
  // The vertex stage loops over every VPL, and llvmpipe ends a loop after 65535 iterations.
  if (vpls > 65535) return "at most 65535 VPLs (the per-vertex loop; llvmpipe stops loops there), got " + std::to_string(vpls);
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

std::vector<lightwave_shadow_caster> lightwave_importance_vpls(const std::vector<lightwave_vpl<float>>& vpls,
                                                               const std::vector<lightwave_receiver_point>& points, int count, std::uint32_t seed) {
  std::vector<double> weight(vpls.size(), 0.0);
  double total = 0.0;
  for (std::size_t i = 0; i < vpls.size(); ++i) {
    for (const lightwave_receiver_point& point : points) weight[i] += lightwave_vpl_weight(point.position, point.normal, vpls[i]);
    total += weight[i];
  }
  std::vector<lightwave_shadow_caster> chosen;
  if (!(total > 0.0) || count < 1) return chosen;
  // Systematic sampling: the k-th pick at (k + u) / count of the cumulative weight. A VPL heavier
  // than total / count would be picked twice: the repeat moves on to the next VPL not chosen.
  const double offset = uniform_float_from_bits(hash_uint32(seed ^ 0x2545f491u));
  std::vector<char> taken(vpls.size(), 0);
  std::size_t cursor = 0;
  double cumulative = 0.0;
  for (int k = 0; k < count; ++k) {
    const double target = (static_cast<double>(k) + offset) / count * total;
    while (cursor + 1 < vpls.size() && cumulative + weight[cursor] <= target) cumulative += weight[cursor++];
    std::size_t pick = cursor;
    while (pick < vpls.size() && (taken[pick] || weight[pick] <= 0.0)) ++pick;
    if (pick == vpls.size()) break;
    taken[pick] = 1;
    chosen.push_back({static_cast<int>(pick), static_cast<float>(std::min(1.0, count * weight[pick] / total))});
  }
  return chosen;
}

namespace {

glm::mat4 look_along(const glm::vec3& position, const glm::vec3& direction) {
  const glm::vec3 up = std::abs(direction.y) > 0.99f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
  return glm::lookAt(position, position + direction, up);
}

// Points spread over the scene's surface in proportion to area (systematic over the triangles'
// cumulative areas, barycentric coordinates from the hash), kept when the camera can see them
// (inside its frustum, facing it): what the shadow casters are chosen and aimed for. Vertices
// alone would weigh a 36-triangle box scene by its corners, and without the camera test the
// underside of the floor would draw VPLs below it.
std::vector<lightwave_receiver_point> visible_surface_points(const mesh& geometry, const camera& view, float aspect, int count) {
  const glm::mat4 view_projection = camera_projection_matrix(view, aspect) * camera_view_matrix(view);
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
    const glm::vec4 clip = view_projection * glm::vec4(position, 1.0f);
    const bool in_view = clip.w > 0.0f && std::abs(clip.x) <= clip.w && std::abs(clip.y) <= clip.w;
    if (!in_view || !(glm::dot(normal, view.position - position) > 0.0f)) continue;
    points.push_back({position, glm::normalize(normal)});
  }
  return points;
}

}  // namespace

glm::mat4 lightwave_aimed_shadow_matrix(const lightwave_vpl<float>& vpl, const std::vector<lightwave_receiver_point>& points, float near_plane,
                                        float far_plane, float aspect, float fallback_fov_degrees) {
  glm::vec3 mean(0.0f);
  std::vector<glm::vec3> lit;  // the points this VPL lights
  for (const lightwave_receiver_point& point : points) {
    const float w = lightwave_vpl_weight(point.position, point.normal, vpl);
    if (!(w > 0.0f)) continue;
    mean += w * glm::normalize(point.position - vpl.position);
    lit.push_back(point.position);
  }
  if (!(glm::length(mean) > 1e-6f)) return glm::perspective(glm::radians(fallback_fov_degrees), aspect, near_plane, far_plane) * look_along(vpl.position, vpl.normal);
  const glm::vec3 axis = glm::normalize(mean);
  const glm::mat4 view = look_along(vpl.position, axis);
  // The half-angles that hold every lit point, across and up the map, plus 2 degrees.
  float tan_x = 0.0f, tan_y = 0.0f;
  for (const glm::vec3& position : lit) {
    const glm::vec3 eye = glm::vec3(view * glm::vec4(position, 1.0f));
    const float depth = std::max(-eye.z, 1e-4f);
    tan_x = std::max(tan_x, std::abs(eye.x) / depth);
    tan_y = std::max(tan_y, std::abs(eye.y) / depth);
  }
  const float max_half = glm::radians(80.0f), margin = glm::radians(2.0f);
  const float half_y = std::min(max_half, std::max(std::atan(tan_y), std::atan(tan_x / aspect)) + margin);
  return glm::perspective(2.0f * half_y, aspect, near_plane, far_plane) * view;
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
      depth_program_(load_program(shaders, "scene.vert", "depth_only.frag")),
      shadow_framebuffer_(generate_framebuffer()),
      target_(settings.width, settings.height, {settings.format, settings.format, settings.format}, true) {
  if (source.light.kind != light_kind::spot) throw error("Light Wave needs a spot light; scene " + source.name + " has a directional one");
  if (const setting_problem problem = validate(source.light.spot)) throw error("scene " + source.name + ": " + problem.message());
  const shader_defines defines = {{"VPLKIT_LIGHTWAVE_MODE", std::to_string(static_cast<int>(technique_.mode))},
                                  {"VPLKIT_LIGHTWAVE_SHADOW_VARIANT", std::to_string(static_cast<int>(settings_.shadow_variant))},
                                  {"VPLKIT_LIGHTWAVE_INDIRECT", technique_.mode >= lightwave_mode::unshadowed ? "1" : "0"},
                                  {"VPLKIT_MAX_SHADOW_MAPS", std::to_string(lightwave_max_shadow_maps)}};
  main_program_ = load_program(shaders, "lightwave.vert", "lightwave.frag", defines);
  capture_program_ = link_program("lightwave.vert (transform feedback)",
                                  {{shader_stage::vertex, shaders.expand_file("lightwave.vert", {{"VPLKIT_LIGHTWAVE_INDIRECT", "1"}})}},
                                  {"vertex_indirect"});

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
  dirty_ = true;
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
      << "x" << settings_.height << ", " << vpl_count() << " VPLs (" << settings_.angle_deg << " degrees, " << settings_.per_ray << " per ray), shadow maps: "
      << std::fixed << std::setprecision(2) << static_cast<double>(shadow_map_bytes()) / (1024.0 * 1024.0) << " MB (Eq. 5.4/5.5)";
  return out.str();
}

void lightwave_pipeline::rebuild() {
  const spot_light<float>& light = scene_.light.spot;
  const bounding_box box = bounds(scene_.geometry);
  float max_distance = settings_.max_distance;
  if (max_distance == 0.0f)
    for (int corner = 0; corner < 8; ++corner) {
      const glm::vec3 p((corner & 1) ? box.maximum.x : box.minimum.x, (corner & 2) ? box.maximum.y : box.minimum.y,
                        (corner & 4) ? box.maximum.z : box.minimum.z);
      max_distance = std::max(max_distance, glm::length(p - light.position));
    }
  layout_ = {light.position, light.direction, settings_.angle_deg, settings_.per_ray, max_distance};
  vpls_.clear();
  lightwave_layout(layout_, std::back_inserter(vpls_));

  // VPL texture: texel (0, i) = [position | attenuation], texel (1, i) = [normal | 0].
  std::vector<glm::vec4> texels(vpls_.size() * 2);
  for (std::size_t i = 0; i < vpls_.size(); ++i) {
    texels[2 * i] = glm::vec4(vpls_[i].position, vpls_[i].attenuation);
    texels[2 * i + 1] = glm::vec4(vpls_[i].normal, 0.0f);
  }
  check_texture_size(2, static_cast<int>(vpls_.size()), "the Light Wave VPL texture");
  vpl_texture_ = gl_texture(generate_texture());
  glBindTexture(GL_TEXTURE_2D, vpl_texture_.get());
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, 2, static_cast<GLsizei>(vpls_.size()), 0, GL_RGBA, GL_FLOAT, texels.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);

  // Shadow matrices: the spot light's frustum, then each chosen VPL's.
  const float radius = std::max(box.radius(), 1e-3f);
  const float aspect = static_cast<float>(shadow_size_.x) / static_cast<float>(shadow_size_.y);
  const float near_plane = 0.01f * radius, far_plane = glm::length(light.position - box.centre()) + 2.0f * radius;
  shadow_matrices_.clear();
  shadow_matrices_.push_back(glm::perspective(2.0f * spot_light_frustum_half_angle(light), aspect, near_plane, far_plane) * look_along(light.position, light.direction));
  // The shadow casters: drawn by importance or uniformly (accurate), the fixed ring (integrated).
  // The integrated shadows keep the thesis's maps (along the VPLs' normals, one field of view):
  // their in-between lookups interpolate a fragment's coordinates between two maps, which stands
  // for an in-between light only when the maps share their projection; aimed maps of different
  // fields of view darkened an empty plane (lowest factor 0.72, measured).
  const bool importance = casters_follow_camera();
  const std::vector<lightwave_receiver_point> points =
      importance ? visible_surface_points(scene_.geometry, scene_.view, static_cast<float>(settings_.width) / static_cast<float>(settings_.height), 4096)
                 : std::vector<lightwave_receiver_point>{};
  casters_.clear();
  if (importance) {
    casters_ = lightwave_importance_vpls(vpls_, points, settings_.accurate_maps, settings_.seed);
  } else {
    for (int index : lightwave_shadow_vpls(technique_.mode, settings_)) casters_.push_back({index, 1.0f});
  }
  for (const lightwave_shadow_caster& caster : casters_) {
    const lightwave_vpl<float>& vpl = vpls_[static_cast<std::size_t>(caster.vpl)];
    shadow_matrices_.push_back(importance ? lightwave_aimed_shadow_matrix(vpl, points, near_plane, far_plane + max_distance, aspect, settings_.vpl_field_of_view)
                                          : glm::perspective(glm::radians(settings_.vpl_field_of_view), aspect, near_plane, far_plane + max_distance) *
                                                look_along(vpl.position, vpl.normal));
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
  for (std::size_t i = 0; i < shadow_matrices_.size(); ++i) p.set("shadow_matrix[" + std::to_string(i) + "]", shadow_matrices_[i]);
  // Each caster's VPL and the inverse of the probability it was drawn with: the weights of its
  // lookups (importance variant).
  for (std::size_t i = 0; i < casters_.size(); ++i) {
    const lightwave_vpl<float>& vpl = vpls_[static_cast<std::size_t>(casters_[i].vpl)];
    p.set("caster_position_attenuation[" + std::to_string(i) + "]", glm::vec4(vpl.position, vpl.attenuation));
    p.set("caster_normal_weight[" + std::to_string(i) + "]", glm::vec4(vpl.normal, 1.0f / casters_[i].probability));
  }
  check_gl("building the Light Wave VPLs and shadow maps");
  dirty_ = false;
  ++rebuilds_;
}

void lightwave_pipeline::set_camera(const camera& view) {
  check_camera(view, "Light Wave scene " + scene_.name);
  scene_.view = view;
  if (casters_follow_camera()) dirty_ = true;
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
  dirty_ = true;
  draw_changed();
}

void lightwave_pipeline::draw_changed() {
  if (dirty_) {
    timer_.begin("VPLs and shadow maps");
    rebuild();
    timer_.end();
    view_valid_ = false;
  }
  if (!view_valid_) draw_main_pass();
}

void lightwave_pipeline::draw_main_pass() {
  timer_.begin("main pass");
  target_.bind();
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
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
  mesh_.draw(main_program_);
  timer_.end();
  check_gl("rendering scene " + scene_.name + " with " + technique_.name);
  view_valid_ = true;
  ++main_draws_;
}

void lightwave_pipeline::set_vertex_uniforms(const program& target) const {
  target.set("view_projection", camera_projection_matrix(scene_.view, static_cast<float>(settings_.width) / static_cast<float>(settings_.height)) *
                                    camera_view_matrix(scene_.view));
  target.set("eye", scene_.view.position);
  target.set("vpl_texture", 0);
  target.set("vpl_count", static_cast<int>(vpls_.size()));
  set_uniforms(target, "shading", settings_.shading);
}

std::vector<glm::vec3> lightwave_pipeline::capture_vertex_indirect() {
  if (dirty_) rebuild();
  set_vertex_uniforms(capture_program_);
  const std::size_t count = scene_.geometry.vertices.size();
  gl_buffer captured(generate_buffer());
  glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, captured.get());
  glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER, static_cast<GLsizeiptr>(count * sizeof(glm::vec3)), nullptr, GL_STATIC_READ);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, captured.get());
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, vpl_texture_.get());
  // Nothing is rasterised, but a draw needs a complete framebuffer (a surfaceless EGL context
  // has no default one).
  target_.bind();
  capture_program_.use();
  glEnable(GL_RASTERIZER_DISCARD);
  glBeginTransformFeedback(GL_POINTS);
  mesh_.draw_points();
  glEndTransformFeedback();
  glDisable(GL_RASTERIZER_DISCARD);
  std::vector<glm::vec3> result(count);
  glGetBufferSubData(GL_TRANSFORM_FEEDBACK_BUFFER, 0, static_cast<GLsizeiptr>(count * sizeof(glm::vec3)), result.data());
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
  check_gl("capturing the Light Wave vertex stage");
  return result;
}

}  // namespace vplkit
