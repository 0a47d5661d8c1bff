#include "frontend/techniques/rsm/rsm_pipeline.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <initializer_list>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>

#include <vplkit/cube_map.hpp>
#include <vplkit/hash.hpp>
#include <vplkit/gl/settings_uniforms.hpp>

#include "frontend/gl/debug_output.hpp"
#include "frontend/core/error.hpp"

namespace vplkit {

namespace {

// Light `index` of `source`, refused with the reason when the RSM pipeline cannot draw it.
const scene_light& rsm_light(const scene& source, std::size_t index) {
  if (source.lights.empty()) throw error("scene " + source.name + ": the RSM pipeline needs a light, the scene has none");
  if (index >= source.lights.size())
    throw error("scene " + source.name + ": no light " + std::to_string(index) + " (it has " + std::to_string(source.lights.size()) + ")");
  return source.lights[index];
}

}  // namespace

light_frustum make_light_frustum(const scene& source, int rsm_size, std::size_t light, int face) {
  return make_light_frustum(source, bounds(source.geometry), rsm_size, light, face);
}

light_frustum make_light_frustum(const scene& source, const bounding_box& box, int rsm_size, std::size_t light_index, int face) {
  light_frustum frustum;
  const float radius = std::max(box.radius(), 1e-3f);
  const scene_light& primary = rsm_light(source, light_index);
  if (primary.kind == light_kind::point) {
    if (face < 0 || face > 5) throw error("scene " + source.name + ", light " + std::to_string(light_index) + ": no cube face " + std::to_string(face));
    // One face of the cube: 90 degrees around its axis, OpenGL's orientation (vplkit/cube_map.hpp).
    const glm::vec3 position = primary.point.position;
    frustum.view = glm::lookAt(position, position + cube_face_axis<float>(face), cube_face_up<float>(face));
    frustum.tan_half_fov = 1.0f;
    const float far_plane = glm::length(position - box.centre()) + 2.0f * radius;
    frustum.view_projection = glm::perspective(glm::radians(90.0f), 1.0f, 0.01f * radius, far_plane) * frustum.view;
  } else if (primary.kind == light_kind::spot) {
    const spot_light<float>& light = primary.spot;
    const glm::vec3 up = std::abs(light.direction.y) > 0.99f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
    frustum.view = glm::lookAt(light.position, light.position + light.direction, up);
    const float half_angle = spot_light_frustum_half_angle(light);
    frustum.tan_half_fov = std::tan(half_angle);
    const float far_plane = glm::length(light.position - box.centre()) + 2.0f * radius;
    frustum.view_projection = glm::perspective(2.0f * half_angle, 1.0f, 0.01f * radius, far_plane) * frustum.view;
  } else {
    const glm::vec3 direction = primary.directional.direction;
    const glm::vec3 up = std::abs(direction.y) > 0.99f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
    frustum.view = glm::lookAt(box.centre() - 2.0f * radius * direction, box.centre(), up);
    frustum.view_projection = glm::ortho(-radius, radius, -radius, radius, 0.5f * radius, 3.5f * radius) * frustum.view;
    frustum.half_extent = radius;
    const float texel = 2.0f * radius / static_cast<float>(rsm_size);
    frustum.texel_area = texel * texel;
  }
  return frustum;
}

rsm_frame_constants make_frame_constants(const scene& source, const rsm_pipeline_settings& settings, std::size_t light, int face) {
  return make_frame_constants(source, bounds(source.geometry), source.geometry.triangle_count(), settings, light, face);
}

rsm_frame_constants make_frame_constants(const scene& source, const bounding_box& box, std::size_t triangles, const rsm_pipeline_settings& settings,
                                         std::size_t light, int face) {
  if (const std::string problem = validate(settings); !problem.empty()) throw error("RSM pipeline settings: " + problem);
  const scene_light& primary = rsm_light(source, light);
  check_light(primary, "scene " + source.name + ", light " + std::to_string(light));
  if (triangles == 0) throw error("scene " + source.name + " has no triangles");
  rsm_frame_constants constants;
  constants.technique = find_rsm_technique(settings.technique);
  constants.light = make_light_frustum(source, box, settings.rsm_size, light, face);
  constants.primary = primary;
  constants.light_index = light;
  constants.face = primary.kind == light_kind::point ? face : -1;
  constants.gather = derive(settings).gather;
  const bool spot = primary.kind != light_kind::directional;  // a spot or a point light's face: perspective
  constants.gather.perspective = spot ? 1 : 0;
  constants.light_view_inverse = glm::inverse(constants.light.view);
  constants.voxel_march = settings.voxel_march;
  constants.unprojection = make_rsm_unprojection(spot ? constants.light.tan_half_fov : constants.light.half_extent, spot, glm::ivec2(settings.rsm_size));
  constants.camera_view = camera_view_matrix(source.view);
  constants.camera_view_projection =
      camera_projection_matrix(source.view, static_cast<float>(settings.width) / static_cast<float>(settings.height)) * constants.camera_view;
  constants.shadow = settings.shadow;
  constants.bilateral = settings.bilateral;
  constants.filter = settings.filter;
  constants.temporal = settings.temporal;
  constants.image_size = glm::ivec2(settings.width, settings.height);
  constants.indirect_divisor = settings.indirect_divisor;
  constants.indirect_size = (constants.image_size + settings.indirect_divisor - 1) / settings.indirect_divisor;
  return constants;
}

std::vector<rsm_frame_constants> make_view_constants(const scene& source, const bounding_box& box, std::size_t triangles,
                                                     const rsm_pipeline_settings& settings) {
  if (source.lights.empty()) {
    // No light (--lights none): one view of a sun of zero irradiance. Its RSM's flux, the gather
    // and the direct light are all 0, so the frame is the scene unlit, drawn by the same passes.
    scene_light dark;
    dark.kind = light_kind::directional;
    dark.directional.irradiance = glm::vec3(0.0f);
    const scene unlit{source.name, mesh{}, source.view, {dark}, {}, {}};
    return {make_frame_constants(unlit, box, triangles, settings, 0, 0)};
  }
  check_lights(source.lights, "scene " + source.name);
  std::vector<rsm_frame_constants> views;
  for (std::size_t k = 0; k < source.lights.size(); ++k) {
    const int faces = source.lights[k].kind == light_kind::point ? 6 : 1;
    for (int face = 0; face < faces; ++face) views.push_back(make_frame_constants(source, box, triangles, settings, k, face));
  }
  return views;
}

std::optional<coarse_cube_views> coarse_cube_of(const std::vector<rsm_frame_constants>& views, std::size_t view) {
  const rsm_frame_constants& here = views.at(view);
  if (!(here.technique.indirect && here.gather.coverage_blocks > 0) || !judges_coarse_lights_by_segment(here.technique.visibility) || here.face < 0)
    return std::nullopt;
  coarse_cube_views cube;
  // Points in the gathering face's eye space: to the cube's (world) axes by the inverse view's
  // rotation (transform_direction); each face's eye space from there is the kernel's
  // cube_face_eye, the convention make_light_frustum renders the faces with.
  cube.frames.cube_from_light = glm::inverse(here.light.view);
  std::array<bool, 6> found{};
  for (std::size_t v = 0; v < views.size(); ++v)
    if (views[v].light_index == here.light_index && views[v].face >= 0 && views[v].face < 6) {
      const std::size_t g = static_cast<std::size_t>(views[v].face);
      found[g] = true;
      cube.view_of_face[g] = v;
    }
  for (bool present : found)
    if (!present) return std::nullopt;
  return cube;
}

namespace {

const char* flag(bool value) { return value ? "1" : "0"; }


// Whether the frame reduces the RSM to coarse lights: a gathering technique with coverage.
bool with_coverage(const rsm_frame_constants& constants) { return constants.technique.indirect && constants.gather.coverage_blocks > 0; }

// Whether the gather marches the scene's voxel grid (rsm-voxel).
bool with_voxels(const rsm_frame_constants& constants) { return constants.technique.indirect && constants.technique.visibility == rsm_visibility::voxel; }

// The gather's texture unit of the voxel grid: after the RSM, the G-buffer and the coarse lights.
int voxel_unit(const rsm_frame_constants& constants) { return with_coverage(constants) ? 6 : 3; }

// The conservative occupancy grid of every triangle of `geometry` (vplkit/voxel_visibility.hpp).
voxel_grid build_voxel_grid(const mesh& geometry, const bounding_box& box, const voxel_grid_settings<float>& settings) {
  voxel_grid grid = make_voxel_grid(make_voxel_grid_shape(box.minimum, box.maximum, settings));
  for (std::size_t i = 0; i + 2 < geometry.indices.size(); i += 3)
    voxel_grid_add_triangle(grid, geometry.vertices[geometry.indices[i]].position, geometry.vertices[geometry.indices[i + 1]].position,
                            geometry.vertices[geometry.indices[i + 2]].position);
  return grid;
}

// Whether sequences accumulate: a gathering technique with a blend below 1.
bool with_temporal(const rsm_frame_constants& constants) { return constants.technique.indirect && constants.temporal.blend < 1.0f; }

// Whether this context's GLSL 3.30 has packHalf2x16 (GL_ARB_shading_language_packing, core in 4.2).
bool has_half_packing() {
  GLint count = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i) {
    const char* name = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, static_cast<GLuint>(i)));
    if (name && std::strcmp(name, "GL_ARB_shading_language_packing") == 0) return true;
  }
  return false;
}

// The separable filter's x pass writes the y pass's taps packed as halves into an RGBA32UI target
// (blur_x.frag): one fetch per tap in the y pass instead of two. Exact only where the buffers are
// rgba16f; with rgba32f, or without half packing, the x pass writes floats as the indirect buffer.
// (Chosen when the target is made; the programs and the read-back follow the target's format.)
bool packed_blur(const rsm_pipeline_settings& settings) {
  return settings.filter == post_filter::separable && settings.format == texel_format::rgba16f && has_half_packing();
}

// The separable filter's y pass for the 2 x 2 pixels of each indirect texel at once (blur_y.frag),
// where the indirect buffer is half resolution: the four share the texel's taps. The same values
// as post.frag's y pass per pixel, a quarter of its tap fetches.
bool quad_blur(const rsm_pipeline_settings& settings) { return settings.filter == post_filter::separable && settings.indirect_divisor == 2; }

// The uniforms the post filter's passes share (blur_x.frag, blur_y.frag, post.frag): the
// bilateral settings where the pass filters, the buffers' sizes, and its samplers' units in the
// order given.
void set_filter_uniforms(const program& target, const rsm_frame_constants& constants, bool filters, std::initializer_list<const char*> samplers) {
  if (filters) set_uniforms(target, "bilateral", constants.bilateral);
  target.set("indirect_divisor", constants.indirect_divisor);
  target.set("indirect_size", constants.indirect_size);
  target.set("gbuffer_size", constants.image_size);
  int unit = 0;
  for (const char* name : samplers) target.set(name, unit++);
}

void set_light_uniforms(const program& target, const rsm_frame_constants& constants) {
  if (constants.primary.kind == light_kind::spot) set_uniforms(target, "spot", constants.primary.spot);
  else if (constants.primary.kind == light_kind::directional) set_uniforms(target, "directional", constants.primary.directional);
  else set_uniforms(target, "point", constants.primary.point);
}

}  // namespace

rsm_pipeline::rsm_pipeline(const shader_library& shaders, const scene& source, const rsm_pipeline_settings& settings)
    : scene_{source.name, mesh{}, source.view, source.lights, source.notes, {}},
      bounds_(bounds(source.geometry)),
      triangles_(source.geometry.triangle_count()),
      settings_(settings),
      views_(make_view_constants(source, bounds_, triangles_, settings)),
      constants_(views_.front()),
      mesh_(source.geometry),
      gbuffer_program_(load_program(shaders, "scene.vert", "gbuffer.frag")),
      gbuffer_target_(settings.width, settings.height, {settings.format, settings.format, settings.format}, true),
      history_targets_{framebuffer(with_temporal(constants_) ? constants_.indirect_size.x : 1, with_temporal(constants_) ? constants_.indirect_size.y : 1,
                                   {settings.format}, false),
                       framebuffer(with_temporal(constants_) ? constants_.indirect_size.x : 1, with_temporal(constants_) ? constants_.indirect_size.y : 1,
                                   {settings.format}, false)},
      blur_x_target_(settings.filter == post_filter::separable ? constants_.indirect_size.x : 1,
                     settings.filter == post_filter::separable ? constants_.indirect_size.y : 1,
                     {packed_blur(settings) ? texel_format::rgba32ui : settings.format}, false),
      blur_y_target_(quad_blur(settings) ? constants_.indirect_size.x : 1, quad_blur(settings) ? constants_.indirect_size.y : 1,
                     {texel_format::rgba32f, texel_format::rgba32f, texel_format::rgba32f}, false),
      post_target_(settings.width, settings.height, {settings.format, settings.format, settings.format}, false),
      empty_vertex_array_(generate_vertex_array()) {
  // Each light has its own RSM (cached while it does not move), coverage lights and gather output.
  for (std::size_t k = 0; k < views_.size(); ++k) {
    rsm_targets_.emplace_back(settings.rsm_size, settings.rsm_size, std::vector<texel_format>{texel_format::rgba32ui}, true);
    coarse_targets_.emplace_back(std::max(constants_.gather.coverage_blocks, 1), std::max(constants_.gather.coverage_blocks, 1),
                                 std::vector<texel_format>{texel_format::rgba32f, texel_format::rgba32f, texel_format::rgba32f}, false);
    indirect_targets_.emplace_back(constants_.indirect_size.x, constants_.indirect_size.y, std::vector<texel_format>{settings.format}, false);
  }
  rsm_valid_.assign(views_.size(), 0);
  for (std::size_t k = 0; k < views_.size(); ++k) {
    if (views_[k].face != 0 || !coarse_cube_of(views_, k)) continue;
    const std::size_t light = views_[k].light_index;
    if (cube_depths_.size() <= light) cube_depths_.resize(light + 1);
    cube_depths_[light] = gl_texture(generate_texture());
    glBindTexture(GL_TEXTURE_2D_ARRAY, cube_depths_[light].get());
    glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_R32UI, settings.rsm_size, settings.rsm_size, 6, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
    // Integer textures are complete only with nearest filtering (texelFetch reads level 0).
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, 0);
    check_gl("allocating light " + std::to_string(light) + "'s six cube face depths of " + std::to_string(settings.rsm_size) + "^2");
  }
  if (with_voxels(constants_)) {
    // Built once: a pipeline's triangles are fixed for its life (a new scene is a new pipeline).
    const auto start = std::chrono::steady_clock::now();
    voxels_ = std::make_shared<const voxel_grid>(build_voxel_grid(source.geometry, bounds_, settings_.voxel_grid));
    voxel_build_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const glm::ivec2 size = voxel_texture_size(voxels_->shape.cells);
    voxel_texture_.emplace(size.x, size.y, texel_format::rgba32ui, voxels_->texels.data());
  }
  if (has_emission(source.geometry)) emission_.emplace(shaders);
  load_programs(shaders);
  set_settings_uniforms();
  set_pose_uniforms();
  check_gl("setting up the RSM pipeline");
}

void rsm_pipeline::load_programs(const shader_library& shaders) {
  const rsm_technique& technique = constants_.technique;
  const bool separable = settings_.filter == post_filter::separable;
  const bool packed = separable && blur_x_target_.colour(0).format() == texel_format::rgba32ui;
  if (technique.indirect) {
    gather_program_ = load_program(shaders, "fullscreen.vert", "gather.frag",
                                   {{"VPLKIT_RSM_PATTERN", std::to_string(static_cast<int>(technique.pattern))},
                                    {"VPLKIT_VISIBILITY", std::to_string(static_cast<int>(technique.visibility))},
                                    {"VPLKIT_SLOT_COUNT", std::to_string(constants_.gather.slots.count)},
                                    {"VPLKIT_RSM_COVERAGE", flag(with_coverage(constants_))}});
    if (with_coverage(constants_)) coarse_program_ = load_program(shaders, "fullscreen.vert", "rsm_coarse.frag");
    if (with_temporal(constants_)) temporal_program_ = load_program(shaders, "fullscreen.vert", "temporal.frag");
    if (separable) blur_x_program_ = load_program(shaders, "fullscreen.vert", "blur_x.frag", {{"VPLKIT_PACKED_BLUR", flag(packed)}});
    if (quad_blur(settings_)) blur_y_program_ = load_program(shaders, "fullscreen.vert", "blur_y.frag", {{"VPLKIT_PACKED_BLUR", flag(packed)}});
  }
  // The light-dependent programs for the kinds the scene's lights have (set_light keeps a light's kind).
  for (const rsm_frame_constants& view : views_) {
    const auto slot = static_cast<std::size_t>(view.primary.kind);
    if (rsm_programs_[slot].id() != 0) continue;
    const bool directional = view.primary.kind == light_kind::directional, point = view.primary.kind == light_kind::point;
    rsm_programs_[slot] = load_program(shaders, "scene.vert", "rsm.frag", {{"VPLKIT_LIGHT_DIRECTIONAL", flag(directional)}, {"VPLKIT_LIGHT_POINT", flag(point)}});
    post_programs_[slot] = load_program(shaders, "fullscreen.vert", "post.frag",
                                        {{"VPLKIT_INDIRECT", flag(technique.indirect)},
                                         {"VPLKIT_SEPARABLE", flag(separable)},
                                         {"VPLKIT_PACKED_BLUR", flag(technique.indirect && packed)},
                                         {"VPLKIT_QUAD_BLUR", flag(technique.indirect && quad_blur(settings_))},
                                         {"VPLKIT_LIGHT_DIRECTIONAL", flag(directional)},
                                         {"VPLKIT_LIGHT_POINT", flag(point)}});
  }

}

// The uniforms that come from the settings (the constructor's, and apply_settings's); the pose's
// are set by set_pose_uniforms.
void rsm_pipeline::set_settings_uniforms() {
  const rsm_technique& technique = constants_.technique;
  const bool separable = settings_.filter == post_filter::separable;
  rsm_program().set("rsm_size", glm::ivec2(settings_.rsm_size));
  gbuffer_program_.set("rsm_size", glm::ivec2(settings_.rsm_size));
  set_uniforms(gbuffer_program_, "shadow", constants_.shadow);
  gbuffer_program_.set("rsm_packed", 0);

  if (technique.indirect) {
    set_uniforms(gather_program_, "settings", constants_.gather);
    gather_program_.set("indirect_divisor", constants_.indirect_divisor);
    gather_program_.set("gbuffer_size", constants_.image_size);
    int unit = 0;
    for (const char* name : {"rsm_packed", "gbuffer_position_depth", "gbuffer_normal"}) gather_program_.set(name, unit++);
    if (with_coverage(constants_)) {
      for (const char* name : {"coarse_position_extent", "coarse_normal", "coarse_flux"}) gather_program_.set(name, unit++);
      coarse_program_.set("rsm_size", glm::ivec2(settings_.rsm_size));
      coarse_program_.set("coverage_blocks", constants_.gather.coverage_blocks);
      coarse_program_.set("rsm_packed", 0);
      // Unit 8 also when no cube is bound there (a spot's or a sun's view): a usampler2DArray left
      // on unit 0 beside rsm_packed's usampler2D makes every draw an invalid operation.
      if (judges_coarse_lights_by_segment(technique.visibility)) gather_program_.set("rsm_face_depths", 8);
    }
    if (with_voxels(constants_)) {
      gather_program_.set("voxel_packed", voxel_unit(constants_));
      set_uniforms(gather_program_, "voxel_shape", voxels_->shape);
      set_uniforms(gather_program_, "voxel_march", constants_.voxel_march);
    }
    if (with_temporal(constants_)) {
      set_uniforms(temporal_program_, "temporal", constants_.temporal);
      temporal_program_.set("indirect_divisor", constants_.indirect_divisor);
      temporal_program_.set("indirect_size", constants_.indirect_size);
      temporal_program_.set("gbuffer_size", constants_.image_size);
      int temporal_unit = 0;
      for (const char* name : {"indirect_buffer", "history_buffer", "gbuffer_position_depth"}) temporal_program_.set(name, temporal_unit++);
    }
    if (separable) set_filter_uniforms(blur_x_program_, constants_, true, {"indirect_buffer", "gbuffer_normal"});
    if (quad_blur(settings_)) set_filter_uniforms(blur_y_program_, constants_, true, {"indirect_buffer", "gbuffer_position_depth", "gbuffer_normal"});
  }
  const bool quad = technique.indirect && quad_blur(settings_);
  set_uniforms(post_program(), "irradiance", constants_.gather.irradiance);
  // Unit 0: the y pass's taps (blur_taps.glsl), or with the quad y pass (which filtered: the
  // shading pass does not) its planes at units 0, 4, 5.
  if (quad)
    set_filter_uniforms(post_program(), constants_, false,
                        {"filtered_red", "gbuffer_position_depth", "gbuffer_albedo_density", "gbuffer_normal", "filtered_green", "filtered_blue"});
  else
    set_filter_uniforms(post_program(), constants_, true, {"indirect_buffer", "gbuffer_position_depth", "gbuffer_albedo_density", "gbuffer_normal"});
}

bool rsm_pipeline::apply_settings(const technique_settings& settings) {
  const auto* typed = dynamic_cast<const described_settings<rsm_pipeline_settings, rsm_technique>*>(&settings);
  if (!typed) return false;
  const rsm_pipeline_settings& next = typed->value();
  // Another technique, or a setting that sets a define or sizes what the constructor builds (the
  // table says which: setting::defines, setting::builds), needs a new pipeline.
  if (!validate(next).empty() || next.technique != settings_.technique || !rebuilding_changes(rsm_settings_table(), settings_, next).empty()) return false;
  const std::vector<rsm_frame_constants> views = make_view_constants(scene_, bounds_, triangles_, next);
  settings_ = next;
  views_ = views;
  pattern_frame_ = 0;
  bind_view(0);
  check_gl("applying the RSM pipeline's settings");
  // The G-buffer to the post filter again, and no history from the old settings. The RSM and the
  // coverage's coarse lights depend on the light, the RSM's size and the blocks only, which a
  // change in place keeps.
  view_valid_ = false;
  history_valid_ = false;
  sequence_frame_ = 0;
  return true;
}

void rsm_pipeline::set_pose_uniforms() {
  const light_frustum& light = constants_.light;
  rsm_program().set("view_projection", light.view_projection);
  rsm_program().set("light_view", light.view);
  rsm_program().set("tan_half_fov", light.tan_half_fov);
  rsm_program().set("texel_area", light.texel_area);
  set_light_uniforms(rsm_program(), constants_);
  gbuffer_program_.set("view_projection", constants_.camera_view_projection);
  gbuffer_program_.set("camera_view", constants_.camera_view);
  gbuffer_program_.set("light_view", light.view);
  gbuffer_program_.set("light_view_projection", light.view_projection);
  if (with_coverage(constants_)) set_uniforms(coarse_program_, "unprojection", constants_.unprojection);
  gbuffer_program_.set("light_projection", light.view_projection * glm::inverse(light.view));
  if (constants_.technique.indirect) {
    set_uniforms(gather_program_, "unprojection", constants_.unprojection);
    gather_program_.set("light_view", light.view);
    gather_program_.set("light_view_projection", light.view_projection);
    if (with_voxels(constants_)) gather_program_.set("voxel_from_light", voxel_cells_from(voxels_->shape, constants_.light_view_inverse));
  }
  set_light_uniforms(post_program(), constants_);
  if (constants_.face >= 0) post_program().set("light_face", constants_.face);
}

void rsm_pipeline::move_to(const camera& view, const std::vector<scene_light>& lights) {
  const camera previous_view = scene_.view;
  const std::vector<scene_light> previous_lights = scene_.lights;
  scene_.view = view;
  scene_.lights = lights;
  try {
    views_ = make_view_constants(scene_, bounds_, triangles_, settings_);
  } catch (...) {
    scene_.view = previous_view;
    scene_.lights = previous_lights;
    throw;
  }
  bind_view(0);
}

std::string rsm_pipeline::pass_name(const char* pass, std::size_t view) const {
  // With one view, the name it always had; else the light, and a point light's face, so that
  // render --stats shows the time per light.
  if (views_.size() == 1) return pass;
  const rsm_frame_constants& drawn = views_[view];
  return std::string(pass) + " light " + std::to_string(drawn.light_index) + (drawn.face >= 0 ? " face " + std::to_string(drawn.face) : "");
}

void rsm_pipeline::bind_view(std::size_t view) {
  constants_ = views_.at(view);
  set_settings_uniforms();
  if (constants_.technique.indirect) set_pattern_frame(pattern_frame_);
  set_pose_uniforms();
}

void rsm_pipeline::set_camera(const camera& view) {
  check_camera(view, "scene " + scene_.name);
  move_to(view, scene_.lights);
  view_valid_ = false;
}

void rsm_pipeline::set_light(std::size_t index, const scene_light& light) {
  if (index >= scene_.lights.size())
    throw error("scene " + scene_.name + ": no light " + std::to_string(index) + " (it has " + std::to_string(scene_.lights.size()) + ")");
  const light_kind built_for = scene_.lights[index].kind;
  if (light.kind != built_for)
    throw error("scene " + scene_.name + ": the RSM pipeline was built for a " + light_kind_name(built_for) + " light " + std::to_string(index) +
                "; make a new pipeline for another kind");
  check_light(light, "scene " + scene_.name);
  std::vector<scene_light> moved = scene_.lights;
  moved[index] = light;
  move_to(scene_.view, moved);
  for (std::size_t v = 0; v < views_.size(); ++v)
    if (views_[v].light_index == index) rsm_valid_[v] = 0;  // the other lights' RSMs stay valid
  view_valid_ = false;
}

rsm_frame rsm_pipeline::render() {
  draw();
  rsm_frame frame;
  frame.radiance = post_target_.read_image(0);
  frame.indirect = post_target_.read_image(1);
  frame.pass_times = timer_.collect();
  return frame;
}

bool rsm_pipeline::accumulates() const { return with_temporal(constants_); }

void rsm_pipeline::set_pattern_frame(std::uint32_t frame) {
  pattern_frame_ = frame;
  rsm_gather_settings<float> gather = constants_.gather;
  if (frame > 0) {
    gather.radial.seed = hash_combine(gather.radial.seed, frame);
    gather.disk.seed = hash_combine(gather.disk.seed, frame);
  }
  set_uniforms(gather_program_, "settings", gather);
}

void rsm_pipeline::draw_next() {
  if (!accumulates()) return draw();
  // Temporal accumulation keeps one history of one gather; several views would need one each.
  if (views_.size() > 1)
    throw error("scene " + scene_.name + ": temporal accumulation (temporal blend < 1) draws one spot or sun, the scene has " +
                std::to_string(views_.size()) + " light views (choose one spot or sun with --lights k, or --temporal-blend 1)");
  set_pattern_frame(sequence_frame_);
  draw_passes(true, true);
  ++sequence_frame_;
}

rsm_frame rsm_pipeline::render_next() {
  draw_next();
  rsm_frame frame;
  frame.radiance = post_target_.read_image(0);
  frame.indirect = post_target_.read_image(1);
  frame.pass_times = timer_.collect();
  return frame;
}

void rsm_pipeline::draw() { draw_passes(true); }

void rsm_pipeline::draw_changed() {
  const bool rsms_valid = std::all_of(rsm_valid_.begin(), rsm_valid_.end(), [](char valid) { return valid != 0; });
  if (!rsms_valid || !view_valid_) draw_passes(false);  // redraws the RSMs of the lights that moved
}

void rsm_pipeline::draw_passes(bool all_rsms, bool accumulate) {
  const rsm_technique& technique = constants_.technique;
  if (!accumulate && (history_valid_ || sequence_frame_ > 0)) {
    // A frame outside a sequence: no history, and the settings' own pattern.
    history_valid_ = false;
    sequence_frame_ = 0;
    pattern_frame_ = 0;
  }
  last_accumulated_ = accumulate;
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);  // depth 0 marks "no surface" in every buffer
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);

  // The passes once per light view (a spot or sun: one; a point light: six cube faces), each with
  // its own RSM, shadow density and gather; the post pass of every view after the first adds its
  // radiance and filtered indirect light to the ones before (the filter is linear in its input
  // for the fixed G-buffer guides, so the sum of the filtered images is the filtered sum). One
  // spot or sun draws exactly what it always drew.
  // Every RSM first: a point light's gather reads all six of its faces' depths (coarse_cube_of).
  for (std::size_t k = 0; k < views_.size(); ++k) {
    if (!(all_rsms || !rsm_valid_[k])) continue;
    bind_view(k);
    glEnable(GL_DEPTH_TEST);
    draw_rsm(k);
  }
  for (std::size_t k = 0; k < views_.size(); ++k) {  // k: the light view
    bind_view(k);
    glEnable(GL_DEPTH_TEST);
    draw_gbuffer(k);
    glDisable(GL_DEPTH_TEST);
    glBindVertexArray(empty_vertex_array_.get());
    if (technique.indirect) draw_gather(k);
    // The filter's input: the gather, or (sequences, one light) the gather accumulated over the frames.
    draw_post(accumulate ? accumulate_history() : indirect_targets_[k], k);
    glBindVertexArray(0);
  }
  if (emission_) {
    // Onto the sum of the views, on the G-buffer's depth of the view (every view's is the same).
    timer_.begin("emission");
    emission_->draw(mesh_, constants_.camera_view_projection, scene_.view.position, post_target_.colour(0), gbuffer_target_.depth());
    timer_.end();
  }
  check_gl("rendering scene " + scene_.name + " with " + technique.name);
  view_valid_ = true;
  ++view_draws_;
}

// Pass 1, and the coverage's coarse lights from it.
void rsm_pipeline::draw_rsm(std::size_t view) {
  const framebuffer& rsm_target = rsm_targets_[view];
  timer_.begin(pass_name("RSM generation", view));
  rsm_target.bind();
  const GLuint empty_texel[4] = {0, 0, 0, 0};  // glClear's float colour is undefined for an integer target
  glClearBufferuiv(GL_COLOR, 0, empty_texel);
  glClear(GL_DEPTH_BUFFER_BIT);
  mesh_.draw(rsm_program());
  timer_.end();
  if (with_coverage(constants_)) {
    timer_.begin(pass_name("coverage lights", view));
    glDisable(GL_DEPTH_TEST);
    glBindVertexArray(empty_vertex_array_.get());
    coarse_targets_[view].bind();
    rsm_target.colour(0).bind(0);
    coarse_program_.use();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glEnable(GL_DEPTH_TEST);
    const rsm_frame_constants& drawn = views_[view];
    if (drawn.face >= 0 && drawn.light_index < cube_depths_.size() && cube_depths_[drawn.light_index].get() != 0) {
      // The face's depths into its layer of the light's cube (the RSM's first word: R32UI keeps
      // the bits), for the coarse lights' visibility of every face's gather.
      rsm_target.bind_for_reading(0);
      glBindTexture(GL_TEXTURE_2D_ARRAY, cube_depths_[drawn.light_index].get());
      glCopyTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, drawn.face, 0, 0, rsm_target.width(), rsm_target.height());
    }
    timer_.end();
  }
  rsm_valid_[view] = 1;
  ++rsm_draws_;
}

// Pass 2.
// With several views the G-buffer is drawn per view: its shadow density (Alg. 4) is the view's.
void rsm_pipeline::draw_gbuffer(std::size_t view) {
  timer_.begin(pass_name("G-buffer generation", view));
  gbuffer_target_.bind();
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  rsm_targets_[view].colour(0).bind(0);
  mesh_.draw(gbuffer_program_);
  timer_.end();
}

// Pass 3: the gather at the indirect buffer's receivers.
void rsm_pipeline::draw_gather(std::size_t view) {
  timer_.begin(pass_name("RSM sampling", view));
  indirect_targets_[view].bind();
  rsm_targets_[view].colour(0).bind(0);
  gbuffer_target_.colour(0).bind(1);
  gbuffer_target_.colour(2).bind(2);
  if (with_coverage(constants_))
    for (int i = 0; i < 3; ++i) coarse_targets_[view].colour(static_cast<std::size_t>(i)).bind(3 + i);
  if (with_voxels(constants_)) voxel_texture_->bind(voxel_unit(constants_));
  if (with_coverage(constants_) && judges_coarse_lights_by_segment(constants_.technique.visibility)) {
    // The coarse lights' visibility (lib/rsm_coarse_visibility.glsl): a point light's six depth
    // maps, the layers of its cube_depths_ on unit 8, or cube_faces 0 (unoccluded).
    const std::optional<coarse_cube_views> cube = coarse_cube_of(views_, view);
    if (cube) {
      glActiveTexture(GL_TEXTURE0 + 8);
      glBindTexture(GL_TEXTURE_2D_ARRAY, cube_depths_.at(views_[view].light_index).get());
      gather_program_.set("cube_frames.cube_from_light", cube->frames.cube_from_light);
    }
    gather_program_.set("cube_faces", cube ? 1 : 0);
  }
  gather_program_.use();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  timer_.end();
}

// Pass 3b (sequences): the gather blended with the history, reprojected; returns the target written.
const framebuffer& rsm_pipeline::accumulate_history() {
  timer_.begin("temporal accumulation");
  const int written = 1 - history_index_;
  history_targets_[written].bind();
  indirect_targets_.front().colour(0).bind(0);  // one view (draw_next refuses more)
  history_targets_[history_index_].colour(0).bind(1);
  gbuffer_target_.colour(0).bind(2);
  last_temporal_inputs_ = {history_valid_, history_view_, history_view_projection_};
  temporal_program_.set("history_valid", history_valid_ ? 1 : 0);
  temporal_program_.set("previous_view", history_view_);
  temporal_program_.set("previous_view_projection", history_view_projection_);
  temporal_program_.use();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  timer_.end();
  history_index_ = written;
  history_valid_ = true;
  history_view_ = constants_.camera_view;
  history_view_projection_ = constants_.camera_view_projection;
  return history_targets_[written];
}

// Pass 4: the bilateral filter (separable: its x pass first) and the shading.
void rsm_pipeline::draw_post(const framebuffer& filter_input, std::size_t view) {
  timer_.begin(pass_name("post processing", view));
  const bool separable = constants_.technique.indirect && settings_.filter == post_filter::separable;
  if (separable) {
    blur_x_target_.bind();
    filter_input.colour(0).bind(0);
    gbuffer_target_.colour(2).bind(1);
    blur_x_program_.use();
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  const bool quad = separable && quad_blur(settings_);
  if (quad) {
    blur_y_target_.bind();
    blur_x_target_.colour(0).bind(0);
    gbuffer_target_.colour(0).bind(1);
    gbuffer_target_.colour(2).bind(2);
    blur_y_program_.use();
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  post_target_.bind();
  (quad ? blur_y_target_ : separable ? blur_x_target_ : filter_input).colour(0).bind(0);
  for (int i = 0; i < 3; ++i) gbuffer_target_.colour(static_cast<std::size_t>(i)).bind(i + 1);
  if (quad)
    for (int i = 1; i < 3; ++i) blur_y_target_.colour(static_cast<std::size_t>(i)).bind(i + 3);
  post_program().use();
  if (view > 0) {
    // Added to the views before: radiance, indirect and direct light sum, alpha (1) stays.
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE);
  }
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDisable(GL_BLEND);
  timer_.end();
}

double rsm_pipeline::draw_wall_clock_ms() {
  glFinish();
  const auto start = std::chrono::steady_clock::now();
  draw();
  glFinish();
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  timer_.collect();  // the queries of this frame are not wanted
  return ms;
}

std::string rsm_pipeline::draw_counts() const {
  return "RSM " + std::to_string(rsm_draws_) + ", G-buffer to post filter " + std::to_string(view_draws_);
}

std::string rsm_pipeline::describe() const {
  return "scene " + scene_.name + " (" + std::to_string(triangles_) + " triangles), technique " + settings_.technique + ", " +
         std::to_string(settings_.width) + "x" + std::to_string(settings_.height) + ", RSM " + std::to_string(settings_.rsm_size) + "^2" +
         (views_.size() > 1 ? " x " + std::to_string(views_.size()) + " light views" : std::string()) + ", indirect " +
         std::to_string(constants_.indirect_size.x) + "x" + std::to_string(constants_.indirect_size.y) +
         (voxels_ ? ", voxel grid " + std::to_string(voxels_->shape.cells.x) + "x" + std::to_string(voxels_->shape.cells.y) + "x" +
                        std::to_string(voxels_->shape.cells.z) + " (" + std::to_string(voxels_->bytes() / 1024) + " KiB, built in " +
                        std::to_string(static_cast<int>(voxel_build_ms_ + 0.5)) + " ms)"
                  : std::string());
}

std::optional<image> rsm_pipeline::raw_indirect() const {
  if (!constants_.technique.indirect) return std::nullopt;
  // The sum over the lights of each one's gather; the depth (alpha) is the receivers', the same for all.
  image sum = indirect_targets_.front().read_image(0);
  for (std::size_t k = 1; k < indirect_targets_.size(); ++k) {
    const image light = indirect_targets_[k].read_image(0);
    for (std::size_t i = 0; i < sum.texels.size(); ++i) sum.texels[i] += glm::vec4(glm::vec3(light.texels[i]), 0.0f);
  }
  return sum;
}

rsm_pass_buffers rsm_pipeline::read_buffers(std::size_t view) const {
  const framebuffer& rsm_target = rsm_targets_.at(view);
  const framebuffer& indirect_target = indirect_targets_.at(view);
  rsm_pass_buffers buffers;
  buffers.rsm.width = rsm_target.width();
  buffers.rsm.height = rsm_target.height();
  const std::vector<std::uint32_t> words = rsm_target.read_uint(0);
  buffers.rsm.texels.resize(words.size() / 4);
  std::memcpy(buffers.rsm.texels.data(), words.data(), words.size() * sizeof(std::uint32_t));
  for (std::size_t i = 0; i < 3; ++i) buffers.gbuffer[i] = gbuffer_target_.read_image(i);
  if (with_coverage(constants_))
    for (std::size_t i = 0; i < 3; ++i) buffers.coarse[i] = coarse_targets_[view].read_image(i);
  buffers.voxels = voxels_;
  if (constants_.technique.indirect) {
    buffers.indirect = indirect_target.read_image(0);
    if (last_accumulated_) {
      buffers.accumulated = history_targets_[history_index_].read_image(0);
      buffers.history = history_targets_[1 - history_index_].read_image(0);
    }
    if (settings_.filter == post_filter::separable && blur_x_target_.colour(0).format() == texel_format::rgba32ui) {
      // The packed taps as the image the x pass wrote before they were packed: [irradiance | depth].
      const std::vector<std::uint32_t> packed_words = blur_x_target_.read_uint(0);
      buffers.blurred_x.width = blur_x_target_.width();
      buffers.blurred_x.height = blur_x_target_.height();
      buffers.blurred_x.texels.resize(packed_words.size() / 4);
      for (std::size_t i = 0; i < buffers.blurred_x.texels.size(); ++i) {
        const glm::vec2 red_green = glm::unpackHalf2x16(packed_words[4 * i]), blue_depth = glm::unpackHalf2x16(packed_words[4 * i + 1]);
        buffers.blurred_x.texels[i] = glm::vec4(red_green, blue_depth);
      }
    } else if (settings_.filter == post_filter::separable) {
      buffers.blurred_x = blur_x_target_.read_image(0);
    }
  }
  return buffers;
}

}  // namespace vplkit
