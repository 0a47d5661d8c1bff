#include "frontend/cli/options.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include <vplkit/irradiance.hpp>
#include <vplkit/gl/program.hpp>

#include "frontend/core/error.hpp"
#include "frontend/image/image.hpp"
#include "frontend/scene/gltf_scene.hpp"
#include "frontend/scene/obj_loader.hpp"
#include "frontend/scene/pose.hpp"

namespace vplkit::cli {

namespace fs = std::filesystem;

std::string shown(std::string_view text) {
  constexpr std::size_t limit = 60;
  return "'" + std::string(text.substr(0, limit)) + (text.size() > limit ? "...' (" + std::to_string(text.size()) + " characters)" : "'");
}

std::string format_number(float value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

namespace {

// A whole number of 1 to 6 digits at the start of `text`, which then starts after it.
std::optional<int> take_side(std::string_view& text) {
  std::size_t digits = 0;
  while (digits < text.size() && digits <= 6 && text[digits] >= '0' && text[digits] <= '9') ++digits;
  if (digits == 0 || digits > 6) return std::nullopt;
  int value = 0;
  std::from_chars(text.data(), text.data() + digits, value);
  text.remove_prefix(digits);
  return value;
}

}  // namespace

std::string parse_size(const std::string& text, int& width, int& height) {
  const std::string expected = "expected N or WxH (for example 512 or 640x480), got " + shown(text);
  std::string_view rest = text;
  const std::optional<int> w = take_side(rest);
  if (!w) return expected;
  std::optional<int> h = w;
  if (!rest.empty()) {
    if (rest[0] != 'x') return expected;
    rest.remove_prefix(1);
    h = take_side(rest);
    if (!h || !rest.empty()) return expected;
  }
  if (*w < 1 || *h < 1 || *w > max_image_side || *h > max_image_side)
    return "each side must be in [1, " + std::to_string(max_image_side) + "], got " + shown(text);
  width = *w;
  height = *h;
  return {};
}

std::string parse_position(const std::string& text, glm::vec3& position, float limit) {
  float values[3];
  if (!parse_number_list(text, values, 3, limit))
    return "expected x,y,z, each a finite number within +-" + format_number(limit) + " (for example 0,0.7,0), got " + shown(text);
  position = glm::vec3(values[0], values[1], values[2]);
  return {};
}

CLI::Validator number_in(double low, double high, bool low_open, const std::string& what) {
  const std::string range = std::string(low_open ? "(" : "[") + format_number(static_cast<float>(low)) + ", " + format_number(static_cast<float>(high)) + "]";
  return CLI::Validator(
      [=](std::string& text) {
        double value = 0.0;
        const bool in_range = CLI::detail::lexical_cast(text, value) && (low_open ? value > low : value >= low) && value <= high;
        return in_range ? std::string() : "must be a number in " + range + " (" + what + "), got " + shown(text);
      },
      range);
}

CLI::Validator positive_number(const std::string& what) { return number_in(0.0, std::numeric_limits<float>::max(), true, what); }

CLI::Option* option_scope::add(CLI::Option* option, std::string readers, std::function<bool(const std::string&)> reads) {
  options_.push_back({option, std::move(readers), std::move(reads)});
  return option;
}

void option_scope::require_read_by(const std::string& choice, const std::string& what) const {
  for (const scoped& entry : options_)
    if (entry.option->count() > 0 && !entry.reads(choice))
      throw usage_error(entry.option->get_name() + " is read by " + entry.readers + ", not by " + what + " " + choice);
}

headless_request common_options::headless() const {
  headless_request request;
  request.api = headless_api_from_name(context, "--context");
  request.device = device;
  return request;
}

fs::path common_options::shaders() const { return shader_dir.empty() ? default_shader_dir() : fs::path(shader_dir); }

common_option_handles add_common_options(CLI::App& command, common_options& options, const std::string& default_size) {
  options.min_distance = irradiance_settings<float>().min_distance;
  common_option_handles handles{};
  handles.size = command.add_option("--size", options.size_text, "final image size, N or WxH [" + default_size + "]")
      ->check(CLI::Validator(
          [&options](std::string& text) {
            options.size_given = true;
            return parse_size(text, options.width, options.height);
          },
          "N|WxH"));
  handles.format = command.add_option("--format", options.format, "float format of the render targets (the RSM is packed: RGBA32UI)")
      ->check(CLI::IsMember({"rgba16f", "rgba32f"}))->capture_default_str();
  handles.min_distance = command.add_option("--min-distance", options.min_distance, "distance clamp of the light terms, scene units (irradiance_settings::min_distance)")
      ->check(positive_number("scene units"))->capture_default_str();
  handles.shader_dir = command.add_option("--shader-dir", options.shader_dir,
                                         "folder with the vplkit shaders (default: $VPLKIT_SHADER_DIR, then the built-in path)");
  handles.context = command.add_option("--context", options.context,
                                      "headless context: auto ($VPLKIT_CONTEXT, else EGL, else OSMesa), egl (a device, else surfaceless), egl-surfaceless or osmesa (vplkit info lists them)")
                        ->check(CLI::IsMember(headless_api_names()))->capture_default_str();
  handles.device = command.add_option("--device", options.device, "EGL device index (default: $VPLKIT_EGL_DEVICE, else the first GPU, else software)")
                       ->check(CLI::Range(0, 1024));
  return handles;
}

CLI::Option* add_scene_option(CLI::App& command, common_options& options, const std::string& default_scene) {
  return command
      .add_option("--scene", options.scene,
                  "built-in scene (" + [] {
                    std::string names;
                    for (const std::string& name : built_in_scene_names()) names += (names.empty() ? "" : ", ") + name;
                    return names;
                  }() + ") or an .obj, .gltf or .glb file [" + default_scene + "]")
      ->each([&options](const std::string&) { options.scene_given = true; });
}

void add_pose_options(CLI::App& command, common_options& options) {
  const auto pose_option = [&command](const std::string& name, std::optional<pose>& target, const std::string& help) {
    return command
        .add_option_function<std::string>(
            name,
            [&target, name](const std::string& text) {
              pose parsed;
              if (const std::string problem = parse_pose(text, parsed); !problem.empty()) throw CLI::ValidationError(name, problem + ", got " + shown(text));
              target = parsed;
            },
            help)
        ->type_name("x,y,z,tx,ty,tz");
  };
  pose_option("--camera", options.camera_pose, "start from this camera: its position and the point it looks at (the viewer prints its pose)");
  pose_option("--light", options.light_pose,
              "start from this light: a spot light's position and the point it aims at; a directional light shines from the first point "
              "towards the second");
}

void apply_poses(const common_options& options, camera& view, scene_light& light) {
  try {
    if (options.camera_pose) apply_pose(*options.camera_pose, view, "--camera");
    if (options.light_pose) apply_pose(*options.light_pose, light, "--light");
  } catch (const vplkit::error& failure) {
    throw usage_error(failure.what());
  }
}

void apply_poses(const common_options& options, camera& view, spot_light<float>& light) {
  scene_light spot;
  spot.spot = light;
  apply_poses(options, view, spot);
  light = spot.spot;
}

scene load_scene(const common_options& options, const std::string& name) {
  const std::string extension = fs::path(name).extension().string();
  scene loaded = extension == ".obj"                          ? frame_mesh(fs::path(name).stem().string(), load_obj(name))
                 : extension == ".gltf" || extension == ".glb" ? load_gltf(name)
                                                               : built_in_scene(name);
  apply_poses(options, loaded.view, loaded.light);
  check_scene(loaded);
  return loaded;
}

}  // namespace vplkit::cli
