#include "frontend/scene/camera.hpp"

#include <glm/gtc/matrix_transform.hpp>

namespace vplkit {

glm::mat4 camera_view_matrix(const camera& view) { return glm::lookAt(view.position, view.target, view.up); }

glm::mat4 camera_projection_matrix(const camera& view, float aspect) {
  return glm::perspective(glm::radians(view.vertical_fov_degrees), aspect, view.near_plane, view.far_plane);
}

}  // namespace vplkit
