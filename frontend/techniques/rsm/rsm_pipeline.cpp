#include "frontend/techniques/rsm/rsm_pipeline.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>

#include <vplkit/hash.hpp>
#include <vplkit/gl/settings_uniforms.hpp>

#include "frontend/gl/debug_output.hpp"
#include "frontend/core/error.hpp"

namespace vplkit {

light_frustum make_light_frustum(const scene& source, int rsm_size) { return make_light_frustum(source, bounds(source.geometry), rsm_size); }

light_frustum make_light_frustum(const scene& source, const bounding_box& box, int rsm_size) {
  light_frustum frustum;
  const float radius = std::max(box.radius(), 1e-3f);
  const scene_light& primary = single_light(source, "the RSM pipeline");
  if (primary.kind == light_kind::point) throw error("scene " + source.name + ": the RSM pipeline does not draw point lights yet");
  if (primary.kind == light_kind::spot) {
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

rsm_frame_constants make_frame_constants(const scene& source, const rsm_pipeline_settings& settings) {
  return make_frame_constants(source, bounds(source.geometry), source.geometry.triangle_count(), settings);
}

rsm_frame_constants make_frame_constants(const scene& source, const bounding_box& box, std::size_t triangles, const rsm_pipeline_settings& settings) {
  if (const std::string problem = validate(settings); !problem.empty()) throw error("RSM pipeline settings: " + problem);
  const scene_light& primary = single_light(source, "the RSM pipeline");
  check_light(primary, "scene " + source.name);
  if (triangles == 0) throw error("scene " + source.name + " has no triangles");
  rsm_frame_constants constants;
  constants.technique = find_rsm_technique(settings.technique);
  constants.light = make_light_frustum(source, box, settings.rsm_size);
  constants.primary = primary;
  constants.gather = derive(settings).gather;
  const bool spot = primary.kind == light_kind::spot;
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

namespace {

const char* flag(bool value) { return value ? "1" : "0"; }

bool is_directional(const scene& source) { return single_light(source, "the RSM pipeline").kind == light_kind::directional; }

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

void set_light_uniforms(const program& target, const rsm_frame_constants& constants) {
  if (constants.primary.kind == light_kind::spot) set_uniforms(target, "spot", constants.primary.spot);
  else set_uniforms(target, "directional", constants.primary.directional);
}

}  // namespace

rsm_pipeline::rsm_pipeline(const shader_library& shaders, const scene& source, const rsm_pipeline_settings& settings)
    : scene_{source.name, mesh{}, source.view, source.lights, source.notes, {}},
      bounds_(bounds(source.geometry)),
      triangles_(source.geometry.triangle_count()),
      settings_(settings),
      constants_(make_frame_constants(source, bounds_, triangles_, settings)),
      mesh_(source.geometry),
      rsm_program_(load_program(shaders, "scene.vert", "rsm.frag", {{"VPLKIT_LIGHT_DIRECTIONAL", flag(is_directional(source))}})),
      gbuffer_program_(load_program(shaders, "scene.vert", "gbuffer.frag")),
      rsm_target_(settings.rsm_size, settings.rsm_size, {texel_format::rgba32ui}, true),
      coarse_target_(std::max(constants_.gather.coverage_blocks, 1), std::max(constants_.gather.coverage_blocks, 1),
                     {texel_format::rgba32f, texel_format::rgba32f, texel_format::rgba32f}, false),
      gbuffer_target_(settings.width, settings.height, {settings.format, settings.format, settings.format}, true),
      indirect_target_(constants_.indirect_size.x, constants_.indirect_size.y, {settings.format}, false),
      history_targets_{framebuffer(with_temporal(constants_) ? constants_.indirect_size.x : 1, with_temporal(constants_) ? constants_.indirect_size.y : 1,
                                   {settings.format}, false),
                       framebuffer(with_temporal(constants_) ? constants_.indirect_size.x : 1, with_temporal(constants_) ? constants_.indirect_size.y : 1,
                                   {settings.format}, false)},
      blur_x_target_(settings.filter == post_filter::separable ? constants_.indirect_size.x : 1,
                     settings.filter == post_filter::separable ? constants_.indirect_size.y : 1,
                     {packed_blur(settings) ? texel_format::rgba32ui : settings.format}, false),
      post_target_(settings.width, settings.height, {settings.format, settings.format}, false),
      empty_vertex_array_(generate_vertex_array()) {
  if (with_voxels(constants_)) {
    // Built once: a pipeline's triangles are fixed for its life (a new scene is a new pipeline).
    const auto start = std::chrono::steady_clock::now();
    voxels_ = std::make_shared<const voxel_grid>(build_voxel_grid(source.geometry, bounds_, settings_.voxel_grid));
    voxel_build_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const glm::ivec2 size = voxel_texture_size(voxels_->shape.cells);
    voxel_texture_.emplace(size.x, size.y, texel_format::rgba32ui, voxels_->texels.data());
  }
  load_programs(shaders, source);
  set_settings_uniforms();
  set_pose_uniforms();
  check_gl("setting up the RSM pipeline");
}

void rsm_pipeline::load_programs(const shader_library& shaders, const scene& source) {
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
  }
  post_program_ = load_program(shaders, "fullscreen.vert", "post.frag",
                               {{"VPLKIT_INDIRECT", flag(technique.indirect)},
                                {"VPLKIT_SEPARABLE", flag(separable)},
                                {"VPLKIT_PACKED_BLUR", flag(technique.indirect && packed)},
                                {"VPLKIT_LIGHT_DIRECTIONAL", flag(is_directional(source))}});

}

// The uniforms that come from the settings (the constructor's, and apply_settings's); the pose's
// are set by set_pose_uniforms.
void rsm_pipeline::set_settings_uniforms() {
  const rsm_technique& technique = constants_.technique;
  const bool separable = settings_.filter == post_filter::separable;
  rsm_program_.set("rsm_size", glm::ivec2(settings_.rsm_size));
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
    if (separable) {
      set_uniforms(blur_x_program_, "bilateral", constants_.bilateral);
      blur_x_program_.set("indirect_divisor", constants_.indirect_divisor);
      blur_x_program_.set("indirect_size", constants_.indirect_size);
      blur_x_program_.set("gbuffer_size", constants_.image_size);
      blur_x_program_.set("indirect_buffer", 0);
      blur_x_program_.set("gbuffer_normal", 1);
    }
  }
  set_uniforms(post_program_, "bilateral", constants_.bilateral);
  set_uniforms(post_program_, "irradiance", constants_.gather.irradiance);
  post_program_.set("indirect_divisor", constants_.indirect_divisor);
  post_program_.set("indirect_size", constants_.indirect_size);
  post_program_.set("gbuffer_size", constants_.image_size);
  int unit = 0;
  for (const char* name : {"indirect_buffer", "gbuffer_position_depth", "gbuffer_albedo_density", "gbuffer_normal"})
    post_program_.set(name, unit++);
}

bool rsm_pipeline::apply_settings(const technique_settings& settings) {
  const auto* typed = dynamic_cast<const described_settings<rsm_pipeline_settings, rsm_technique>*>(&settings);
  if (!typed) return false;
  const rsm_pipeline_settings& next = typed->value();
  // Another technique, or a setting that sets a define or sizes what the constructor builds (the
  // table says which: setting::defines, setting::builds), needs a new pipeline.
  if (!validate(next).empty() || next.technique != settings_.technique || !rebuilding_changes(rsm_settings_table(), settings_, next).empty()) return false;
  const rsm_frame_constants constants = make_frame_constants(scene_, bounds_, triangles_, next);
  settings_ = next;
  constants_ = constants;
  set_settings_uniforms();
  set_pose_uniforms();
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
  rsm_program_.set("view_projection", light.view_projection);
  rsm_program_.set("light_view", light.view);
  rsm_program_.set("tan_half_fov", light.tan_half_fov);
  rsm_program_.set("texel_area", light.texel_area);
  set_light_uniforms(rsm_program_, constants_);
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
  set_light_uniforms(post_program_, constants_);
}

void rsm_pipeline::move_to(const camera& view, const std::vector<scene_light>& lights) {
  const camera previous_view = scene_.view;
  const std::vector<scene_light> previous_lights = scene_.lights;
  scene_.view = view;
  scene_.lights = lights;
  try {
    constants_ = make_frame_constants(scene_, bounds_, triangles_, settings_);
  } catch (...) {
    scene_.view = previous_view;
    scene_.lights = previous_lights;
    throw;
  }
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
  rsm_valid_ = view_valid_ = false;
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
  rsm_gather_settings<float> gather = constants_.gather;
  if (frame > 0) {
    gather.radial.seed = hash_combine(gather.radial.seed, frame);
    gather.disk.seed = hash_combine(gather.disk.seed, frame);
  }
  set_uniforms(gather_program_, "settings", gather);
}

void rsm_pipeline::draw_next() {
  if (!accumulates()) return draw();
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
  if (!rsm_valid_ || !view_valid_) draw_passes(!rsm_valid_);
}

void rsm_pipeline::draw_passes(bool with_rsm, bool accumulate) {
  const rsm_technique& technique = constants_.technique;
  if (!accumulate && (history_valid_ || sequence_frame_ > 0)) {
    // A frame outside a sequence: no history, and the settings' own pattern.
    history_valid_ = false;
    sequence_frame_ = 0;
    if (technique.indirect) set_pattern_frame(0);
  }
  last_accumulated_ = accumulate;
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);  // depth 0 marks "no surface" in every buffer
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);

  glEnable(GL_DEPTH_TEST);
  if (with_rsm) draw_rsm();
  draw_gbuffer();
  glDisable(GL_DEPTH_TEST);
  glBindVertexArray(empty_vertex_array_.get());
  if (technique.indirect) draw_gather();
  // The filter's input: the gather, or (sequences) the gather accumulated over the frames.
  draw_post(accumulate ? accumulate_history() : indirect_target_);
  glBindVertexArray(0);
  check_gl("rendering scene " + scene_.name + " with " + technique.name);
  view_valid_ = true;
  ++view_draws_;
}

// Pass 1, and the coverage's coarse lights from it.
void rsm_pipeline::draw_rsm() {
  timer_.begin("RSM generation");
  rsm_target_.bind();
  const GLuint empty_texel[4] = {0, 0, 0, 0};  // glClear's float colour is undefined for an integer target
  glClearBufferuiv(GL_COLOR, 0, empty_texel);
  glClear(GL_DEPTH_BUFFER_BIT);
  mesh_.draw(rsm_program_);
  timer_.end();
  if (with_coverage(constants_)) {
    timer_.begin("coverage lights");
    glDisable(GL_DEPTH_TEST);
    glBindVertexArray(empty_vertex_array_.get());
    coarse_target_.bind();
    rsm_target_.colour(0).bind(0);
    coarse_program_.use();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glEnable(GL_DEPTH_TEST);
    timer_.end();
  }
  rsm_valid_ = true;
  ++rsm_draws_;
}

// Pass 2.
void rsm_pipeline::draw_gbuffer() {
  timer_.begin("G-buffer generation");
  gbuffer_target_.bind();
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  rsm_target_.colour(0).bind(0);
  mesh_.draw(gbuffer_program_);
  timer_.end();
}

// Pass 3: the gather at the indirect buffer's receivers.
void rsm_pipeline::draw_gather() {
  timer_.begin("RSM sampling");
  indirect_target_.bind();
  rsm_target_.colour(0).bind(0);
  gbuffer_target_.colour(0).bind(1);
  gbuffer_target_.colour(2).bind(2);
  if (with_coverage(constants_))
    for (int i = 0; i < 3; ++i) coarse_target_.colour(static_cast<std::size_t>(i)).bind(3 + i);
  if (with_voxels(constants_)) voxel_texture_->bind(voxel_unit(constants_));
  gather_program_.use();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  timer_.end();
}

// Pass 3b (sequences): the gather blended with the history, reprojected; returns the target written.
const framebuffer& rsm_pipeline::accumulate_history() {
  timer_.begin("temporal accumulation");
  const int written = 1 - history_index_;
  history_targets_[written].bind();
  indirect_target_.colour(0).bind(0);
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
void rsm_pipeline::draw_post(const framebuffer& filter_input) {
  timer_.begin("post processing");
  const bool separable = constants_.technique.indirect && settings_.filter == post_filter::separable;
  if (separable) {
    blur_x_target_.bind();
    filter_input.colour(0).bind(0);
    gbuffer_target_.colour(2).bind(1);
    blur_x_program_.use();
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  post_target_.bind();
  (separable ? blur_x_target_ : filter_input).colour(0).bind(0);
  for (int i = 0; i < 3; ++i) gbuffer_target_.colour(static_cast<std::size_t>(i)).bind(i + 1);
  post_program_.use();
  glDrawArrays(GL_TRIANGLES, 0, 3);
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
         std::to_string(settings_.width) + "x" + std::to_string(settings_.height) + ", RSM " + std::to_string(settings_.rsm_size) + "^2, indirect " +
         std::to_string(constants_.indirect_size.x) + "x" + std::to_string(constants_.indirect_size.y) +
         (voxels_ ? ", voxel grid " + std::to_string(voxels_->shape.cells.x) + "x" + std::to_string(voxels_->shape.cells.y) + "x" +
                        std::to_string(voxels_->shape.cells.z) + " (" + std::to_string(voxels_->bytes() / 1024) + " KiB, built in " +
                        std::to_string(static_cast<int>(voxel_build_ms_ + 0.5)) + " ms)"
                  : std::string());
}

std::optional<image> rsm_pipeline::raw_indirect() const {
  if (!constants_.technique.indirect) return std::nullopt;
  return indirect_target_.read_image(0);
}

rsm_pass_buffers rsm_pipeline::read_buffers() const {
  rsm_pass_buffers buffers;
  buffers.rsm.width = rsm_target_.width();
  buffers.rsm.height = rsm_target_.height();
  const std::vector<std::uint32_t> words = rsm_target_.read_uint(0);
  buffers.rsm.texels.resize(words.size() / 4);
  std::memcpy(buffers.rsm.texels.data(), words.data(), words.size() * sizeof(std::uint32_t));
  for (std::size_t i = 0; i < 3; ++i) buffers.gbuffer[i] = gbuffer_target_.read_image(i);
  if (with_coverage(constants_))
    for (std::size_t i = 0; i < 3; ++i) buffers.coarse[i] = coarse_target_.read_image(i);
  buffers.voxels = voxels_;
  if (constants_.technique.indirect) {
    buffers.indirect = indirect_target_.read_image(0);
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
