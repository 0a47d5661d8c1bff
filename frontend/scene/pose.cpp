#include "frontend/scene/pose.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <string_view>

#include "frontend/core/error.hpp"
#include "frontend/core/files.hpp"

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
  // A point light shines everywhere: its pose's target is one unit below it, for the text only.
  if (light.kind == light_kind::point) return {light.point.position, light.point.position - glm::vec3(0.0f, 1.0f, 0.0f)};
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
  else if (light.kind == light_kind::point) light.point.position = (checked_direction(where, owner), where.position);
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

std::vector<pose_frame> read_pose_file(const std::filesystem::path& path, bool with_scene) {
  const std::string text = read_file(path, max_pose_file_bytes, "pose file");
  std::vector<pose_frame> frames;
  std::size_t start = 0;
  for (int number = 1; start < text.size(); ++number) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string_view line(text.data() + start, end - start);
    start = end + 1;
    const std::string where = path.string() + ":" + std::to_string(number);
    pose_frame frame;
    frame.line = number;
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) {
      std::string_view comment = line.substr(hash + 1);
      while (!comment.empty() && (comment.front() == ' ' || comment.front() == '\t')) comment.remove_prefix(1);
      while (!comment.empty() && (comment.back() == ' ' || comment.back() == '\t' || comment.back() == '\r')) comment.remove_suffix(1);
      frame.comment = std::string(comment);
      line = line.substr(0, hash);
    }
    std::vector<std::string_view> words;
    for (std::size_t at = 0; at < line.size();) {
      while (at < line.size() && (line[at] == ' ' || line[at] == '\t' || line[at] == '\r')) ++at;
      std::size_t stop = at;
      while (stop < line.size() && line[stop] != ' ' && line[stop] != '\t' && line[stop] != '\r') ++stop;
      if (stop > at) words.push_back(line.substr(at, stop - at));
      at = stop;
    }
    if (words.empty()) continue;
    for (std::size_t i = 0; i < words.size(); i += 2) {
      const std::string name(words[i]);
      if (i + 1 >= words.size()) throw error(where + ": " + name.substr(0, 40) + " needs a value");
      const std::string value(words[i + 1]);
      if (name == "--camera" || name == "--light") {
        std::optional<pose>& target = name == "--camera" ? frame.camera : frame.light;
        if (target) throw error(where + ": " + name + " is given twice");
        pose parsed;
        if (const std::string problem = parse_pose(value, parsed); !problem.empty()) throw error(where + ": " + name + ": " + problem);
        target = parsed;
      } else if (name == "--scene" && with_scene) {
        if (!frame.scene.empty()) throw error(where + ": --scene is given twice");
        frame.scene = value;
      } else {
        throw error(where + ": expected " + (with_scene ? "--scene, " : "") + "--camera or --light, got '" + name.substr(0, 40) + "'");
      }
    }
    if (!frame.camera && !frame.light && frame.scene.empty()) throw error(where + ": the line gives no pose");
    if (frames.size() == max_pose_frames) throw error(path.string() + ": more than " + std::to_string(max_pose_frames) + " frames");
    frames.push_back(std::move(frame));
  }
  if (frames.empty()) throw error(path.string() + ": no frames (one per line: --camera x,y,z,tx,ty,tz and/or --light x,y,z,tx,ty,tz)");
  return frames;
}

}  // namespace vplkit
