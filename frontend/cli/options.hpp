// What every subcommand of the command line shares: the session (where messages go, whether it
// is a dry run), the checked parsers of sizes, positions and numbers, and option scoping, with
// which an option that the chosen technique or method does not read is an error naming it.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include <vplkit/gl/program.hpp>

#include "frontend/gl/context.hpp"
#include "frontend/gl/render_target.hpp"
#include "frontend/scene/pose.hpp"
#include "frontend/scene/scene.hpp"

namespace vplkit::cli {

/// Where a command writes and whether it runs at all: a dry run parses and checks every option and
/// stops before it opens a context or reads a file (the option fuzzer runs the CLI that way).
struct session {
  std::ostream& out;
  bool dry_run = false;
};

/// A command line that parses but asks for something inconsistent (exit 2, like a parse error).
class usage_error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An argument as a message shows it: quoted, and cut after 60 characters.
std::string shown(std::string_view text);

/// A float as a message shows it (ostream's default format).
std::string format_number(float value);

/// "512" or "640x480" into width and height; empty on success, else the reason.
std::string parse_size(const std::string& text, int& width, int& height);

/// "x,y,z" (spaces allowed around the numbers, each finite within +-limit); empty on success.
std::string parse_position(const std::string& text, glm::vec3& position, float limit);

/// A number in [low, high] (or (low, high] when low_open); NaN and infinities fail.
CLI::Validator number_in(double low, double high, bool low_open, const std::string& what);
/// A finite number > 0.
CLI::Validator positive_number(const std::string& what);

/// Options that only some choices (techniques of `render`, methods of `reference`) read.
class option_scope {
 public:
  /// `option` is read only when reads(choice); `readers` says by whom, for the message.
  CLI::Option* add(CLI::Option* option, std::string readers, std::function<bool(const std::string&)> reads);
  /// Throws usage_error naming the first option given on the command line that `choice` does
  /// not read: "--ray-angle is read by the lightwave-* techniques, not by technique rsm-alg6".
  void require_read_by(const std::string& choice, const std::string& what) const;

 private:
  struct scoped {
    const CLI::Option* option;
    std::string readers;
    std::function<bool(const std::string&)> reads;
  };
  std::vector<scoped> options_;
};

/// Whether `name` starts with `prefix` (technique families: "rsm-", "lightwave-", ...).
inline bool starts_with(const std::string& name, std::string_view prefix) { return name.rfind(prefix, 0) == 0; }

/// The options that several technique families read: registered once per command (CLI11 names
/// an option once), scoped there to the techniques that read them.
struct common_options {
  std::string scene = "cornell-box";
  bool scene_given = false;     ///< the default scene depends on the technique
  std::uint32_t seed = 0;       ///< of the sampling patterns (RSM) and of the accurate shadows' VPLs (Light Wave)
  std::string size_text;
  int width = 512, height = 512;
  bool size_given = false;
  std::string format = "rgba16f";
  float min_distance = 0.01f;
  std::string shader_dir;
  std::string context = "auto";  ///< headless context: a name of headless_api_names()
  int device = -1;               ///< EGL device index, -1: automatic
  std::optional<pose> camera_pose;  ///< --camera: instead of the scene's camera
  std::optional<pose> light_pose;   ///< --light: instead of the scene's light
  headless_request headless() const;
  texel_format texel() const { return format == "rgba32f" ? texel_format::rgba32f : texel_format::rgba16f; }
  std::filesystem::path shaders() const;
};

/// The options add_common_options registered, for a command that scopes some of them.
struct common_option_handles {
  CLI::Option* size;
  CLI::Option* format;
  CLI::Option* min_distance;
  CLI::Option* shader_dir;
  CLI::Option* context;
  CLI::Option* device;
};
/// --size, --format, --min-distance, --shader-dir, --context and --device (--scene and --seed
/// are added by the commands that read them). `default_size` is shown in the help.
common_option_handles add_common_options(CLI::App& command, common_options& options, const std::string& default_size);

/// A headless GL context and the shader library: what every drawing command opens first.
struct headless_session {
  explicit headless_session(const common_options& options) : context(create_headless_context(options.headless())), shaders(options.shaders()) {}
  std::unique_ptr<gl_context> context;
  shader_library shaders;
};

/// --scene, with `default_scene` shown in the help.
CLI::Option* add_scene_option(CLI::App& command, common_options& options, const std::string& default_scene);

/// --camera and --light (poses "x,y,z,tx,ty,tz", frontend/scene/pose.hpp), which move the
/// scene's camera and light before the first frame (every technique and method reads them).
void add_pose_options(CLI::App& command, common_options& options);

/// The camera and light moved to --camera and --light where given. Throws usage_error naming the
/// option when the scene cannot take the pose (e.g. a camera looking along its up vector).
void apply_poses(const common_options& options, camera& view, scene_light& light);
void apply_poses(const common_options& options, camera& view, spot_light<float>& light);

/// A built-in scene by name or an .obj, .gltf or .glb file, checked (finite, in range) before it
/// is used, with --camera and --light applied.
scene load_scene(const common_options& options, const std::string& name);

}  // namespace vplkit::cli
