// Where a camera or a light is and where it looks: the --camera / --light options of render,
// reference and view, the viewer's moves, and the pose the viewer prints so that a headless render
// can start from what was seen. A pose is a position and a target point; the camera keeps its up
// vector and field of view, a spot light its cone and intensity, a directional light shines from
// the position towards the target (only the direction is kept).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "frontend/scene/scene.hpp"

namespace vplkit {

struct pose {
  glm::vec3 position{0.0f};
  glm::vec3 target{0.0f, 0.0f, -1.0f};
};

pose pose_of(const camera& view);
/// A spot light: its position and the point one unit along its axis. A directional light: the
/// origin minus its direction, and the origin.
pose pose_of(const scene_light& light);

/// Throws vplkit::error starting with `owner`, leaving the camera or light as it was: for a
/// camera, check_camera's errors for the moved camera; for a light, a pose whose position equals
/// its target or has a value that is not finite.
void apply_pose(const pose& where, camera& view, const std::string& owner);
void apply_pose(const pose& where, scene_light& light, const std::string& owner);
void apply_pose(const pose& where, spot_light<float>& light, const std::string& owner);

/// `count` comma-separated numbers (spaces allowed around each, a leading '+' too), each finite
/// within +-limit, into `values`. Returns false, leaving `values` unspecified, on anything else.
bool parse_number_list(std::string_view text, float* values, int count, float limit);

/// "x,y,z" with 9 significant digits (enough for a float to read back the same).
std::string format_point(glm::vec3 point);
/// "x,y,z,tx,ty,tz" with 9 significant digits: parse_pose reads back the same floats.
std::string format_pose(const pose& where);
/// Parses "x,y,z,tx,ty,tz" (each finite within +-max_scene_coordinate; position != target).
/// Empty on success, else the reason (without the text, which the caller shows as it shows
/// arguments).
std::string parse_pose(const std::string& text, pose& where);

/// One frame of a pose file: the poses its line gives (a missing one keeps the previous frame's,
/// or the scene's for the first frame) and, where the reader allows it, a scene.
struct pose_frame {
  std::optional<pose> camera;  ///< --camera
  std::optional<pose> light;   ///< --light
  std::string scene;           ///< --scene (empty: none given)
  int line = 0;                ///< 1-based line in the file
  std::string comment;         ///< what follows '#' on the line, trimmed
};

/// The largest pose file read (bytes) and the most frames it may hold.
inline constexpr std::uintmax_t max_pose_file_bytes = std::uintmax_t{16} << 20;
inline constexpr std::size_t max_pose_frames = 100000;

/// Reads a pose file: one frame per line, each line the pose options as `render` takes them,
/// `--camera x,y,z,tx,ty,tz` and `--light x,y,z,tx,ty,tz` (and `--scene NAME` when `with_scene`),
/// separated by spaces; '#' starts a comment; blank and comment-only lines are skipped. Throws
/// vplkit::error naming the file and the line for anything else (an unknown or repeated option, a
/// bad pose, a line without a pose), for a file without frames and for one beyond the limits above.
std::vector<pose_frame> read_pose_file(const std::filesystem::path& path, bool with_scene);

}  // namespace vplkit
