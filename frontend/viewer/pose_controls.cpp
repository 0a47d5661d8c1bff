#include "frontend/viewer/pose_controls.hpp"

#include <algorithm>
#include <cmath>

namespace vplkit {

namespace {

constexpr float pole_margin = 0.0174532925f;  // 1 degree
constexpr float half_pi = 1.57079632679f;

// The direction `yaw` and `pitch` away from `direction` (unit), pitch clamped short of the poles.
glm::vec3 turned(glm::vec3 direction, float yaw, float pitch) {
  const float elevation = std::asin(std::clamp(direction.y, -1.0f, 1.0f));
  const float azimuth = std::atan2(direction.x, direction.z);
  const float new_elevation = std::clamp(elevation + pitch, -half_pi + pole_margin, half_pi - pole_margin);
  const float new_azimuth = azimuth + yaw;
  return {std::cos(new_elevation) * std::sin(new_azimuth), std::sin(new_elevation), std::cos(new_elevation) * std::cos(new_azimuth)};
}

}  // namespace

pose_axes axes_of(const pose& where) {
  const glm::vec3 forward = glm::normalize(where.target - where.position);
  const glm::vec3 reference = std::abs(forward.y) > 0.999f ? glm::vec3(0.0f, 0.0f, -1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  const glm::vec3 right = glm::normalize(glm::cross(forward, reference));
  return {forward, right, glm::cross(right, forward)};
}

pose orbit(const pose& where, float yaw, float pitch) {
  const glm::vec3 offset = where.position - where.target;
  const float distance = glm::length(offset);
  return {where.target + distance * turned(offset / distance, yaw, pitch), where.target};
}

pose dolly(const pose& where, float factor) {
  const glm::vec3 offset = where.position - where.target;
  const float distance = glm::length(offset);
  const float scaled = std::max(distance * factor, 1e-3f);
  return {where.target + offset * (scaled / distance), where.target};
}

pose fly(const pose& where, glm::vec3 step) {
  const pose_axes axes = axes_of(where);
  const glm::vec3 offset = step.x * axes.right + step.y * axes.up + step.z * axes.forward;
  return {where.position + offset, where.target + offset};
}

pose look(const pose& where, float yaw, float pitch) {
  const glm::vec3 offset = where.target - where.position;
  const float distance = glm::length(offset);
  return {where.position, where.position + distance * turned(offset / distance, yaw, pitch)};
}

std::string light_arguments(const std::optional<std::vector<std::size_t>>& file_lights, std::size_t count, std::size_t selected, const pose& selected_pose) {
  if (count == 0) return "--lights none";
  const auto file_index = [&](std::size_t k) { return file_lights && k < file_lights->size() ? (*file_lights)[k] : k; };
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "," + std::to_string(...).
  std::string placed = "--light ";
  placed += format_pose(selected_pose);
  if (!file_lights && selected == 0) return placed;
  std::string text = "--lights ";
  text += std::to_string(file_index(selected));
  for (std::size_t k = 0; k < count; ++k)
    if (k != selected) {
      text += ',';
      text += std::to_string(file_index(k));
    }
  text += ' ';
  return text + placed;
}

}  // namespace vplkit
