#include "frontend/techniques/final_gather/final_gather_pipeline.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <thread>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/direct_light.hpp>
#include <vplkit/gl/settings_uniforms.hpp>

#include "frontend/gl/debug_output.hpp"
#include "frontend/core/error.hpp"
#include "frontend/core/parallel.hpp"
#include "frontend/techniques/rsm/rsm_pipeline.hpp"

namespace vplkit {

namespace {

const final_gather_settings& checked(const final_gather_settings& settings) {
  if (const std::string problem = validate(settings); !problem.empty()) throw error("final gathering settings: " + problem);
  return settings;
}

// The view of face `face` from o: rows (s, t, -major), so texel (i, j) lands on pixel (i, j).
glm::mat4 face_view(int face, const glm::vec3& o) {
  glm::vec3 major, s_axis, t_axis;
  cube_face_axes(face, major, s_axis, t_axis);
  glm::mat4 view(1.0f);
  for (int column = 0; column < 3; ++column) {
    view[column][0] = s_axis[column];
    view[column][1] = t_axis[column];
    view[column][2] = -major[column];
  }
  return view * glm::translate(glm::mat4(1.0f), -o);
}

// The tiles of the light depth map: a point light's six faces side by side, else one.
int light_depth_tiles(const std::vector<scene_light>& lights) {
  for (const scene_light& light : lights)
    if (light.kind == light_kind::point) return 6;
  return 1;
}

constexpr std::size_t no_light = SIZE_MAX;

}  // namespace

final_gather_pipeline::final_gather_pipeline(const shader_library& shaders, const final_gather_scene& source, const final_gather_settings& settings)
    : scene_(source),
      settings_(checked(settings)),
      technique_(find_final_gather_technique(settings.technique)),
      room_(source.room),
      object_(source.object),
      light_depth_program_(load_program(shaders, "scene.vert", "final_gather_light_depth.frag")),
      cube_program_(load_program(shaders, "scene.vert", "cube_face.frag")),
      downsample_program_(load_program(shaders, "fullscreen.vert", "cube_downsample.frag")),
      gbuffer_program_(load_program(shaders, "scene.vert", "final_gather_gbuffer.frag")),
      shade_program_(load_program(shaders, "fullscreen.vert", "final_gather_shade.frag",
                                  {{"VPLKIT_FINAL_GATHER", std::to_string(static_cast<int>(technique_.variant))}})),
      direct_program_(load_program(shaders, "fullscreen.vert", "final_gather_direct.frag")),
      light_depth_(light_depth_tiles(source.lights) * final_gather_light_depth_size, final_gather_light_depth_size, {texel_format::rgba32f}, true),
      faces_(6 * settings.face_size, settings.face_size, {texel_format::rgba32f}, true),
      small_cube_(6 * settings.resolution, settings.resolution, {texel_format::rgba32f}, false),
      environment_(technique_.variant == final_gather_variant::environment_map ? 6 * settings.environment_resolution : 1,
                   technique_.variant == final_gather_variant::environment_map ? settings.environment_resolution : 1, {texel_format::rgba32f}, false),
      gbuffer_(settings.width, settings.height, {texel_format::rgba32f, texel_format::rgba32f, texel_format::rgba32f}, true),
      direct_(settings.width, settings.height, {texel_format::rgba32f}, false),
      output_(settings.width, settings.height, {settings.format, settings.format, settings.format}, false),
      empty_vertex_array_(generate_vertex_array()) {
  if (source.object.indices.empty()) throw error("final gathering: the object " + source.name + " has no triangles");
  if (technique_.variant == final_gather_variant::environment_map)
    environment_program_ = load_program(shaders, "fullscreen.vert", "environment_convolution.frag");
  check_lights(source.lights, "final gathering, object " + source.name);
  for (const program* target : {&cube_program_, &direct_program_}) set_uniforms(*target, "irradiance", settings_.irradiance);
  // One texel of the light's depth map per lookup: the reference's shadow rays are hard, and the
  // wider window of Alg. 4 would soften the room's shadows it compares against.
  shadow_density_settings<float> shadow;
  shadow.kernel_size = 1;
  for (const program* target : {&cube_program_, &direct_program_}) {
    set_uniforms(*target, "shadow", shadow);
    target->set("light_depth_size", final_gather_light_depth_size);
  }
  cube_program_.set("light_depth", 1);  // the material's texture has a unit of its own (material_texture_unit)
  direct_program_.set("gbuffer_position_kind", 0);
  direct_program_.set("gbuffer_normal", 1);
  direct_program_.set("light_depth", 2);
  downsample_program_.set("faces", 0);
  downsample_program_.set("face_size", settings_.face_size);
  downsample_program_.set("resolution", settings_.resolution);
  if (technique_.variant == final_gather_variant::environment_map) {
    environment_program_.set("small_cube", 0);
    environment_program_.set("resolution", settings_.resolution);
    environment_program_.set("environment_resolution", settings_.environment_resolution);
  }
  int unit = 0;
  for (const char* name : {"small_cube", "environment_map", "gbuffer_position_kind", "gbuffer_normal", "gbuffer_albedo", "direct_irradiance"})
    shade_program_.set(name, unit++);
  shade_program_.set("resolution", settings_.resolution);
  shade_program_.set("environment_resolution", settings_.environment_resolution);
  if (has_emission(source.room) || has_emission(source.object)) emission_.emplace(shaders);
  set_pose_uniforms();
  check_gl("setting up the final gathering pipeline");
}

void final_gather_pipeline::set_pose_uniforms() {
  for (const program* target : {&cube_program_, &shade_program_}) target->set("reference_point", scene_.reference_point);
  if (technique_.variant == final_gather_variant::environment_map) environment_program_.set("reference_point", scene_.reference_point);
  gbuffer_program_.set("view_projection", camera_view_projection());
}

glm::mat4 final_gather_pipeline::camera_view_projection() const {
  return camera_projection_matrix(scene_.view, static_cast<float>(settings_.width) / static_cast<float>(settings_.height)) * camera_view_matrix(scene_.view);
}

void final_gather_pipeline::set_camera(const camera& view) {
  check_camera(view, "final gathering, object " + scene_.name);
  scene_.view = view;
  set_pose_uniforms();
  view_valid_ = false;
}

void final_gather_pipeline::set_light(std::size_t index, const scene_light& light) {
  if (index >= scene_.lights.size())
    throw error("final gathering, object " + scene_.name + ": no light " + std::to_string(index) + " (it has " + std::to_string(scene_.lights.size()) + ")");
  check_light(light, "final gathering, object " + scene_.name + ", light " + std::to_string(index));
  scene_.lights[index] = light;
  // A light turned into a point light needs the six faces' tiles.
  const int width = light_depth_tiles(scene_.lights) * final_gather_light_depth_size;
  if (light_depth_.width() < width) light_depth_ = framebuffer(width, final_gather_light_depth_size, {texel_format::rgba32f}, true);
  cube_valid_ = view_valid_ = false;
}

// Which setting applies in place (the viewer's live controls) and why: a new pipeline for
// another technique (the shading's VPLKIT_FINAL_GATHER define) and for the settings the table
// says size what the constructor builds (setting::builds: the G-buffer, output, faces' and small
// cube map's targets, envmap's environment map, the object's mesh); in place the rest, the
// irradiance clamp the cube map's faces and the shading read as uniforms (the cube map is
// redrawn, as after a light move). The object's position is the pipeline's own
// (set_object_position), not applied from the settings.
bool final_gather_pipeline::apply_settings(const technique_settings& settings) {
  const auto* typed = dynamic_cast<const described_settings<final_gather_setup, final_gather_technique>*>(&settings);
  if (!typed) return false;
  const final_gather_setup& setup = typed->value();
  const final_gather_settings& next = setup.pipeline;
  // What this pipeline was made with: its settings, and the object's source and placement
  // (object_key, which the object's settings change). A pipeline made from a scene rather than a
  // setup has no object's source, and takes no settings in place.
  final_gather_setup current = setup;
  current.pipeline = settings_;
  if (!validate(setup).empty() || scene_.object_source.empty() || object_key(setup) != scene_.object_source ||
      next.technique != settings_.technique || !rebuilding_changes(final_gather_settings_table(), current, setup).empty())
    return false;
  settings_ = next;
  for (const program* target : {&cube_program_, &direct_program_}) set_uniforms(*target, "irradiance", settings_.irradiance);
  shade_program_.set("environment_resolution", settings_.environment_resolution);
  check_gl("applying the final gathering pipeline's settings");
  cube_valid_ = view_valid_ = false;
  return true;
}

std::vector<scene_light> final_gather_pipeline::current_lights() const { return scene_.lights; }

std::string final_gather_pipeline::draw_counts() const {
  return "cube map " + std::to_string(cube_draws_) + ", G-buffer and shading " + std::to_string(view_draws_);
}

std::string final_gather_pipeline::describe() const {
  std::ostringstream out;
  out << "object " << scene_.name << " (" << scene_.object.triangle_count() << " triangles) at (" << scene_.reference_point.x << ", "
      << scene_.reference_point.y << ", " << scene_.reference_point.z << "), technique " << settings_.technique << ", " << settings_.width << "x"
      << settings_.height << ", cube map 6 x " << settings_.face_size << "^2 -> 6 x " << settings_.resolution << "^2";
  return out.str();
}

void final_gather_pipeline::set_object_position(glm::vec3 centre) {
  if (!(std::isfinite(centre.x) && std::isfinite(centre.y) && std::isfinite(centre.z) && glm::length(centre) <= max_scene_coordinate))
    throw error("final gathering: the object's position must be finite and within " + std::to_string(max_scene_coordinate) + " of the origin");
  for (std::size_t i = 0; i < scene_.object.vertices.size(); ++i) scene_.object.vertices[i].position = scene_.local_object.vertices[i].position + centre;
  scene_.reference_point = centre;
  object_ = mesh_buffers(scene_.object);
  set_pose_uniforms();
  cube_valid_ = view_valid_ = false;
}

final_gather_frame final_gather_pipeline::render() {
  draw();
  final_gather_frame frame;
  frame.radiance = output_.read_image(0);
  frame.indirect = output_.read_image(1);
  frame.pass_times = timer_.collect();
  return frame;
}

void final_gather_pipeline::draw() { draw_passes(true); }

void final_gather_pipeline::draw_changed() {
  if (!cube_valid_ || !view_valid_) draw_passes(!cube_valid_);
}

std::string final_gather_pipeline::pass_name(const char* pass, std::size_t light) const {
  // With one light, the name it always had; else the light's index, so that render --stats
  // shows the time per light (as the RSM family's passes).
  if (scene_.lights.size() <= 1) return pass;
  return std::string(pass) + " light " + std::to_string(light);
}

void final_gather_pipeline::draw_passes(bool with_cube) {
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);  // distance 0: nothing seen
  const float room_size = bounds(scene_.room).radius();

  timer_.begin("G-buffer");
  gbuffer_.bind();
  glEnable(GL_DEPTH_TEST);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  gbuffer_program_.set("surface_kind", 1.0f);
  glEnable(GL_CULL_FACE);  // the room's quads face inwards, counter-clockwise
  glCullFace(GL_BACK);
  room_.draw(gbuffer_program_);
  glDisable(GL_CULL_FACE);  // an OBJ object's winding is not to be trusted
  gbuffer_program_.set("surface_kind", 2.0f);
  object_.draw(gbuffer_program_);
  glDisable(GL_DEPTH_TEST);
  timer_.end();

  // Each light with its own depth map, its radiance added to the faces and its direct light to
  // the view's: the view's direct light needs the depth maps too, so a frame after a camera move
  // draws them again (one light's map is kept at a time, not eight).
  direct_.bind();
  glClear(GL_COLOR_BUFFER_BIT);
  if (scene_.lights.empty() && with_cube) draw_cube_faces(no_light, true, room_size);  // the distances, black
  for (std::size_t light = 0; light < scene_.lights.size(); ++light) {
    draw_light_depth(light);
    if (with_cube) draw_cube_faces(light, light == 0, room_size);
    draw_direct(light);
  }
  if (with_cube) finish_cube_map();

  timer_.begin("shading");
  output_.bind();
  small_cube_.colour(0).bind(0);
  environment_.colour(0).bind(1);
  for (int i = 0; i < 3; ++i) gbuffer_.colour(static_cast<std::size_t>(i)).bind(2 + i);
  direct_.colour(0).bind(5);
  shade_program_.use();
  glBindVertexArray(empty_vertex_array_.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  timer_.end();
  if (emission_) {
    // The room's and the object's emitters, on the G-buffer's depth of both.
    timer_.begin("emission");
    for (const mesh_buffers* drawn : {&room_, &object_})
      if (drawn->has_emission()) emission_->draw(*drawn, camera_view_projection(), scene_.view.position, output_.colour(0), gbuffer_.depth());
    timer_.end();
  }
  check_gl("final gathering, object " + scene_.name + ", " + technique_.name);
  view_valid_ = true;
  ++view_draws_;
}

// The light's kind and parameters for the faces and the direct light, and its depth map of the
// room: per tile the light's frustum as the RSM techniques draw it (a spot's square frustum
// around its outer cone, a point light's 90-degree face, a sun's orthographic box over the room),
// its far plane past the room.
void final_gather_pipeline::draw_light_depth(std::size_t light) {
  const scene_light& drawn = scene_.lights[light];
  for (const program* target : {&cube_program_, &direct_program_}) {
    target->set("light_kind", static_cast<int>(drawn.kind));
    if (drawn.kind == light_kind::spot) set_uniforms(*target, "spot", drawn.spot);
    else if (drawn.kind == light_kind::point) set_uniforms(*target, "point", drawn.point);
    else set_uniforms(*target, "sun", drawn.directional);
  }
  scene lit;
  lit.name = scene_.name;
  lit.lights = scene_.lights;
  const bounding_box box = bounds(scene_.room);
  timer_.begin(pass_name("light depth", light));
  light_depth_.bind();
  glEnable(GL_DEPTH_TEST);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);  // eye depth 0: nothing there, hides nothing
  const int tiles = drawn.kind == light_kind::point ? 6 : 1;
  for (int tile = 0; tile < tiles; ++tile) {
    const light_frustum frustum = make_light_frustum(lit, box, final_gather_light_depth_size, light, tile);
    const glm::mat4 projection = frustum.view_projection * glm::inverse(frustum.view);
    // Appended, not "[" + ...: GCC 12's -Wrestrict misfires on operator+(const char*, string&&).
    const auto element = [tile](const char* name) {
      std::string text(name);
      text += '[';
      text += std::to_string(tile);
      text += ']';
      return text;
    };
    for (const program* target : {&cube_program_, &direct_program_}) {
      target->set(element("light_view"), frustum.view);
      target->set(element("light_projection"), projection);
      target->set(element("light_view_projection"), frustum.view_projection);
    }
    light_depth_program_.set("view_projection", frustum.view_projection);
    light_depth_program_.set("light_view", frustum.view);
    glViewport(tile * final_gather_light_depth_size, 0, final_gather_light_depth_size, final_gather_light_depth_size);
    room_.draw(light_depth_program_);  // both sides: a wall seen from behind still casts its shadow
  }
  glDisable(GL_DEPTH_TEST);
  timer_.end();
}

// Pass 3 for one light: the first light (or none) draws the faces; each further light adds its
// radiance where the same surfaces are (depth test LEQUAL against the first's depths: the same
// program and vertices give the same depths), the distance in .w kept.
void final_gather_pipeline::draw_cube_faces(std::size_t light, bool first, float room_size) {
  timer_.begin(pass_name("cube map", light));
  faces_.bind();
  glEnable(GL_DEPTH_TEST);
  if (first) {
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  } else {
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE);
  }
  if (light == no_light) cube_program_.set("light_kind", -1);
  const glm::mat4 projection = glm::perspective(glm::radians(90.0f), 1.0f, 0.001f * room_size, 4.0f * room_size);
  light_depth_.colour(0).bind(1);
  for (int face = 0; face < 6; ++face) {
    glViewport(face * settings_.face_size, 0, settings_.face_size, settings_.face_size);
    cube_program_.set("view_projection", projection * face_view(face, scene_.reference_point));
    room_.draw(cube_program_);  // the object is left out
  }
  glDisable(GL_BLEND);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  glDisable(GL_DEPTH_TEST);
  timer_.end();
}

// Pass 4: one light's shadowed direct irradiance at the G-buffer's surfaces, added to the others'.
void final_gather_pipeline::draw_direct(std::size_t light) {
  timer_.begin(pass_name("direct light", light));
  direct_.bind();
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  gbuffer_.colour(0).bind(0);
  gbuffer_.colour(1).bind(1);
  light_depth_.colour(0).bind(2);
  direct_program_.use();
  glBindVertexArray(empty_vertex_array_.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glDisable(GL_BLEND);
  timer_.end();
}

// Passes 5 and 6: the faces averaged down (checked: the object must not reach into the room),
// and the baseline's environment map.
void final_gather_pipeline::finish_cube_map() {
  glDisable(GL_DEPTH_TEST);
  glBindVertexArray(empty_vertex_array_.get());
  timer_.begin("downsample");
  small_cube_.bind();
  faces_.colour(0).bind(0);
  downsample_program_.use();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  timer_.end();

  // A reference point outside the room, or an object reaching into it, shows as texels that
  // saw nothing (distance 0) or that are nearer than the object's own radius.
  const image small = small_cube_.read_image(0);
  float nearest = 1e30f;
  for (const glm::vec4& texel : small.texels) nearest = std::min(nearest, texel.w);
  if (!(nearest > scene_.object_radius)) {
    glBindVertexArray(0);
    throw error("final gathering: the environment seen from the reference point (" + std::to_string(scene_.reference_point.x) + ", " +
                std::to_string(scene_.reference_point.y) + ", " + std::to_string(scene_.reference_point.z) + ") comes as near as " +
                std::to_string(nearest) + ", within the object's radius " + std::to_string(scene_.object_radius) +
                ": the reference point is outside the room or inside geometry, or the object intersects a wall");
  }

  if (technique_.variant == final_gather_variant::environment_map) {
    timer_.begin("environment convolution");
    environment_.bind();
    small_cube_.colour(0).bind(0);
    environment_program_.use();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    timer_.end();
  }
  glBindVertexArray(0);
  cube_valid_ = true;
  ++cube_draws_;
}

final_gather_buffers final_gather_pipeline::read_buffers() const {
  final_gather_buffers buffers;
  buffers.small_cube = small_cube_.read_image(0);
  if (technique_.variant == final_gather_variant::environment_map) buffers.environment_map = environment_.read_image(0);
  for (std::size_t i = 0; i < 3; ++i) buffers.gbuffer[i] = gbuffer_.read_image(i);
  buffers.direct = direct_.read_image(0);
  return buffers;
}

}  // namespace vplkit
