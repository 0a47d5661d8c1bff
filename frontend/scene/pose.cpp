#include "frontend/scene/pose.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <string_view>

#include "frontend/core/error.hpp"

namespace vplkit {

namespace {

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

glm::vec3 checked_direction(const pose& where, const std::string& owner) {
  if (!finite(where.position) || !finite(where.target)) throw error(owner + ": the pose has a non-finite value");
  const glm::vec3 direction = where.target - where.position;
  if (!(glm::dot(direction, direction) > 0.0f)) throw error(owner + ": the pose's position and target are the same point");
  return glm::normalize(direction);
}

}  // namespace

pose pose_of(const camera& view) { return {view.position, view.target}; }

pose pose_of(const scene_light& light) {
  if (light.kind == light_kind::spot) return {light.spot.position, light.spot.position + light.spot.direction};
  return {-light.directional.direction, glm::vec3(0.0f)};
}

void apply_pose(const pose& where, camera& view, const std::string& owner) {
  camera moved = view;
  moved.position = where.position;
  moved.target = where.target;
  check_camera(moved, owner);
  view = moved;
}

void apply_pose(const pose& where, spot_light<float>& light, const std::string& owner) {
  const glm::vec3 direction = checked_direction(where, owner);
  light.position = where.position;
  light.direction = direction;
}

void apply_pose(const pose& where, scene_light& light, const std::string& owner) {
  if (light.kind == light_kind::spot) apply_pose(where, light.spot, owner);
  else light.directional.direction = checked_direction(where, owner);
}

std::string format_point(glm::vec3 point) {
  std::string text;
  for (int axis = 0; axis < 3; ++axis) {
    char number[32];
    std::snprintf(number, sizeof number, "%.9g", static_cast<double>(point[axis]));
    if (axis > 0) text += ',';
    text += number;
  }
  return text;
}

std::string format_pose(const pose& where) { return format_point(where.position) + "," + format_point(where.target); }

bool parse_number_list(std::string_view text, float* values, int count, float limit) {
  for (int i = 0; i < count; ++i) {
    const std::size_t comma = text.find(',');
    if ((i < count - 1) != (comma != std::string_view::npos)) return false;
    std::string_view number = text.substr(0, comma);
    text = comma == std::string_view::npos ? std::string_view() : text.substr(comma + 1);
    while (!number.empty() && number.front() == ' ') number.remove_prefix(1);
    while (!number.empty() && number.back() == ' ') number.remove_suffix(1);
    if (number.size() > 1 && number[0] == '+' && number[1] != '-') number.remove_prefix(1);
    const auto [end, code] = std::from_chars(number.data(), number.data() + number.size(), values[i]);
    if (number.empty() || code != std::errc() || end != number.data() + number.size() || !std::isfinite(values[i]) || std::fabs(values[i]) > limit)
      return false;
  }
  return true;
}

std::string parse_pose(const std::string& text, pose& where) {
  float values[6];
  if (!parse_number_list(text, values, 6, max_scene_coordinate))
    return "expected x,y,z,tx,ty,tz (a position and the point it looks at, each a finite number within +-1e+07)";
  const pose parsed{{values[0], values[1], values[2]}, {values[3], values[4], values[5]}};
  if (parsed.position == parsed.target) return "the position and the target are the same point";
  where = parsed;
  return {};
}

}  // namespace vplkit
