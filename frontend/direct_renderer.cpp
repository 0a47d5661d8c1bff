#include "frontend/direct_renderer.hpp"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "frontend/debug_output.hpp"
#include "frontend/error.hpp"
#include "frontend/settings_uniforms.hpp"

namespace vplkit {

const char* validate(const direct_settings& settings) {
  if (settings.width < 1 || settings.height < 1) return "image size must be at least 1x1";
  if (settings.shadow_map_size < 1) return "shadow map size must be at least 1";
  if (settings.target_format != texel_format::rgba16f && settings.target_format != texel_format::rgba32f)
    return "render target format must be rgba16f or rgba32f";
  return validate(settings.irradiance);
}

glm::mat4 light_view_projection(const spot_light<float>& light) {
  const glm::vec3 up = std::abs(light.direction.y) > 0.99f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
  const glm::mat4 view = glm::lookAt(light.position, light.position + light.direction, up);
  // A square frustum whose half-angle is the outer cone plus a small margin.
  const float half_angle = std::acos(glm::clamp(light.cos_outer, -1.0f, 1.0f)) + glm::radians(2.0f);
  const float fov = glm::min(2.0f * half_angle, glm::radians(170.0f));
  return glm::perspective(fov, 1.0f, 0.05f, 20.0f) * view;
}

glm::mat4 camera_view_projection(const camera& view, float aspect) {
  return glm::perspective(glm::radians(view.vertical_fov_degrees), aspect, view.near_plane, view.far_plane) *
         glm::lookAt(view.position, view.target, view.up);
}

namespace {
const direct_settings& checked(const direct_settings& settings) {
  if (const char* problem = validate(settings)) throw error(std::string("direct settings: ") + problem);
  return settings;
}
}  // namespace

direct_renderer::direct_renderer(const shader_library& shaders, const scene& source, const direct_settings& settings)
    : scene_(source),
      settings_(checked(settings)),
      mesh_(source.geometry),
      shadow_program_(load_program(shaders, "shadow_depth.vert", "shadow_depth.frag")),
      shade_program_(load_program(shaders, "direct.vert", "direct.frag")),
      shadow_map_(settings.shadow_map_size, settings.shadow_map_size, {}, true),
      target_(settings.width, settings.height, {settings.target_format}, true) {
  if (const char* problem = validate(source.light)) throw error("scene " + source.name + ": " + problem);
  shadow_map_.depth().enable_depth_compare();
}

frame direct_renderer::render() {
  const glm::mat4 light_matrix = light_view_projection(scene_.light);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);

  timer_.begin("shadow map");
  shadow_map_.bind();
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(2.0f, 4.0f);  // slope-scaled bias against shadow acne
  shadow_program_.set("view_projection", light_matrix);
  shadow_program_.use();
  mesh_.draw();
  glDisable(GL_POLYGON_OFFSET_FILL);
  timer_.end();

  timer_.begin("shading");
  target_.bind();
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  shade_program_.set("view_projection",
                     camera_view_projection(scene_.view, static_cast<float>(settings_.width) / static_cast<float>(settings_.height)));
  shade_program_.set("light_view_projection", light_matrix);
  set_uniforms(shade_program_, "light", scene_.light);
  set_uniforms(shade_program_, "irradiance", settings_.irradiance);
  shade_program_.set("shadow_map", 0);
  shadow_map_.depth().bind(0);
  shade_program_.use();
  mesh_.draw();
  timer_.end();
  check_gl("rendering scene " + scene_.name);

  frame result;
  result.width = settings_.width;
  result.height = settings_.height;
  result.radiance = target_.read_float(0);
  result.pass_times = timer_.collect();
  return result;
}

}  // namespace vplkit
