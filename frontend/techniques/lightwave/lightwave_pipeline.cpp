#include "frontend/techniques/lightwave/lightwave_pipeline.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <numeric>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/cube_map.hpp>
#include <vplkit/lightwave.hpp>
#include <vplkit/gl/settings_uniforms.hpp>

#include "frontend/gl/debug_output.hpp"
#include "frontend/core/error.hpp"
#include "frontend/scene/camera.hpp"

namespace vplkit {

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
      depth_program_(load_program(shaders, "scene.vert", "depth_only.frag",
                                  has_alpha_cutouts(source.geometry) ? shader_defines{} : shader_defines{{"VPLKIT_MATERIAL_NO_ALPHA_TEST", "1"}})),
      shadow_framebuffer_(generate_framebuffer()) {
  if (source.lights.empty()) throw error("Light Wave draws at least one light; scene " + source.name + " has none (choose some with --lights)");
  check_lights(source.lights, "scene " + source.name);
  shared_ = std::make_shared<shared_resources>(source.geometry, settings_);
  set_up(shaders, source, true);
  // Each further light: a pipeline of its own on the scene with that light alone, drawing with
  // this one's shared resources. The images are linear in the light, so their sum is the image of
  // all lights; the caches (VPLs, shadow maps, receivers' sums) stay per light, so moving one
  // light rebuilds that light's alone.
  if (source.lights.size() > 1) {
    pass_prefix_ = "light 0: ";
    for (std::size_t k = 1; k < source.lights.size(); ++k) {
      scene alone = source;
      alone.lights = {source.lights[k]};
      light_pipelines_.push_back(std::unique_ptr<lightwave_pipeline>(new lightwave_pipeline(shaders, alone, settings, shared_)));
      light_pipelines_.back()->pass_prefix_ = "light " + std::to_string(k) + ": ";
    }
  }
}

lightwave_pipeline::lightwave_pipeline(const shader_library& shaders, const scene& source, const lightwave_settings& settings,
                                       std::shared_ptr<shared_resources> shared)
    : scene_(source),
      shared_(std::move(shared)),
      settings_(settings),
      technique_(find_lightwave_technique(settings.technique)),
      depth_program_(load_program(shaders, "scene.vert", "depth_only.frag",
                                  has_alpha_cutouts(source.geometry) ? shader_defines{} : shader_defines{{"VPLKIT_MATERIAL_NO_ALPHA_TEST", "1"}})),
      shadow_framebuffer_(generate_framebuffer()) {
  set_up(shaders, source, false);
}

void lightwave_pipeline::set_up(const shader_library& shaders, const scene& source, bool make_shared) {
  kind_ = source.lights[0].kind;
  light_layers_ = kind_ == light_kind::point ? 6 : 1;
  if (make_shared && has_emission(source.geometry)) emission_.emplace(shaders);
  if (make_shared) {
    shared_->mesh_bytes = static_cast<std::uint64_t>(source.geometry.vertices.size()) * sizeof(vertex) +
                          static_cast<std::uint64_t>(source.geometry.indices.size()) * sizeof(std::uint32_t);
  }
  const shader_defines defines = shader_defines_of();
  load_main_programs(shaders, defines);
  // Direct light alone and the faked indirect light use no VPLs.
  if (settings_.energy == lightwave_energy::flux && technique_.mode >= lightwave_mode::unshadowed) {
    set_up_receivers(shaders, source, make_shared);
    set_up_vpl_blocks(shaders);
    set_up_indirect_buffer(shaders, source, defines, make_shared);
  }
  allocate_shadow_maps();
}

// The defines every program of the main pass is built with.
shader_defines lightwave_pipeline::shader_defines_of() const {
  const std::string energy = std::to_string(static_cast<int>(settings_.energy));
  // The flux energy's indirect light: from a screen buffer the receivers fill (shared_->indirect_target),
  // so that the main pass runs on the scene's own triangles, with their materials (the receivers
  // have none) and, with indirect shadows, its heavy fragment stage on few large triangles.
  const bool indirect_buffer = settings_.energy == lightwave_energy::flux && technique_.mode >= lightwave_mode::unshadowed;
  const shader_defines defines = {{"VPLKIT_LIGHTWAVE_MODE", std::to_string(static_cast<int>(technique_.mode))},
                                  {"VPLKIT_LIGHTWAVE_INDIRECT_BUFFER", indirect_buffer ? "1" : "0"},
                                  {"VPLKIT_LIGHTWAVE_SHADOW_VARIANT", std::to_string(static_cast<int>(settings_.shadow_variant))},
                                  {"VPLKIT_LIGHTWAVE_ENERGY", energy},
                                  {"VPLKIT_LIGHTWAVE_INDIRECT", technique_.mode >= lightwave_mode::unshadowed ? "1" : "0"},
                                  {"VPLKIT_MAX_SHADOW_MAPS", std::to_string(lightwave_max_shadow_maps)},
                                  {"VPLKIT_LIGHT_POINT", kind_ == light_kind::point ? "1" : "0"},
                                  {"VPLKIT_LIGHT_DIRECTIONAL", kind_ == light_kind::directional ? "1" : "0"}};
  return defines;
}

void lightwave_pipeline::load_main_programs(const shader_library& shaders, const shader_defines& defines) {
  shader_defines main_defines = defines;
  if (depth_prepass()) main_defines.emplace_back("VPLKIT_MATERIAL_NO_ALPHA_TEST", "1");
  main_program_ = load_program(shaders, "lightwave.vert", "lightwave.frag", main_defines);
  if (settings_.energy == lightwave_energy::thesis)
    capture_program_ = link_program(
        "lightwave.vert (transform feedback)",
        {{shader_stage::vertex, shaders.expand_file("lightwave.vert", {{"VPLKIT_LIGHTWAVE_INDIRECT", "1"}, {"VPLKIT_LIGHTWAVE_ENERGY", "0"}, {"VPLKIT_LIGHTWAVE_CAPTURE", "1"}})}},
        {"vertex_indirect"});
}

// The flux energy's indirect light as a screen buffer the main pass reads (shared_->indirect_target), so
// that the main pass runs on the scene's own triangles, with their materials (the receivers have
// none) and, with indirect shadows, its heavy fragment stage on few large triangles.
void lightwave_pipeline::set_up_indirect_buffer(const shader_library& shaders, const scene& source, const shader_defines& defines, bool make_shared) {
  // Without cut-outs its fragments need no material (no discard: the depth is tested first).
  shader_defines indirect_defines = defines;
  if (!has_alpha_cutouts(source.geometry)) indirect_defines.emplace_back("VPLKIT_MATERIAL_NO_ALPHA_TEST", "1");
  indirect_program_ = load_program(shaders, "lightwave.vert", "lightwave_indirect.frag", indirect_defines);
  // In the output's format (half floats by default, a relative step of 2^-11, as the image's):
  // half the bytes to clear and write cost a software rasteriser about 2 ms less of the boxes'
  // 1280x720 frame.
  // Filled and read by one light's passes at a time: one for every light.
  if (make_shared) shared_->indirect_target.emplace(settings_.width, settings_.height, std::vector<texel_format>{settings_.format}, true);
}

void lightwave_pipeline::allocate_shadow_maps() {
  // The shadow maps: the light's (one, or a point light's six faces), then one per chosen VPL.
  const lightwave_derived_settings derived = derive(settings_);
  shadow_size_ = derived.shadow_map_size;
  shadow_layers_ = light_layers_ + derived.indirect_maps;
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

// Which setting applies in place (the viewer's live controls) and why:
// - rebuild (a new pipeline): the technique (the mode's define), and the settings the table says
//   set a define or size what the constructor builds (setting::defines, setting::builds: the
//   targets, the main programs' defines, the shadow maps' array); besides the table, receiver
//   spacing and triangles (the receivers' mesh, textures and sum targets) and VPLs per pass
//   (lightwave_capture.frag's VPLKIT_LIGHTWAVE_PASS_VPLS, the VPL blocks' stride), which code
//   sets and no option;
// - in place, the VPLs re-planned and the shadow maps redrawn, as after a light move (no program,
//   no target: the VPL texture and blocks are re-uploaded at their new size at every light move
//   anyway): ray-angle, vpls-per-ray, vpl-max-distance;
// - in place, the shadow maps redrawn and (flux energy) the same VPLs summed again at the
//   receivers: min-distance (the sums' clamp and the importance casters' weights read it, the
//   VPLs' placement does not; the thesis energy's vertex stage reads it as a uniform);
// - in place, the shadow maps redrawn: seed (the thesis variant's draw), vpl-field-of-view (the
//   maps' projection), a map count the technique does not read;
// - in place, the main pass only (uniforms it sets at every draw): the rest.
bool lightwave_pipeline::apply_settings(const technique_settings& settings) {
  const auto* typed = dynamic_cast<const described_settings<lightwave_settings, lightwave_technique>*>(&settings);
  if (!typed) return false;
  const lightwave_settings& next = typed->value();
  if (!validate(next).empty() || next.technique != settings_.technique || !rebuilding_changes(lightwave_settings_table(), settings_, next).empty())
    return false;
  if (next.receiver_spacing != settings_.receiver_spacing || next.receiver_triangles != settings_.receiver_triangles || next.vpls_per_pass != settings_.vpls_per_pass)
    return false;
  const bool vpls_move = next.angle_deg != settings_.angle_deg || next.per_ray != settings_.per_ray || next.max_distance != settings_.max_distance;
  const bool clamp_moves = next.irradiance.min_distance != settings_.irradiance.min_distance;
  const bool shadows_move = vpls_move || clamp_moves || next.seed != settings_.seed || next.vpl_field_of_view != settings_.vpl_field_of_view ||
                            next.accurate_maps != settings_.accurate_maps || next.integrated_maps != settings_.integrated_maps;
  // The further lights' pipelines share these settings: the same tests hold for them.
  for (const auto& other : light_pipelines_)
    if (!other->apply_settings(settings)) return false;
  settings_ = next;
  if (vpls_move) vpls_dirty_ = true;
  if (clamp_moves && shared_->receiver_buffers) sums_dirty_ = true;
  if (shadows_move) shadows_dirty_ = true;
  view_valid_ = false;
  return true;
}

void lightwave_pipeline::set_light(std::size_t index, const scene_light& light) {
  if (index >= scene_.lights.size())
    throw error("Light Wave scene " + scene_.name + ": no light " + std::to_string(index) + " (it has " + std::to_string(scene_.lights.size()) + ")");
  if (light.kind != scene_.lights[index].kind)
    throw error("Light Wave scene " + scene_.name + ": light " + std::to_string(index) + " is a " + light_kind_name(scene_.lights[index].kind) +
                " light and cannot become a " + light_kind_name(light.kind) + " one in place (its shadow maps and programs are made for its kind)");
  check_light(light, "Light Wave scene " + scene_.name);
  scene_.lights[index] = light;
  if (index == 0) vpls_dirty_ = shadows_dirty_ = true;
  else light_pipelines_[index - 1]->set_light(0, light);
  view_valid_ = false;
}

const texture_2d* lightwave_pipeline::indirect_shadow_output() const {
  const bool shadowed = technique_.mode == lightwave_mode::accurate || technique_.mode == lightwave_mode::integrated;
  return shadowed ? &shared_->target.colour(1) : nullptr;
}

std::string lightwave_pipeline::draw_counts() const {
  return "VPLs and shadow maps " + std::to_string(rebuilds_) + ", main pass " + std::to_string(main_draws_);
}

std::string lightwave_pipeline::describe() const {
  std::ostringstream out;
  out << "scene " << scene_.name << " (" << scene_.geometry.triangle_count() << " triangles), "
      << (light_pipelines_.empty() ? std::string() : std::to_string(light_count()) + " lights (the counts below per light), ") << "technique " << settings_.technique << ", " << settings_.width
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

void lightwave_pipeline::draw_surfaces(const glm::mat4& view_projection, std::size_t slot) {
  // What the light sees: world position (w = 1 where a surface is), normal and albedo per texel.
  shared_->surfaces->bind();
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  surface_program_.use();
  surface_program_.set("view_projection", view_projection);
  shared_->scene_mesh.draw(surface_program_);
  // Into the same host memory at every light move.
  for (std::size_t k = 0; k < 3; ++k) shared_->surfaces->colour(k).read_image_into(shared_->surface_texels[slot][k]);
}

void lightwave_pipeline::build_flux_vpls() {
  const scene_light& light = scene_.lights[0];
  const auto map_of = [&](const glm::mat4& view_projection, std::size_t slot) {
    draw_surfaces(view_projection, slot);
    const std::array<image, 3>& texels = shared_->surface_texels[slot];
    return lightwave_surface_map{view_projection, &texels[0], &texels[1], &texels[2]};
  };
  // One set of images per map, allocated before any is pointed at (a point light's six faces are
  // looked up together).
  const std::size_t map_count = kind_ == light_kind::point ? 6 : 1;
  if (shared_->surface_texels.size() < map_count) shared_->surface_texels.resize(map_count);
  cone_.angle_deg = settings_.angle_deg;
  cone_.per_ray = settings_.per_ray;
  cone_.light_direction = light_axis();
  if (kind_ == light_kind::spot) {
    const frame_geometry g = geometry();
    const glm::mat4 view_projection = glm::perspective(2.0f * spot_light_frustum_half_angle(light.spot), 1.0f, g.near_plane, g.far_plane) * g.light_view;
    const lightwave_surface_map map = map_of(view_projection, 0);
    // The rays cover the cone up to its outer edge, inside the map's frustum (2 degrees of margin).
    cone_.half_angle_deg = glm::degrees(spot_light_frustum_half_angle(light.spot)) - 2.0f;
    flux_vpls_ = lightwave_flux_vpls_from_map(light.spot, cone_, view_projection, *map.positions, *map.normals, *map.albedos, flux_layout_index_);
  } else if (kind_ == light_kind::point) {
    // The six faces the direct light's shadow uses, each a map of what the light sees.
    const std::vector<glm::mat4> faces = light_matrices();
    std::array<lightwave_surface_map, 6> maps;
    for (std::size_t f = 0; f < 6; ++f) maps[f] = map_of(faces[f], f);
    cone_.half_angle_deg = 90.0f;
    flux_vpls_ = lightwave_point_flux_vpls(light.point, cone_, maps, flux_layout_index_);
  } else {
    const frame_geometry g = geometry();
    const glm::mat4 view_projection = light_matrices().front();
    const lightwave_surface_map map = map_of(view_projection, 0);
    const glm::vec3 right(g.light_view[0][0], g.light_view[1][0], g.light_view[2][0]), up(g.light_view[0][1], g.light_view[1][1], g.light_view[2][1]);
    flux_vpls_ = lightwave_sun_flux_vpls(light.directional, settings_.angle_deg, settings_.per_ray, light_origin(), right, up, g.radius, map, flux_layout_index_);
  }
}

namespace {

lightwave_vpl_view view_of(const lightwave_settings& settings, const std::vector<lightwave_vpl<float>>& thesis,
                           const std::vector<lightwave_flux_vpl<float>>& flux) {
  lightwave_vpl_view view;
  if (settings.energy == lightwave_energy::thesis) view.thesis = &thesis;
  else view.flux = &flux;
  view.min_distance = settings.irradiance.min_distance;
  return view;
}

}  // namespace

lightwave_pipeline::frame_geometry lightwave_pipeline::geometry() const {
  const bounding_box box = bounds(scene_.geometry);
  frame_geometry g;
  g.radius = std::max(box.radius(), 1e-3f);
  g.near_plane = 0.01f * g.radius;
  g.far_plane = glm::length(light_origin() - box.centre()) + 2.0f * g.radius;
  g.light_view = lightwave_look_along(light_origin(), light_axis());
  return g;
}

glm::vec3 lightwave_pipeline::light_origin() const {
  const scene_light& light = scene_.lights[0];
  if (kind_ == light_kind::spot) return light.spot.position;
  if (kind_ == light_kind::point) return light.point.position;
  // A sun has no position: its maps and VPL layouts start two bounding radii out from the scene's
  // centre against its direction (outside the bounds, as the RSM's orthographic map does).
  const bounding_box box = bounds(scene_.geometry);
  return box.centre() - 2.0f * std::max(box.radius(), 1e-3f) * light.directional.direction;
}

glm::vec3 lightwave_pipeline::light_axis() const {
  const scene_light& light = scene_.lights[0];
  if (kind_ == light_kind::spot) return light.spot.direction;
  if (kind_ == light_kind::directional) return light.directional.direction;
  // A point light's sphere layouts turn about any axis: straight down puts the first hemisphere's
  // rays (and the integrated shadows' ring) on the floor under the light.
  return {0.0f, -1.0f, 0.0f};
}

std::vector<glm::mat4> lightwave_pipeline::light_matrices() const {
  const frame_geometry g = geometry();
  if (kind_ == light_kind::spot) {
    const float aspect = static_cast<float>(shadow_size_.x) / static_cast<float>(shadow_size_.y);
    return {glm::perspective(2.0f * spot_light_frustum_half_angle(scene_.lights[0].spot), aspect, g.near_plane, g.far_plane) * g.light_view};
  }
  if (kind_ == light_kind::point) {
    // The cube's faces (vplkit/cube_map.hpp): 90 degrees square each, so that every direction
    // from the light falls in exactly one (cube_face_of), which the main pass looks up.
    std::vector<glm::mat4> faces;
    const glm::vec3 position = light_origin();
    for (int face = 0; face < 6; ++face)
      faces.push_back(glm::perspective(glm::radians(90.0f), 1.0f, g.near_plane, g.far_plane) *
                      glm::lookAt(position, position + cube_face_axis<float>(face), cube_face_up<float>(face)));
    return faces;
  }
  // A sun: parallel rays through a square window of the scene's bounding diameter around its
  // centre, seen from its virtual eye two radii out: the scene lies 1 to 3 radii deep (the RSM's
  // orthographic map, with its margins).
  return {glm::ortho(-g.radius, g.radius, -g.radius, g.radius, 0.5f * g.radius, 3.5f * g.radius) * g.light_view};
}

int lightwave_pipeline::vpl_count() const {
  const bool thesis = settings_.energy == lightwave_energy::thesis;
  if (kind_ == light_kind::point)
    return thesis ? lightwave_sphere_vpl_count(settings_.angle_deg, settings_.per_ray) : lightwave_sphere_sample_count(settings_.angle_deg, settings_.per_ray);
  if (kind_ == light_kind::directional && !thesis) return lightwave_parallel_sample_count(settings_.angle_deg, settings_.per_ray);
  return lightwave_vpl_count(settings_.angle_deg, settings_.per_ray);
}

std::uint64_t lightwave_pipeline::shared_bytes() const {
  std::uint64_t bytes = shared_->mesh_bytes;
  const auto texture_bytes = [](const texture_2d& t) { return static_cast<std::uint64_t>(t.width()) * static_cast<std::uint64_t>(t.height()) * 16u; };
  const std::uint64_t pixels = static_cast<std::uint64_t>(settings_.width) * static_cast<std::uint64_t>(settings_.height);
  const std::uint64_t texel = settings_.format == texel_format::rgba32f ? 16u : 8u;
  // The output image: five colours in the output's format (lightwave.frag's outputs) and a 32-bit depth.
  bytes += pixels * (5u * texel + 4u);
  if (shared_->receiver_buffers) {
    bytes += static_cast<std::uint64_t>(shared_->receivers.vertices.size()) * sizeof(vertex) +
             static_cast<std::uint64_t>(shared_->receivers.indices.size()) * sizeof(std::uint32_t);
    for (const texture_2d& t : shared_->receiver_textures) bytes += texture_bytes(t);
    for (const framebuffer& f : shared_->receiver_sum_targets)
      for (std::size_t k = 0; k < static_cast<std::size_t>(lightwave_sum_receivers); ++k) bytes += texture_bytes(f.colour(k));
  }
  // The surface map: three rgba32f colours and a 32-bit depth.
  if (shared_->surfaces) bytes += static_cast<std::uint64_t>(lightwave_surface_map_size) * lightwave_surface_map_size * (3u * 16u + 4u);
  // The indirect screen buffer: one colour in the output's format and a 32-bit depth.
  if (shared_->indirect_target) bytes += pixels * (texel + 4u);
  return bytes;
}

void lightwave_pipeline::build_vpls() {
  const bounding_box box = bounds(scene_.geometry);
  const frame_geometry g = geometry();
  const glm::vec3 origin = light_origin(), axis = light_axis();
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
        max_distance = std::max(max_distance, glm::length(p - origin));
      }
    // A spot's and a sun's hemispheres (the sun's from its virtual eye outside the scene, along
    // its direction: docs/errata.md, LW-11); a point light's on both sides of it.
    layout_ = {origin, axis, settings_.angle_deg, settings_.per_ray, max_distance};
    if (kind_ == light_kind::point) {
      const int count = lightwave_sphere_vpl_count(settings_.angle_deg, settings_.per_ray);
      for (int index = 0; index < count; ++index) vpls_.push_back(lightwave_sphere_layout_vpl(index, layout_));
    } else {
      lightwave_layout(layout_, std::back_inserter(vpls_));
    }
  } else {
    layout_ = {origin, axis, settings_.angle_deg, settings_.per_ray, 0.0f};
    build_flux_vpls();
    // The receivers sum a ray's samples on one plane as one VPL (a thousandth of the scene's
    // radius: one plane); the shadow casters keep every sample.
    int rays = 0;
    const std::vector<int> ray_of = lightwave_sample_rays(kind_, settings_.angle_deg, settings_.per_ray, flux_layout_index_, rays);
    receiver_vpls_ = lightwave_merge_ray_samples(flux_vpls_, ray_of, rays, 1e-3f * g.radius, &receiver_vpl_of_);
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
  } else if (shared_->receiver_buffers) {
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
  const frame_geometry g = geometry();
  const float aspect = static_cast<float>(shadow_size_.x) / static_cast<float>(shadow_size_.y);
  const lightwave_vpl_view view = view_of(settings_, vpls_, flux_vpls_);
  // Shadow matrices: the light's (a spot's frustum, a point light's six faces, a sun's
  // orthographic window), then each chosen VPL's.
  const float map_far = g.far_plane + layout_.max_distance;
  shadow_matrices_ = light_matrices();
  // The shadow casters: groups by importance (accurate), drawn uniformly (the thesis variant),
  // the fixed ring (integrated). The integrated shadows keep the thesis's maps (along the VPLs'
  // normals, one field of view): their in-between lookups interpolate a fragment's coordinates
  // between two maps, which stands for an in-between light only when the maps share their
  // projection; aimed maps of different fields of view darkened an empty plane (lowest factor
  // 0.72, measured). A point light's integrated maps are placed by importance instead (see
  // integrated_by_importance), still along their VPLs' normals with the one field of view.
  // A flux VPL sits on its surface: its map's eye is lifted off it, so that the surface does not
  // shadow what it lights.
  const auto eye_of = [&](std::size_t i) { return view.position(i) + (view.thesis ? 0.0f : 1e-3f * g.radius) * view.normal(i); };
  const auto along_normal = [&](std::size_t i) {
    return glm::perspective(glm::radians(settings_.vpl_field_of_view), aspect, g.near_plane, map_far) * lightwave_look_along(eye_of(i), view.normal(i));
  };
  if (casters_by_importance() || integrated_by_importance()) {
    const std::vector<lightwave_receiver_point> points =
        lightwave_surface_points(scene_.geometry, casters_follow_camera() ? &scene_.view : nullptr,
                                 static_cast<float>(settings_.width) / static_cast<float>(settings_.height), 4096);
    casters_ = lightwave_importance_casters(view, points, view.flux ? &receiver_vpls_ : nullptr, receiver_vpl_of_, derive(settings_).indirect_maps,
                                            0.25f * g.radius);
    std::vector<float> weights(points.size());
    for (const lightwave_shadow_caster& caster : casters_) {
      const auto i = static_cast<std::size_t>(caster.vpl);
      if (integrated_by_importance()) {
        shadow_matrices_.push_back(along_normal(i));
        continue;
      }
      for (std::size_t k = 0; k < points.size(); ++k) weights[k] = view.weight(i, points[k]);
      shadow_matrices_.push_back(
          lightwave_aimed_shadow_matrix(eye_of(i), view.normal(i), points, weights, g.near_plane, map_far, aspect, settings_.vpl_field_of_view));
    }
  } else {
    const std::vector<int> drawn =
        lightwave_shadow_vpls(technique_.mode, settings_.angle_deg, settings_.per_ray, derive(settings_).indirect_maps, settings_.seed);
    casters_ = lightwave_layout_casters(drawn, view.flux ? &flux_layout_index_ : nullptr);
    for (const lightwave_shadow_caster& caster : casters_) shadow_matrices_.push_back(along_normal(static_cast<std::size_t>(caster.vpl)));
  }
  draw_shadow_layers();
  set_caster_uniforms(view);
  check_gl("building the Light Wave shadow maps");
}

// The depth passes into the layers, one per shadow matrix.
void lightwave_pipeline::draw_shadow_layers() {
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
    shared_->scene_mesh.draw(depth_program_);
  }
  glDisable(GL_POLYGON_OFFSET_FILL);
}

// Each caster's VPL (whether it lights a fragment decides whether its map votes there) and,
// with importance, its group as one light (the share of the fragment's light the map stands for).
void lightwave_pipeline::set_caster_uniforms(const lightwave_vpl_view& view) {
  const program& p = main_program_;
  for (std::size_t i = 0; i < shadow_matrices_.size(); ++i) {
    p.set("shadow_matrix[" + std::to_string(i) + "]", shadow_matrices_[i]);
  }
  for (std::size_t i = 0; i < casters_.size(); ++i) {
    const std::string index = std::to_string(i);
    const auto vpl = static_cast<std::size_t>(casters_[i].vpl);
    p.set("caster_position[" + index + "]", glm::vec4(view.position(vpl), view.thesis ? vpls_[vpl].attenuation : flux_vpls_[vpl].radius));
    p.set("caster_normal[" + index + "]", glm::vec4(view.normal(vpl), 0.0f));
    p.set("group_position_radius[" + index + "]", glm::vec4(casters_[i].position, casters_[i].radius));
    p.set("group_normal_power[" + index + "]", glm::vec4(casters_[i].normal, casters_[i].power));
  }
}

void lightwave_pipeline::rebuild() {
  if (vpls_dirty_ && technique_.mode >= lightwave_mode::unshadowed) {
    timer_.begin("VPLs");
    build_vpls();
    timer_.end();
  } else if (sums_dirty_) {
    // The same VPLs, summed again at the receivers (a clamp changed in place).
    timer_.begin("VPLs");
    sum_at_receivers();
    timer_.end();
  }
  if (shadows_dirty_) {
    timer_.begin("shadow maps");
    build_shadow_maps();
    timer_.end();
  }
  vpls_dirty_ = shadows_dirty_ = sums_dirty_ = false;
  ++rebuilds_;
}

void lightwave_pipeline::set_camera(const camera& view) {
  check_camera(view, "Light Wave scene " + scene_.name);
  scene_.view = view;
  if (casters_follow_camera()) shadows_dirty_ = true;
  view_valid_ = false;
  for (const auto& other : light_pipelines_) other->set_camera(view);
}

lightwave_frame lightwave_pipeline::render() {
  draw();
  lightwave_frame frame;
  frame.radiance = shared_->target.read_image(0);
  frame.indirect_shadow = shared_->target.read_image(1);
  frame.indirect = shared_->target.read_image(2);
  frame.pass_times = collect_pass_times();
  return frame;
}

void lightwave_pipeline::draw() {
  vpls_dirty_ = shadows_dirty_ = true;
  for (const auto& other : light_pipelines_) other->vpls_dirty_ = other->shadows_dirty_ = true;
  draw_changed();
}

void lightwave_pipeline::draw_changed() {
  // What a move invalidated, light by light; then, when anything changed, every light's main pass
  // into the shared image: the first clears it, each further one adds its light (the sum starts
  // from the first light's image, so an unchanged light is drawn again, from its cached VPLs,
  // shadow maps and receivers' sums).
  bool redraw = !view_valid_;
  if (vpls_dirty_ || shadows_dirty_) {
    rebuild();
    redraw = true;
  }
  for (const auto& other : light_pipelines_) {
    if (other->vpls_dirty_ || other->shadows_dirty_) {
      other->rebuild();
      redraw = true;
    }
    redraw = redraw || !other->view_valid_;
  }
  if (!redraw) return;
  draw_main_pass(true);
  for (const auto& other : light_pipelines_) other->draw_main_pass(false);
  if (emission_) {
    timer_.begin("emission");
    emission_->draw(shared_->scene_mesh, camera_view_projection(), scene_.view.position, shared_->target.colour(0), shared_->target.depth());
    timer_.end();
  }
}

std::vector<pass_time> lightwave_pipeline::collect_pass_times() {
  // Light by light, each light's passes in the order they ran.
  std::vector<pass_time> times;
  for (pass_time& t : timer_.collect()) {
    t.pass = pass_prefix_ + t.pass;
    times.push_back(std::move(t));
  }
  for (const auto& other : light_pipelines_)
    for (pass_time& t : other->collect_pass_times()) times.push_back(std::move(t));
  return times;
}

void lightwave_pipeline::draw_main_pass(bool first) {
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  if (shared_->indirect_target) {
    timer_.begin("indirect buffer");
    // Flux energy: the receivers' indirect light into the screen buffer the main pass reads.
    shared_->indirect_target->bind();
    glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    set_vertex_uniforms(indirect_program_);
    indirect_program_.use();
    // The shared receivers carry this light's sums.
    shared_->receiver_buffers->attach_vec4_attribute(3, indirect_buffer_.get());
    shared_->receiver_buffers->draw(indirect_program_);
    main_program_.set("indirect_buffer", 2);
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D, shared_->indirect_target->colour(0).id());
    timer_.end();
  }
  timer_.begin("main pass");
  shared_->target.bind();
  if (first) {
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    const GLfloat unshadowed[4] = {1.0f, 0.0f, 0.0f, 1.0f};  // the factor where no surface is
    glClearBufferfv(GL_COLOR, 1, unshadowed);
  } else {
    // A further light adds its light: every output of the main pass is linear in the light
    // (direct x shadow + indirect, no emission or ambient term), so the sum is the image of all
    // lights. The alpha stays the first light's 1; the indirect shadow factor, a ratio, not a
    // light, stays the first light's.
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE);
    glColorMaski(1, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  }
  set_vertex_uniforms(main_program_);
  main_program_.set("shadow_maps", 1);
  const scene_light& light = scene_.lights[0];
  if (kind_ == light_kind::point) set_uniforms(main_program_, "light", light.point);
  else if (kind_ == light_kind::directional) set_uniforms(main_program_, "light", light.directional);
  else set_uniforms(main_program_, "light", light.spot);
  main_program_.set("light_layers", light_layers_);
  // A spot's map has the screen's aspect and square texels; a point light's faces and a sun's
  // window are square frusta on the same maps: their texels are as wide as the map's shorter side allows.
  main_program_.set("light_map_width", kind_ == light_kind::spot ? shadow_size_.x : std::min(shadow_size_.x, shadow_size_.y));
  set_uniforms(main_program_, "irradiance", settings_.irradiance);
  main_program_.set("indirect_maps", static_cast<int>(casters_.size()));
  main_program_.set("integrated_steps", settings_.integrated_steps);
  main_program_.set("integrated_pair_cos", integrated_by_importance() ? lightwave_integrated_pair_cos : -2.0f);
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
  if (!first) {
    // The first light's pass laid the depth of the visible surface: only it adds light (the same
    // positions to the bit in every program that draws the mesh: invariant gl_Position).
    glDepthFunc(GL_EQUAL);
    glDepthMask(GL_FALSE);
    main_program_.use();
  } else if (depth_prepass()) {
    // The shadowed pass's fragments are the costly part of the frame: a depth pre-pass first, so
    // that only the visible one of each pixel runs them (its shader has no discard, so its depth
    // is tested before it runs; the pre-pass did the alpha test).
    depth_program_.use();
    depth_program_.set("view_projection", camera_view_projection());
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    shared_->scene_mesh.draw(depth_program_);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthFunc(GL_EQUAL);
    glDepthMask(GL_FALSE);
    main_program_.use();
  }
  shared_->scene_mesh.draw(main_program_);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  if (!first) {
    glColorMaski(1, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_BLEND);
  }
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
  shared_->target.bind();
  capture_program_.use();
  glEnable(GL_RASTERIZER_DISCARD);
  glBeginTransformFeedback(GL_POINTS);
  vertices.draw_points();
  glEndTransformFeedback();
  glDisable(GL_RASTERIZER_DISCARD);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
  check_gl("capturing the Light Wave vertex stage");
}

std::vector<glm::vec3> lightwave_pipeline::capture_vertex_indirect() {
  if (settings_.energy == lightwave_energy::flux && !shared_->receiver_buffers)
    throw error(std::string("Light Wave technique ") + technique_.name + " sums no VPLs: no vertex indirect light to capture");
  if (vpls_dirty_ || shadows_dirty_) {
    rebuild();
    timer_.collect();  // not a frame's passes
  }
  // Flux energy: the buffer the main pass reads, captured at the last build.
  const std::size_t count = shared_->receiver_buffers ? shared_->receivers.vertices.size() : scene_.geometry.vertices.size();
  gl_buffer captured(generate_buffer());
  if (!shared_->receiver_buffers) {
    glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, captured.get());
    glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER, static_cast<GLsizeiptr>(count * sizeof(glm::vec3)), nullptr, GL_STATIC_READ);
    capture_into(captured.get(), shared_->scene_mesh);
  }
  std::vector<glm::vec3> result(count);
  if (shared_->receiver_buffers) {
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
