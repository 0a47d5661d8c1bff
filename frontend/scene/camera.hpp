// The camera's matrices: every pipeline and the Monte Carlo reference see a scene through these
// two functions, so that a technique and its reference look at the same pixels.
#pragma once

#include <glm/glm.hpp>

#include "frontend/scene/scene.hpp"

namespace vplkit {

/// World to eye space (glm::lookAt of the camera).
glm::mat4 camera_view_matrix(const camera& view);
/// Eye to clip space for an image of width / height = `aspect` (GL conventions, depth -1..1).
glm::mat4 camera_projection_matrix(const camera& view, float aspect);

}  // namespace vplkit
