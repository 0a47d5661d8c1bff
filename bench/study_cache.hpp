// What the study tools' cached references are keyed by (bench/lightwave_study.cpp,
// bench/rsm_poses.cpp): one text that cache_key (frontend/reference/rsm_measure.hpp) hashes into
// the cache file's name. A reference depends on the scene's content and on where its camera and
// light are, so the key holds the scene's name, a file's bytes and the posed camera and light as
// the study rendered them: a second pose of one scene file once reused the first pose's
// reference (issue 40), because the key named the file and not the pose.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "frontend/core/files.hpp"
#include "frontend/scene/pose.hpp"
#include "frontend/scene/scene.hpp"

namespace vplkit::study {

/// `name` is the scene as the study was given it (a built-in name or a file); `posed` the scene
/// with every pose applied. The image's size, the sample counts and seeds are the caller's to add.
inline std::string scene_identity(const std::string& name, const scene& posed) {
  std::string identity = "scene " + name;
  std::error_code ignored;
  if (std::filesystem::is_regular_file(name, ignored)) identity += "\nbytes " + read_file(name, std::uintmax_t{1} << 30, "scene");
  identity += "\ncamera " + format_pose(pose_of(posed.view)) + " up " + format_point(posed.view.up) + " fov " +
              std::to_string(posed.view.vertical_fov_degrees);
  for (const scene_light& light : posed.lights)
    identity += "\nlight " + std::to_string(static_cast<int>(light.kind)) + " " + format_pose(pose_of(light)) + " " + format_point(light_power(light));
  return identity;
}

}  // namespace vplkit::study
