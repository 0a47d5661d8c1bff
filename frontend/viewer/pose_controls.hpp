// The viewer's moves of a pose (the camera, the light): orbit around the target, dolly towards
// it, fly along the view's axes, look around from the position. Pure functions of a pose, so that
// their properties are tested without a window (tests/frontend/viewer/test_pose_controls.cpp).
// World up is +Y, as the scenes' cameras have it.
#pragma once

#include <glm/glm.hpp>

#include "frontend/scene/pose.hpp"

namespace vplkit {

/// The pose's unit axes: forward (position to target), right (forward x up), up (right x forward).
/// A pose looking straight up or down takes -Z as its up reference.
struct pose_axes {
  glm::vec3 forward, right, up;
};
pose_axes axes_of(const pose& where);

/// Turns the position around the target: `yaw` radians about world +Y, `pitch` radians of
/// elevation (positive: the position rises), kept 1 degree short of the poles; the distance stays.
pose orbit(const pose& where, float yaw, float pitch);
/// Moves the position towards the target: distance x `factor` (> 0), never below 1e-3.
pose dolly(const pose& where, float factor);
/// Moves position and target together by `step` given along (right, up, forward).
pose fly(const pose& where, glm::vec3 step);
/// Turns the view direction about the position (the target moves; the distance stays): `yaw`
/// radians about world +Y, `pitch` radians of elevation (positive: looks up), 1 degree short of
/// the poles.
pose look(const pose& where, float yaw, float pitch);

}  // namespace vplkit
