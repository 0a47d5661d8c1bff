#include "frontend/cli/options.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <optional>
#include <set>
#include <sstream>

#include <vplkit/irradiance.hpp>
#include <vplkit/gl/program.hpp>

#include "frontend/core/error.hpp"
#include "frontend/core/parallel.hpp"
#include "frontend/core/progress.hpp"
#include "frontend/core/setting.hpp"
#include "frontend/image/image.hpp"
#include "frontend/scene/gltf_scene.hpp"
#include "frontend/scene/obj_loader.hpp"
#include "frontend/scene/pose.hpp"

namespace vplkit::cli {

namespace fs = std::filesystem;

std::string shown(std::string_view text) { return quote_for_message(text); }

bool is_glsl_identifier(std::string_view name) {
  if (name.empty() || (name[0] >= '0' && name[0] <= '9')) return false;
  for (char c : name)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_')) return false;
  return true;
}

std::string format_number(float value) {
  std::ostringstream out;
  out << value;
  return out.str();
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

CLI::Option* option_scope::add(CLI::Option* option, std::string readers, std::function<bool(const std::string&)> reads) {
  options_.push_back({option, std::move(readers), std::move(reads)});
  return option;
}

std::string option_scope::unread_by(const std::string& choice, const std::string& what) const {
  for (const scoped& entry : options_)
    if (entry.option->count() > 0 && !entry.reads(choice)) return entry.option->get_name() + " is read by " + entry.readers + ", not by " + what + " " + choice;
  return {};
}

void option_scope::require_read_by(const std::string& choice, const std::string& what) const {
  if (const std::string message = unread_by(choice, what); !message.empty()) throw usage_error(message);
}

headless_request common_options::headless() const {
  headless_request request;
  request.api = headless_api_from_name(context, "--context");
  request.device = device;
  return request;
}

fs::path common_options::shaders() const {
  // The variable stands for the option and is checked like it, each named in its message.
  std::error_code ignored;
  if (!shader_dir.empty()) {
    if (!fs::is_directory(shader_dir, ignored)) throw error("shader directory not found: " + excerpt_path(shader_dir) + " (--shader-dir)");
    return shader_dir;
  }
  if (const char* from_environment = std::getenv("VPLKIT_SHADER_DIR"); from_environment && *from_environment && !fs::is_directory(from_environment, ignored))
    throw error("shader directory not found: " + excerpt_path(from_environment) + " (VPLKIT_SHADER_DIR, which stands for --shader-dir)");
  return default_shader_dir();
}

void check_environment() {
  try {
    (void)headless_api_from_environment();
    (void)egl_device_from_environment();
    (void)hardware_threads();
    (void)progress_interval_from_environment();
  } catch (const vplkit::error& failure) {
    throw usage_error(failure.what());
  }
}

common_option_handles add_common_options(CLI::App& command, common_options& options) {
  common_option_handles handles{};
  handles.shader_dir = command.add_option("--shader-dir", options.shader_dir,
                                         "folder with the vplkit shaders (default: $VPLKIT_SHADER_DIR, else the source tree's for a build tree's vplkit, else the installed ones beside it)");
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
      ->each([&options](const std::string& name) {
        options.scene = name;
        options.scene_given = true;
      });
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
              "start from this light (the first of --lights): a spot light's position and the point it aims at; a directional light "
              "shines from the first point towards the second; a point light moves to the first point");
  command
      .add_option_function<std::string>(
          "--lights",
          [&options](const std::string& text) {
            std::string problem;
            options.light_choice = parse_light_choice(text, problem);
            if (!problem.empty()) throw CLI::ValidationError("--lights", problem + ", got " + shown(text));
          },
          "which of the scene's lights are drawn: all (the default), none, or their indices in the file's order (0,2); at most " +
              std::to_string(max_scene_lights))
      ->type_name("all|none|i,j");
  command
      .add_option_function<float>(
          "--light-intensity", [&options](const float& value) { options.light_intensity = value; },
          "the light's radiant intensity, W/sr (a spot or point light), or irradiance, W/m^2 (a directional light), instead of the "
          "scene's; its colour is kept (the brightest channel becomes this); several lights are scaled together, the brightest to this; "
          "every output is linear in it")
      ->check(number_in(0.0, 1.0e12, false, "W/sr or W/m^2"))
      ->type_name("W");
}

CLI::Option* add_exposure_option(CLI::App& command, common_options& options) {
  return command
      .add_option_function<std::string>(
          "--exposure",
          [&options](const std::string& text) {
            if (text == "auto") {
              options.auto_exposure = true;
              return;
            }
            options.auto_exposure = false;
            options.exposure_ev = static_cast<float>(std::stod(text));
          },
          "the final image's PNG scaled by 2^EV before the sRGB curve, or auto: the EV that puts the 99th percentile of its luminance at 0.8 "
          "(printed); the PFMs stay linear [0]")
      ->check(CLI::Validator(
          [](std::string& text) {
            if (text == "auto") return std::string();
            double value = 0.0;
            return CLI::detail::lexical_cast(text, value) && value >= -32.0 && value <= 32.0 ? std::string()
                                                                                              : "must be auto or a number in [-32, 32] (EV), got " + shown(text);
          },
          "EV|auto"))
      ->type_name("EV|auto");
}

float exposure_scale(const common_options& options, const image& linear, std::ostream& out) {
  if (!options.auto_exposure) return std::exp2(options.exposure_ev);
  const float scale = percentile_exposure(linear);
  out << "exposure: auto, " << format_number(std::log2(scale)) << " EV\n";
  return scale;
}

namespace {

// --light-intensity: the colours kept, the brightest channel of the brightest light set to the
// intensity, the others scaled with it.
void apply_light_intensity(const common_options& options, std::vector<scene_light>& lights) {
  if (options.light_intensity) scale_light_intensities(lights, *options.light_intensity);
}

}  // namespace

std::optional<std::vector<std::size_t>> parse_light_choice(const std::string& text, std::string& problem) {
  problem.clear();
  if (text == "all") return std::nullopt;
  std::vector<std::size_t> chosen;
  if (text == "none") return chosen;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string item = text.substr(start, comma - start);
    if (item.empty() || item.size() > 3 || item.find_first_not_of("0123456789") != std::string::npos) {
      problem = "expected all, none or light indices separated by commas (0,2)";
      return std::nullopt;
    }
    const std::size_t index = static_cast<std::size_t>(std::stoul(item));
    if (std::find(chosen.begin(), chosen.end(), index) != chosen.end()) {
      problem = "light " + item + " is chosen twice";
      return std::nullopt;
    }
    chosen.push_back(index);
    start = comma + 1;
  }
  return chosen;
}

void apply_poses(const common_options& options, camera& view, std::vector<scene_light>& lights) {
  try {
    if (options.light_choice) {
      std::vector<scene_light> chosen;
      for (const std::size_t index : *options.light_choice) {
        if (index >= lights.size())
          throw vplkit::error("--lights: the scene has no light " + std::to_string(index) + " (it has " + std::to_string(lights.size()) +
                              (lights.empty() ? "" : ", 0 to " + std::to_string(lights.size() - 1)) + ")");
        chosen.push_back(lights[index]);
      }
      lights = std::move(chosen);
    }
    if (options.camera_pose) apply_pose(*options.camera_pose, view, "--camera");
    if (options.light_pose) {
      if (lights.empty()) throw vplkit::error("--light: the scene has no light to place (--lights none, or a file without lights)");
      apply_pose(*options.light_pose, lights.front(), "--light");
    }
    apply_light_intensity(options, lights);
  } catch (const vplkit::error& failure) {
    throw usage_error(failure.what());
  }
}

void apply_poses(const common_options& options, pipeline& target) {
  try {
    if (options.camera_pose) {
      camera view = target.current_camera();
      apply_pose(*options.camera_pose, view, "--camera");
      target.set_camera(view);
    }
    if (options.light_choice) throw vplkit::error("--lights: this technique builds its own scene; its light is not chosen from a file");
    if (options.light_pose || options.light_intensity) {
      std::vector<scene_light> lights = target.current_lights();
      if (options.light_pose) apply_pose(*options.light_pose, lights.front(), "--light");
      apply_light_intensity(options, lights);
      for (std::size_t k = 0; k < lights.size(); ++k) target.set_light(k, lights[k]);
    }
  } catch (const vplkit::error& failure) {
    throw usage_error(failure.what());
  }
}

scene load_scene(const common_options& options, const std::string& name) {
  const std::string extension = fs::path(name).extension().string();
  scene loaded = extension == ".obj"                          ? frame_mesh(fs::path(name).stem().string(), load_obj(name))
                 : extension == ".gltf" || extension == ".glb" ? load_gltf(name)
                                                               : built_in_scene(name);
  apply_poses(options, loaded.view, loaded.lights);
  check_scene(loaded);
  // std::cout, not a session's stream: loading happens after the dry run stops, where a command
  // writes to standard output.
  // A scene loaded again (render's frame without visibility, the sweep's configurations) prints
  // its notes once.
  static std::set<std::string> printed;
  for (const std::string& note : loaded.notes)
    if (printed.insert(note).second) std::cout << "note: " << note << "\n";
  return loaded;
}

}  // namespace vplkit::cli
