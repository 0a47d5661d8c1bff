// What every subcommand of the command line shares: the session (where messages go, whether it
// is a dry run), a checked number parser, the scene and pose options, and option scoping, with
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
#include "frontend/techniques/pipeline.hpp"

namespace vplkit::cli {

/// Where a command writes and whether it runs at all: a dry run parses and checks every option and
/// stops before it opens a context or reads a file (the option fuzzer runs the CLI that way).
struct session {
  std::ostream& out;
  bool dry_run = false;
};

/// The exit code of a run that --max-seconds cut short after writing a complete part of its work
/// (render --poses: frames 1 to k): neither success (0) nor a failure that wrote nothing (1, 2).
constexpr int exit_stopped_by_deadline = 3;

/// A command line that parses but asks for something inconsistent (exit 2, like a parse error).
class usage_error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An argument as a message shows it: quoted, and cut after 60 characters.
std::string shown(std::string_view text);

/// Whether `name` is a GLSL identifier: a letter or '_', then letters, digits and '_'.
bool is_glsl_identifier(std::string_view name);

/// A float as a message shows it (ostream's default format).
std::string format_number(float value);

/// A number in [low, high] (or (low, high] when low_open); NaN and infinities fail.
CLI::Validator number_in(double low, double high, bool low_open, const std::string& what);

/// Options that only some choices (techniques of `render`, methods of `reference`) read.
class option_scope {
 public:
  /// `option` is read only when reads(choice); `readers` says by whom, for the message.
  CLI::Option* add(CLI::Option* option, std::string readers, std::function<bool(const std::string&)> reads);
  /// The message for the first option given on the command line that `choice` does not read:
  /// "--ray-angle is read by ..., not by technique rsm-alg6"; "" when there is none.
  std::string unread_by(const std::string& choice, const std::string& what) const;
  /// Throws usage_error with unread_by's message.
  void require_read_by(const std::string& choice, const std::string& what) const;

 private:
  struct scoped {
    const CLI::Option* option;
    std::string readers;
    std::function<bool(const std::string&)> reads;
  };
  std::vector<scoped> options_;
};

/// What every drawing command reads besides the technique's settings: the scene and the poses,
/// where the shaders are, and which headless context to open.
struct common_options {
  std::string scene;
  bool scene_given = false;     ///< the default scene is the technique family's
  std::string shader_dir;
  std::string context = "auto";  ///< headless context: a name of headless_api_names()
  int device = -1;               ///< EGL device index, -1: automatic
  std::optional<pose> camera_pose;  ///< --camera: instead of the scene's camera
  std::optional<pose> light_pose;   ///< --light: where the first of the chosen lights is
  /// --light-intensity: the light's radiant intensity (W/sr, a spot or point light) or
  /// irradiance (W/m^2, a sun) instead of the scene's, its colour kept (the brightest channel
  /// becomes this); several lights are scaled together (scale_light_intensities).
  std::optional<float> light_intensity;
  /// --lights: which of the scene's lights are drawn, by index in the file's order; absent: all.
  std::optional<std::vector<std::size_t>> light_choice;
  /// --exposure: the final PNG (and the viewer's image) is scaled by 2^EV; auto_exposure picks EV
  /// from the image (exposure_scale). PFMs stay linear.
  float exposure_ev = 0.0f;
  bool auto_exposure = false;
  headless_request headless() const;
  /// --shader-dir, else $VPLKIT_SHADER_DIR, else default_shader_dir(); throws vplkit::error
  /// naming the option or the variable when it is not a folder.
  std::filesystem::path shaders() const;
};

/// The environment variables that stand for options (VPLKIT_CONTEXT for --context,
/// VPLKIT_EGL_DEVICE for --device, VPLKIT_THREADS, VPLKIT_PROGRESS_SECONDS) checked like them:
/// throws usage_error naming the variable for a malformed value, before a command runs.
/// (VPLKIT_SHADER_DIR is checked where shaders are read, like --shader-dir.)
void check_environment();

/// The options add_common_options registered, for a command that scopes some of them.
struct common_option_handles {
  CLI::Option* shader_dir;
  CLI::Option* context;
  CLI::Option* device;
};
/// --shader-dir, --context and --device.
common_option_handles add_common_options(CLI::App& command, common_options& options);

/// A headless GL context and the shader library: what every drawing command opens first.
struct headless_session {
  explicit headless_session(const common_options& options) : context(create_headless_context(options.headless())), shaders(options.shaders()) {}
  std::unique_ptr<gl_context> context;
  shader_library shaders;
};

/// --scene, with `default_scene` shown in the help (several when `several`: the sweep's).
CLI::Option* add_scene_option(CLI::App& command, common_options& options, const std::string& default_scene);

/// --camera and --light (poses "x,y,z,tx,ty,tz", frontend/scene/pose.hpp), which move the
/// scene's camera and light before the first frame, and --light-intensity (every technique and
/// method reads them).
void add_pose_options(CLI::App& command, common_options& options);

/// --exposure EV|auto (the final image's PNG; the viewer's image).
CLI::Option* add_exposure_option(CLI::App& command, common_options& options);

/// The lights chosen by --lights, the camera and the first light moved to --camera and --light
/// where given, and the lights' intensity set by --light-intensity. Throws usage_error naming
/// the option when the scene cannot take it (a light index it does not have, a camera looking
/// along its up vector, --light without a light).
void apply_poses(const common_options& options, camera& view, std::vector<scene_light>& lights);
/// --lights' text: nullopt for all, the indices otherwise (none: empty); `problem` says what is
/// wrong with a bad text (nullopt then too).
std::optional<std::vector<std::size_t>> parse_light_choice(const std::string& text, std::string& problem);
/// The same for a pipeline that built its own scene (final gathering).
void apply_poses(const common_options& options, pipeline& target);

/// The scale --exposure gives `linear`'s PNG: 2^EV, or with auto the percentile_exposure of the
/// image (its 99th luminance percentile at 0.8), which it then prints as an EV to `out`.
float exposure_scale(const common_options& options, const image& linear, std::ostream& out);

/// A built-in scene by name or an .obj, .gltf or .glb file, checked (finite, in range) before it
/// is used, with --camera, --light and --light-intensity applied. The scene's notes (what a glTF
/// reader did not read, how a camera or light was placed) go to standard output.
scene load_scene(const common_options& options, const std::string& name);

}  // namespace vplkit::cli
