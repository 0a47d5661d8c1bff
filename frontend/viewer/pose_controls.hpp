// The viewer's moves of a pose (the camera, the light): orbit around the target, dolly towards
// it, fly along the view's axes, look around from the position. Pure functions of a pose, so that
// their properties are tested without a window (tests/frontend/viewer/test_pose_controls.cpp).
// World up is +Y, as the scenes' cameras have it.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

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

/// The light part of the viewer's "vplkit render" arguments, so that the command draws the view's
/// lights with the selected one where it is: `file_lights` is the file's index of each of the
/// view's `count` lights (absent: every light of the file, in order), `selected` the one the
/// controls move and `selected_pose` its pose. The selected light goes first in --lights (--light
/// places the first chosen light), the others after it in their order:
///   no light: "--lights none"; every light of the file with the first selected: "--light P";
///   otherwise "--lights s,a,b --light P" (file indices). Only the selected light's pose is in the
///   text: another light moved before is drawn where the file has it.
std::string light_arguments(const std::optional<std::vector<std::size_t>>& file_lights, std::size_t count, std::size_t selected, const pose& selected_pose);

}  // namespace vplkit
