// The vplkit command line: `info`, `render` (headless, the main job), `view` (a window),
// `compare` and `reference`. Every option is range-checked as it is parsed (non-finite numbers
// included); the checks that need several options run before anything is opened or read.
#include "frontend/cli.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <iomanip>
#include <optional>
#include <charconv>
#include <new>
#include <string_view>
#include <functional>
#include <sstream>

#include <vplkit/version.hpp>

#include "frontend/context.hpp"
#include "frontend/debug_output.hpp"
#include "frontend/error.hpp"
#include "frontend/final_gather_pipeline.hpp"
#include "frontend/files.hpp"
#include "frontend/image_io.hpp"
#include "frontend/image_metrics.hpp"
#include "frontend/reference.hpp"
#include "frontend/parallel.hpp"
#include "frontend/lightwave_pipeline.hpp"
#include "frontend/obj_loader.hpp"
#include "frontend/program.hpp"
#include "frontend/render_images.hpp"
#include "frontend/rsm_pipeline.hpp"
#include "frontend/scene.hpp"

namespace {

namespace fs = std::filesystem;

// Largest image side the CLI accepts before asking GL; GL_MAX_TEXTURE_SIZE is checked later.
constexpr int max_image_side = 16384;

// An argument as a message shows it: quoted, and cut after 60 characters.
std::string shown(std::string_view text) {
  constexpr std::size_t limit = 60;
  return "'" + std::string(text.substr(0, limit)) + (text.size() > limit ? "...' (" + std::to_string(text.size()) + " characters)" : "'");
}

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

// "512" or "640x480".
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

std::string format_number(float value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// A number in [low, high] (or (low, high] when low_open); NaN and infinities fail.
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

struct render_options {
  std::string scene_name = "cornell-box";
  bool scene_given = false;  // the default scene and size depend on the technique
  bool size_given = false;
  std::string size_text = "512";
  std::string format = "rgba16f";
  std::string filter = "separable";
  std::string shader_dir;
  vplkit::rsm_pipeline_settings settings;
  vplkit::lightwave_settings lightwave;
  vplkit::final_gather_settings final_gather;
  std::string lightwave_shadow_variant = "importance";
  std::string preset = "default";             // rsm_gather_preset: "default" or "thesis"
  std::optional<int> paths, samples_per_path, slots;  // explicit values override the preset
  std::optional<float> radius, max_radius_texels;
  bool raw_indirect = false;
  std::string object = "sphere";
  std::string object_position_text = "0,0.7,0";
  glm::vec3 object_position{0.0f, 0.7f, 0.0f};
  float object_size = 0.5f;
};

// Largest coordinate of --object-position: the room is [-1, 1] x [0, 2] x [-1, 1].
constexpr float max_object_coordinate = 1000.0f;

// "x,y,z", spaces allowed around the numbers.
std::string parse_position(const std::string& text, glm::vec3& position) {
  const std::string expected = "expected x,y,z (for example 0,0.7,0), got " + shown(text);
  std::string_view rest = text;
  glm::vec3 parsed(0.0f);
  for (int axis = 0; axis < 3; ++axis) {
    const std::size_t comma = rest.find(',');
    if ((axis < 2) != (comma != std::string_view::npos)) return expected;
    std::string_view number = rest.substr(0, comma);
    rest = comma == std::string_view::npos ? std::string_view() : rest.substr(comma + 1);
    while (!number.empty() && number.front() == ' ') number.remove_prefix(1);
    while (!number.empty() && number.back() == ' ') number.remove_suffix(1);
    if (number.size() > 1 && number[0] == '+' && number[1] != '-') number.remove_prefix(1);
    const auto [end, code] = std::from_chars(number.data(), number.data() + number.size(), parsed[axis]);
    if (number.empty() || code != std::errc() || end != number.data() + number.size() || !std::isfinite(parsed[axis]) ||
        std::fabs(parsed[axis]) > max_object_coordinate)
      return "each of x,y,z must be a finite number within +-" + format_number(max_object_coordinate) + ", got " + shown(text);
  }
  position = parsed;
  return {};
}

void add_render_options(CLI::App& command, render_options& options) {
  std::vector<std::string> techniques;
  for (const vplkit::rsm_technique& technique : vplkit::rsm_techniques()) techniques.push_back(technique.name);
  for (const vplkit::lightwave_technique& technique : vplkit::lightwave_techniques()) techniques.push_back(technique.name);
  for (const vplkit::final_gather_technique& technique : vplkit::final_gather_techniques()) techniques.push_back(technique.name);
  vplkit::rsm_pipeline_settings& s = options.settings;
  vplkit::lightwave_settings& lw = options.lightwave;
  command.add_option("--technique", s.technique, "rendering technique (rsm-*: paper 000, lightwave-*: paper 003)")
      ->check(CLI::IsMember(techniques))->capture_default_str();
  command.add_option("--scene", options.scene_name,
                     "built-in scene (cornell-box, indirect-shadow, instanced, boxes, teapot, teapots) or an .obj file "
                     "[cornell-box; boxes for lightwave-*]")
      ->each([&](const std::string&) { options.scene_given = true; });
  command.add_option("--size", options.size_text, "final image size, N or WxH [512; 1280x720 for lightwave-*]")
      ->check(CLI::Validator(
          [&](std::string& text) {
            options.size_given = true;
            return parse_size(text, s.width, s.height);
          },
          "N|WxH"));
  command.add_option("--rsm-size", s.rsm_size, "square RSM resolution")->check(CLI::Range(1, max_image_side))->capture_default_str();
  command.add_option("--indirect-divisor", s.indirect_divisor, "indirect buffer = image / this per axis (2: half, 1: full)")
      ->check(CLI::IsMember({1, 2, 4, 8}))->capture_default_str();
  command.add_option("--format", options.format, "float format of every render target")
      ->check(CLI::IsMember({"rgba16f", "rgba32f"}))->capture_default_str();
  const vplkit::rsm_gather_preset<float> defaults = vplkit::default_rsm_gather_preset<float>();
  const vplkit::rsm_gather_preset<float> thesis = vplkit::thesis_rsm_gather_preset<float>();
  command.add_option("--preset", options.preset,
                     "RSM gather: default (radius " + format_number(defaults.radius_fraction) + " of the RSM, " + std::to_string(defaults.paths) + "x" +
                         std::to_string(defaults.samples_per_path) + " samples, " + std::to_string(defaults.slots) + " slots; docs/rsm-study.md) or thesis (" +
                         format_number(thesis.radius_fraction) + ", " + std::to_string(thesis.paths) + "x" + std::to_string(thesis.samples_per_path) +
                         ", " + std::to_string(thesis.slots) + " slots); the options below override it")
      ->check(CLI::IsMember({"default", "thesis"}))->capture_default_str();
  command.add_option("--paths", options.paths, "radial pattern: paths [preset]")->check(CLI::Range(1, 256));
  command.add_option("--samples-per-path", options.samples_per_path, "radial pattern: samples per path [preset]")->check(CLI::Range(1, 256));
  command.add_option("--radius", options.radius, "sampling radius (radial and disk) as a fraction of the RSM side [preset]")
      ->check(number_in(0.0, 2.0, true, "a fraction of the RSM side"));
  command.add_option("--max-radius", options.max_radius_texels, "sampling radius in RSM texels (instead of --radius)")
      ->check(positive_number("RSM texels"));
  command.add_option("--slots", options.slots, "micro linear buffer slots [preset]")->check(CLI::Range(1, 16));
  command.add_option("--disk-samples", s.disk.samples, "original RSM: samples")->check(CLI::Range(1, 65536))->capture_default_str();
  command.add_option("--seed", s.radial.seed, "seed of the sampling patterns")->capture_default_str();
  command.add_option("--min-distance", s.irradiance.min_distance,
                     "distance clamp of the light terms, scene units (irradiance_settings::min_distance)")
      ->check(positive_number("scene units"))->capture_default_str();
  command.add_option("--post-filter", options.filter, "bilateral post filter: full 2D kernel or separable")
      ->check(CLI::IsMember({"full", "separable"}))->capture_default_str();
  command.add_option("--ray-angle", lw.angle_deg, "Light Wave: degrees between VPL rays (divides 90 and 360)")
      ->check(CLI::Range(1, 90))->capture_default_str();
  command.add_option("--vpls-per-ray", lw.per_ray, "Light Wave: VPLs per ray (stacked hemispheres)")->check(CLI::Range(1, 32))->capture_default_str();
  command.add_option("--vpl-max-distance", lw.max_distance, "Light Wave: distance the hemispheres approach (0: from the scene's size)")
      ->check(number_in(0.0, vplkit::max_scene_coordinate, false, "scene units"))->capture_default_str();
  command.add_option("--shadow-maps", lw.accurate_maps, "Light Wave: VPL shadow maps of the accurate shadows (0: none)")
      ->check(CLI::Range(0, 64))->capture_default_str();
  command.add_option("--shadow-variant", options.lightwave_shadow_variant,
                     "Light Wave: importance (VPLs drawn by their light on the scene, maps aimed at it, lookups weighted by each VPL's light) "
                     "or thesis (uniform VPLs, maps along their normals, the plain mean)")
      ->check(CLI::IsMember({"importance", "thesis"}))->capture_default_str();
  command.add_option("--integrated-steps", lw.integrated_steps, "Light Wave: in-between lookups per pair of maps")->check(CLI::Range(0, 64))->capture_default_str();
  command.add_option("--shadow-map-scale", lw.shadow_map_scale, "Light Wave: shadow map size in screens")
      ->check(number_in(0.0, 16.0, true, "screens"))->capture_default_str();
  command.add_option("--faked-multiplier", lw.faked_multiplier, "Light Wave: m of Eq. 5.2 (the thesis uses 1.1 to 1.5)")
      ->check(number_in(0.5, 4.0, false, "Eq. 5.2"))->capture_default_str();
  vplkit::final_gather_settings& fg = options.final_gather;
  command.add_option("--object", options.object, "final gathering: the dynamic object, sphere or an .obj file (meshes/bunny.obj)")
      ->capture_default_str();
  command.add_option("--object-position", options.object_position_text, "final gathering: the object's centre x,y,z (the room is [-1,1]x[0,2]x[-1,1]; each within +-1000)")
      ->check(CLI::Validator([&](std::string& text) { return parse_position(text, options.object_position); }, "x,y,z"))
      ->capture_default_str();
  command.add_option("--object-size", options.object_size, "final gathering: the object's size across (the room is 2 wide)")
      ->check(number_in(0.0, 10.0, true, "scene units"))->capture_default_str();
  command.add_option("--cube-resolution", fg.resolution, "final gathering: M, the small cube map's face resolution (4 or 2)")
      ->check(CLI::Range(1, 64))->capture_default_str();
  command.add_option("--face-size", fg.face_size, "final gathering: the cube map's face size before averaging")->check(CLI::Range(1, 4096))->capture_default_str();
  command.add_option("--shader-dir", options.shader_dir,
                     "folder with the vplkit shaders (default: $VPLKIT_SHADER_DIR, then the built-in path)");
}

bool is_lightwave(const render_options& options) { return options.settings.technique.rfind("lightwave-", 0) == 0; }
bool is_final_gather(const render_options& options) {
  return options.settings.technique.rfind("finalgather-", 0) == 0 || options.settings.technique == "envmap";
}

void finish_settings(render_options& options) {
  vplkit::rsm_pipeline_settings& s = options.settings;
  if (is_lightwave(options)) {
    if (!options.scene_given) options.scene_name = "boxes";
    vplkit::lightwave_settings& lw = options.lightwave;
    lw.technique = s.technique;
    if (options.size_given) {
      lw.width = s.width;
      lw.height = s.height;
    }
    lw.format = options.format == "rgba32f" ? vplkit::texel_format::rgba32f : vplkit::texel_format::rgba16f;
    lw.irradiance = s.irradiance;
    lw.seed = s.radial.seed;
    lw.shadow_variant = options.lightwave_shadow_variant == "thesis" ? vplkit::lightwave_shadow_variant::thesis : vplkit::lightwave_shadow_variant::importance;
  }
  s.format = options.format == "rgba32f" ? vplkit::texel_format::rgba32f : vplkit::texel_format::rgba16f;
  s.filter = options.filter == "separable" ? vplkit::post_filter::separable : vplkit::post_filter::full;
  s.apply(options.preset == "thesis" ? vplkit::thesis_rsm_gather_preset<float>() : vplkit::default_rsm_gather_preset<float>());
  if (options.paths) s.radial.paths = *options.paths;
  if (options.samples_per_path) s.radial.samples_per_path = *options.samples_per_path;
  if (options.slots) s.slots = *options.slots;
  if (options.radius && options.max_radius_texels) throw vplkit::error("give the sampling radius once: --radius (a fraction of the RSM side) or --max-radius (texels)");
  if (options.radius) s.radius = *options.radius;
  if (options.max_radius_texels) s.radius = *options.max_radius_texels / static_cast<float>(s.rsm_size);
  s.disk.seed = s.radial.seed;
}

vplkit::output_file png_file(fs::path path, int width, int height, std::vector<std::uint8_t> pixels) {
  return {std::move(path), [width, height, pixels = std::move(pixels)] { return vplkit::encode_png(width, height, pixels); }};
}

vplkit::output_file pfm_file(fs::path path, vplkit::float_image image) {
  return {std::move(path), [image = std::move(image)] { return vplkit::encode_pfm(image); }};
}

// Where a command writes and whether it runs at all: a dry run parses and checks every option and
// stops before it opens a context or reads a file (the option fuzzer runs the CLI that way).
struct session {
  std::ostream& out;
  bool dry_run = false;
};

vplkit::scene load_scene(const std::string& name) {
  vplkit::scene loaded = fs::path(name).extension() == ".obj" ? vplkit::frame_mesh(fs::path(name).stem().string(), vplkit::load_obj(name))
                                                             : vplkit::built_in_scene(name);
  vplkit::check_scene(loaded);
  return loaded;
}

fs::path shader_dir(const render_options& options) {
  return options.shader_dir.empty() ? vplkit::default_shader_dir() : fs::path(options.shader_dir);
}

// "output/cornell-box.png" + "-indirect" -> "output/cornell-box-indirect.png"
fs::path with_suffix(const fs::path& path, const std::string& suffix) {
  return path.parent_path() / (path.stem().string() + suffix + path.extension().string());
}

fs::path with_extension(fs::path path, const std::string& extension) { return path.replace_extension(extension); }

int run_info(const session& io, const std::string& context_kind) {
  if (io.dry_run) return 0;
  std::unique_ptr<vplkit::gl_context> context;
  if (context_kind == "window") context = std::make_unique<vplkit::window_context>(64, 64, "vplkit info");
  else context = vplkit::create_headless_context();
  io.out << "vplkit " << vplkit::version_string << "\ncontext     " << context->kind() << "\n"
            << vplkit::describe_current_context() << "\nshaders     " << vplkit::default_shader_dir().string() << "\n";
  return 0;
}

int run_lightwave(const session& io, render_options& options, std::string out) {
  const vplkit::lightwave_settings& settings = options.lightwave;
  if (out.empty()) out = "output/" + fs::path(options.scene_name).stem().string() + "-" + settings.technique + ".png";
  const fs::path out_path(out);
  if (out_path.extension() != ".png") throw vplkit::error("--out must name a .png file, got " + shown(out));
  if (const std::string problem = vplkit::validate(settings); !problem.empty()) throw vplkit::error(problem);
  if (io.dry_run) return 0;
  auto context = vplkit::create_headless_context();
  const vplkit::shader_library shaders(shader_dir(options));
  const vplkit::scene source = load_scene(options.scene_name);
  vplkit::lightwave_pipeline pipeline(shaders, source, settings);
  // The first frame pays for llvmpipe's shader JIT and its first timer query is garbage; the
  // light is then "moved" onto itself to time a rebuild, and a third frame has nothing to rebuild.
  pipeline.render();
  pipeline.set_light(source.light.spot);
  const vplkit::lightwave_frame first = pipeline.render();
  const vplkit::lightwave_frame frame = pipeline.render();
  std::vector<vplkit::output_file> files{png_file(out_path, frame.width, frame.height, vplkit::to_srgb8(frame.radiance, frame.width, frame.height))};
  if (!pipeline.shadow_casters().empty()) {
    // The indirect shadow factor as grey, linear (1 = white = not shadowed).
    std::vector<float> factor(frame.indirect_shadow.size());
    for (std::size_t i = 0; i < factor.size(); i += 4)
      for (std::size_t c = 0; c < 4; ++c) factor[i + c] = c == 3 ? 1.0f : frame.indirect_shadow[i];
    files.push_back(png_file(with_suffix(out_path, "-indirect-shadow"), frame.width, frame.height, vplkit::to_srgb8(factor, frame.width, frame.height)));
  }
  vplkit::write_all_or_nothing(files);
  const double mebibytes = static_cast<double>(pipeline.shadow_map_bytes()) / (1024.0 * 1024.0);
  io.out << "scene " << source.name << " (" << source.geometry.triangle_count() << " triangles), technique " << settings.technique << ", "
            << frame.width << "x" << frame.height << ", " << pipeline.vpl_count() << " VPLs (" << settings.angle_deg << " degrees, "
            << settings.per_ray << " per ray)\nshadow maps: " << std::fixed << std::setprecision(2) << mebibytes << " MB (Eq. 5.4/5.5)\n"
            << "a frame after the light moved (VPLs and shadow maps rebuilt):\n"
            << vplkit::format_pass_table(first.pass_times) << "next frames (nothing moved):\n"
            << vplkit::format_pass_table(frame.pass_times);
  for (const vplkit::output_file& file : files) io.out << "wrote " << fs::absolute(file.path).string() << "\n";
  return 0;
}

int run_final_gather(const session& io, render_options& options, std::string out) {
  vplkit::final_gather_settings settings = options.final_gather;
  settings.technique = options.settings.technique;
  settings.width = options.settings.width;
  settings.height = options.settings.height;
  settings.irradiance = options.settings.irradiance;
  settings.format = options.format == "rgba32f" ? vplkit::texel_format::rgba32f : vplkit::texel_format::rgba16f;
  if (const std::string problem = vplkit::validate(settings); !problem.empty()) throw vplkit::error(problem);
  if (out.empty()) out = "output/" + fs::path(options.object).stem().string() + "-" + settings.technique + ".png";
  const fs::path out_path(out);
  if (out_path.extension() != ".png") throw vplkit::error("--out must name a .png file, got " + shown(out));
  if (io.dry_run) return 0;
  auto context = vplkit::create_headless_context();
  const vplkit::shader_library shaders(shader_dir(options));
  const vplkit::final_gather_scene source = vplkit::make_final_gather_scene(options.object, options.object_position, options.object_size);
  vplkit::final_gather_pipeline pipeline(shaders, source, settings);
  pipeline.render();  // JIT warm-up; llvmpipe's first timer query is garbage
  const vplkit::final_gather_frame frame = pipeline.render();
  const int w = frame.width, h = frame.height;
  const fs::path indirect_path = with_suffix(out_path, "-indirect");
  vplkit::write_all_or_nothing({png_file(out_path, w, h, vplkit::to_srgb8(frame.radiance, w, h)),
                                png_file(indirect_path, w, h, vplkit::to_srgb8(frame.indirect, w, h, vplkit::percentile_exposure(frame.indirect)))});
  io.out << "object " << source.name << " (" << source.object.triangle_count() << " triangles) at (" << source.reference_point.x << ", "
            << source.reference_point.y << ", " << source.reference_point.z << "), technique " << settings.technique << ", " << w << "x" << h
            << ", cube map 6 x " << settings.face_size << "^2 -> 6 x " << settings.resolution << "^2\n"
            << vplkit::format_pass_table(frame.pass_times) << "wrote " << fs::absolute(out_path).string() << "\nwrote "
            << fs::absolute(indirect_path).string() << "\n";
  return 0;
}

int run_render(const session& io, render_options& options, std::string out) {
  finish_settings(options);
  if (is_lightwave(options)) return run_lightwave(io, options, out);
  if (is_final_gather(options)) return run_final_gather(io, options, out);
  const vplkit::rsm_technique& technique = vplkit::find_rsm_technique(options.settings.technique);
  if (out.empty()) out = "output/" + fs::path(options.scene_name).stem().string() + "-" + technique.name + ".png";
  const fs::path out_path(out);
  if (out_path.extension() != ".png") throw vplkit::error("--out must name a .png file, got " + shown(out));
  if (const std::string problem = vplkit::validate(options.settings); !problem.empty()) throw vplkit::error(problem);
  if (options.raw_indirect && !technique.indirect)
    throw vplkit::error("--raw-indirect: technique " + std::string(technique.name) + " gathers no indirect light");
  if (io.dry_run) return 0;

  auto context = vplkit::create_headless_context();
  const vplkit::shader_library shaders(shader_dir(options));
  const vplkit::scene source = load_scene(options.scene_name);
  vplkit::rsm_pipeline pipeline(shaders, source, options.settings);
  // The first frame pays for llvmpipe's shader JIT, and llvmpipe's first GL_TIME_ELAPSED query
  // reads a garbage start time (seen: 282 s); the pass table reports a warmed-up frame.
  pipeline.render();
  const vplkit::rsm_frame frame = pipeline.render();
  const vplkit::rsm_pass_buffers raw = options.raw_indirect ? pipeline.read_buffers() : vplkit::rsm_pass_buffers{};
  const int w = frame.width, h = frame.height;

  // Everything is rendered before anything is written, so a failure leaves no partial set.
  std::vector<vplkit::output_file> files;
  files.push_back(png_file(out_path, w, h, vplkit::to_srgb8(frame.radiance, w, h)));
  if (technique.indirect) {
    const float exposure = vplkit::percentile_exposure(frame.indirect);
    files.push_back(png_file(with_suffix(out_path, "-indirect"), w, h, vplkit::to_srgb8(frame.indirect, w, h, exposure)));
    if (technique.visibility != vplkit::rsm_visibility::none) {
      vplkit::rsm_pipeline_settings without = options.settings;
      without.technique = "rsm-radial";
      // One frame: the image does not depend on the JIT warm-up that the timed frame above needs.
      const vplkit::rsm_frame reference = vplkit::rsm_pipeline(shaders, source, without).render();
      // Amplified 8x relative to the indirect image's exposure, as in Fig. 5.1c.
      files.push_back(png_file(with_suffix(out_path, "-visibility-difference"), w, h,
                               vplkit::to_srgb8(vplkit::luminance_difference(reference.indirect, frame.indirect, 8.0f * exposure), w, h)));
    }
  }
  // The indirect irradiance, linear, at the image's size after the post filter (0 for direct light only).
  files.push_back(pfm_file(with_extension(with_suffix(out_path, "-indirect"), ".pfm"), vplkit::float_image_from_rgba(frame.indirect, w, h)));
  if (options.raw_indirect) {
    files.push_back(pfm_file(with_extension(with_suffix(out_path, "-raw-indirect"), ".pfm"), vplkit::float_image_from_buffer(raw.indirect)));
  }
  vplkit::write_all_or_nothing(files);

  io.out << "scene " << source.name << " (" << source.geometry.triangle_count() << " triangles), technique "
            << technique.name << ", " << w << "x" << h << ", RSM " << options.settings.rsm_size << "^2, indirect "
            << (w + options.settings.indirect_divisor - 1) / options.settings.indirect_divisor << "x"
            << (h + options.settings.indirect_divisor - 1) / options.settings.indirect_divisor << "\n"
            << vplkit::format_pass_table(frame.pass_times);
  for (const vplkit::output_file& file : files) io.out << "wrote " << fs::absolute(file.path).string() << "\n";
  return 0;
}

// The same file, whether or not it exists yet (so --error-image cannot overwrite an input).
bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code code;
  if (fs::equivalent(a, b, code)) return true;
  return fs::weakly_canonical(a, code) == fs::weakly_canonical(b, code) && !code;
}

int run_compare(const session& io, const std::string& image_path, const std::string& reference_path, const std::string& mask_path, const std::string& error_path,
                float error_scale) {
  if (!error_path.empty()) {
    if (fs::path(error_path).extension() != ".png") throw vplkit::error("--error-image must name a .png file, got " + shown(error_path));
    for (const std::string& input : {image_path, reference_path, mask_path})
      if (!input.empty() && same_file(error_path, input))
        throw vplkit::error("--error-image " + error_path + " is the input " + input + "; name a new file");
  }
  if (io.dry_run) return 0;
  const vplkit::float_image image = vplkit::read_image_file(image_path);
  const vplkit::float_image reference = vplkit::read_image_file(reference_path);
  std::optional<vplkit::float_image> mask;
  if (!mask_path.empty()) mask = vplkit::read_image_file(mask_path);
  const auto size_of = [](const vplkit::float_image& i) { return std::to_string(i.width) + "x" + std::to_string(i.height); };
  if (image.width != reference.width || image.height != reference.height)
    throw vplkit::error("the image " + image_path + " is " + size_of(image) + " but the reference " + reference_path + " is " + size_of(reference));
  if (mask && (mask->width != reference.width || mask->height != reference.height))
    throw vplkit::error("the mask " + mask_path + " is " + size_of(*mask) + " but the reference " + reference_path + " is " + size_of(reference));
  const vplkit::image_metrics m = vplkit::compare_images(image, reference, mask ? &*mask : nullptr);
  if (!error_path.empty())
    vplkit::write_png(error_path, image.width, image.height, vplkit::false_colour_error(image, reference, error_scale));
  io.out << std::setprecision(6) << "| metric | value |\n|---|---:|\n| RMSE | " << m.rmse << " |\n| relative MSE | " << m.relative_mse
            << " |\n| PSNR (dB) | " << m.psnr << " |\n| SSIM (luminance) | " << m.ssim << " |\n| similarity (Alg. 1, %) | " << m.similarity << " |\n";
  io.out << "| relative RMSE (RMSE / reference mean) | " << m.relative.rmse << " |\n| relative bias ((mean - reference mean) / reference mean) | "
            << m.relative.bias << " |\n";
  if (m.leak_rmse) io.out << "| masked RMSE (" << m.leak_pixels << " pixels, e.g. a leak region) | " << *m.leak_rmse << " |\n";
  if (m.masked)
    io.out << "| masked relative RMSE (" << m.masked->pixels << " pixels) | " << m.masked->rmse << " |\n| masked relative bias | " << m.masked->bias << " |\n";
  if (!error_path.empty()) io.out << "wrote " << fs::absolute(error_path).string() << "\n";
  return 0;
}

struct reference_options {
  std::string method = "monte-carlo";
  std::string visibility = "exact";
  bool visibility_given = false;
  bool samples_given = false;
  int samples = 64;
  std::uint32_t seed = 1;
  int receiver_stride = 1;
  std::string out;
};

// The brute-force RSM gather (paper 000, Fig. 5.1d) of the frame `vplkit render` draws with the
// same scene, size, RSM size, indirect divisor and format, at the receivers of its indirect buffer.
int run_rsm_brute_force(const session& io, render_options& options, const reference_options& reference) {
  if (reference.samples_given) throw vplkit::error("--samples is an option of --method monte-carlo");
  const std::string out = reference.out.empty()
                              ? "output/" + fs::path(options.scene_name).stem().string() + "-rsm-brute-force-" + reference.visibility + ".pfm"
                              : reference.out;
  const fs::path out_path(out);
  if (out_path.extension() != ".pfm") throw vplkit::error("--out must name a .pfm file (a .png and -receivers.pfm go next to it), got " + shown(out));
  options.settings.technique = "rsm-radial";  // the RSM and the G-buffer do not depend on the gather
  if (const std::string problem = vplkit::validate(options.settings); !problem.empty()) throw vplkit::error(problem);
  if (io.dry_run) return 0;
  auto context = vplkit::create_headless_context();
  const vplkit::shader_library shaders(shader_dir(options));
  const vplkit::scene source = load_scene(options.scene_name);
  vplkit::rsm_pipeline pipeline(shaders, source, options.settings);
  pipeline.render();
  const vplkit::rsm_pass_buffers buffers = pipeline.read_buffers();
  const vplkit::ray_scene rays(source.geometry);
  vplkit::rsm_brute_force_options brute_force;
  brute_force.exact_visibility = reference.visibility == "exact";
  brute_force.receiver_stride = reference.receiver_stride;
  brute_force.threads = vplkit::hardware_threads();
  const vplkit::image_buffer gathered = vplkit::reference_rsm_gather(rays, buffers, pipeline.constants(), brute_force);
  // The mask: the computed receivers the RSM gather covers.
  const std::vector<std::uint8_t> covered = vplkit::rsm_covered_receivers(buffers, pipeline.constants(), reference.receiver_stride);
  vplkit::image_buffer mask = gathered;
  for (std::size_t i = 0; i < covered.size(); ++i) mask.texels[i] = glm::vec4(covered[i] ? 1.0f : 0.0f);
  const auto counted = std::count(covered.begin(), covered.end(), std::uint8_t{1});
  const vplkit::float_image irradiance = vplkit::float_image_from_buffer(gathered);
  const std::vector<float> rgba = vplkit::rgba_from_float_image(irradiance);
  const fs::path png = with_extension(out_path, ".png"), receivers = with_extension(with_suffix(out_path, "-receivers"), ".pfm");
  vplkit::write_all_or_nothing({pfm_file(out_path, irradiance), png_file(png, irradiance.width, irradiance.height,
                                                      vplkit::to_srgb8(rgba, irradiance.width, irradiance.height, vplkit::percentile_exposure(rgba))),
             pfm_file(receivers, vplkit::float_image_from_buffer(mask))});
  io.out << "scene " << source.name << ", brute-force RSM gather with " << (brute_force.exact_visibility ? "exact (ray-cast)" : "no") << " visibility, RSM "
            << options.settings.rsm_size << "^2, at the " << gathered.width << "x" << gathered.height << " receivers of the indirect buffer of a "
            << options.settings.width << "x" << options.settings.height << " frame (every " << reference.receiver_stride << ". per axis), " << counted
            << " covered by the RSM gather (in front of the light, inside its frustum)\n"
            << "compare with `vplkit render --raw-indirect` of the same frame: vplkit compare <out>-raw-indirect.pfm " << out_path.string() << " --mask "
            << receivers.string() << "\nwrote " << fs::absolute(out_path).string() << "\nwrote " << fs::absolute(png).string() << "\nwrote "
            << fs::absolute(receivers).string() << "\n";
  return 0;
}

int run_reference(const session& io, render_options& options, const reference_options& reference) {
  finish_settings(options);
  if (reference.method == "rsm-brute-force") return run_rsm_brute_force(io, options, reference);
  if (reference.visibility_given) throw vplkit::error("--visibility is an option of --method rsm-brute-force");
  if (reference.receiver_stride != 1) throw vplkit::error("--receiver-stride is an option of --method rsm-brute-force");
  std::string out = reference.out;
  const int samples = reference.samples;
  const std::uint32_t seed = reference.seed;
  if (out.empty()) out = "output/" + fs::path(options.scene_name).stem().string() + "-reference.pfm";
  const fs::path out_path(out);
  if (out_path.extension() != ".pfm") throw vplkit::error("--out must name a .pfm file (a .png is written next to it), got " + shown(out));
  if (samples < 1) throw vplkit::error("--samples must be >= 1");
  if (io.dry_run) return 0;
  const vplkit::scene source = load_scene(options.scene_name);
  const int w = options.settings.width, h = options.settings.height;
  const vplkit::one_bounce_images images = vplkit::reference_one_bounce(source, w, h, samples, seed, vplkit::hardware_threads());
  // PFM and PNG of the final image, PFM of the indirect irradiance: written only after all is done.
  const fs::path png = with_extension(out_path, ".png");
  const fs::path indirect = with_suffix(out_path, "-indirect");
  vplkit::write_all_or_nothing({pfm_file(out_path, images.radiance), pfm_file(indirect, images.indirect),
             png_file(png, w, h, vplkit::to_srgb8(vplkit::rgba_from_float_image(images.radiance), w, h))});
  io.out << "scene " << source.name << ", one-bounce Monte Carlo reference, " << w << "x" << h << ", " << samples << " bounce rays per pixel, seed "
            << seed << "\nwrote " << fs::absolute(out_path).string() << "\nwrote " << fs::absolute(indirect).string() << "\nwrote "
            << fs::absolute(png).string() << "\n";
  return 0;
}

int run_view(const session& io, render_options& options, int frames) {
  finish_settings(options);
  if (is_lightwave(options) || is_final_gather(options))
    throw vplkit::error("view shows the RSM techniques; render the Light Wave and final gathering ones with vplkit render");
  if (const std::string problem = vplkit::validate(options.settings); !problem.empty()) throw vplkit::error(problem);
  if (io.dry_run) return 0;
  vplkit::window_context window(options.settings.width, options.settings.height, "vplkit - " + options.scene_name);
  const vplkit::shader_library shaders(shader_dir(options));
  vplkit::rsm_pipeline pipeline(shaders, load_scene(options.scene_name), options.settings);
  vplkit::program present = vplkit::load_program(shaders, "fullscreen.vert", "present.frag");
  vplkit::gl_vertex_array empty_vertex_array(vplkit::generate_vertex_array());
  for (int frame = 0; (frames == 0 || frame < frames) && !window.should_close(); ++frame) {
    pipeline.render();
    const auto [width, height] = window.framebuffer_size();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, width, height);
    present.set("image", 0);
    pipeline.output().bind(0);
    present.use();
    glBindVertexArray(empty_vertex_array.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    vplkit::check_gl("presenting a frame");
    window.swap_and_poll();
  }
  io.out << "closed the window after showing scene " << options.scene_name << "\n";
  return 0;
}

}  // namespace

namespace vplkit {

int run_command_line(int argc, const char* const* argv, std::ostream& out, std::ostream& err, command_line_mode mode) {
  CLI::App app{"vplkit: real-time one-bounce indirect illumination (RSM with visibility, Light Wave, "
               "robust final gathering)"};
  // At most one subcommand; an unknown word is then reported by name as an unexpected argument
  // (require_subcommand(1) would only say that a subcommand is required).
  app.require_subcommand(0, 1);
  app.set_version_flag("--version", vplkit::version_string);

  std::string context_kind = "headless";
  CLI::App* info = app.add_subcommand("info", "print the GL version and renderer and the library version");
  info->add_option("--context", context_kind, "which context to open")->check(CLI::IsMember({"headless", "window"}))->capture_default_str();

  render_options render_settings;
  std::string render_out;
  CLI::App* render = app.add_subcommand("render", "render a scene headless (OSMesa) to PNG images");
  add_render_options(*render, render_settings);
  render->add_flag("--raw-indirect", render_settings.raw_indirect, "also write <out>-raw-indirect.pfm: the unfiltered gather at the indirect buffer's "
                                                                  "receivers (compare it with vplkit reference --method rsm-brute-force)");
  render->add_option("--out", render_out, "final image path (.png; folders are created) [output/<scene>-<technique>.png]; "
                                   "the indirect and difference images go next to it");

  render_options view_settings;
  int frames = 0;
  CLI::App* view = app.add_subcommand("view", "show a scene in a window (use xvfb-run without a display)");
  add_render_options(*view, view_settings);
  view->add_option("--frames", frames, "close after this many frames (0: when the window is closed)")
      ->check(CLI::NonNegativeNumber)->capture_default_str();

  std::string compare_image, compare_reference, compare_mask, compare_error;
  float error_scale = 0.0f;
  CLI::App* compare = app.add_subcommand("compare", "compare an image with a reference (.pfm linear or .png sRGB)");
  compare->add_option("image", compare_image, "the image to judge")->required();
  compare->add_option("reference", compare_reference, "the reference")->required();
  compare->add_option("--mask", compare_mask, "pixels (luminance > 0.5) for the light-leak error and the masked relative errors, e.g. the "
                                             "-receivers.pfm of vplkit reference --method rsm-brute-force");
  compare->add_option("--error-image", compare_error, "write the false-colour error image (.png)");
  compare->add_option("--error-scale", error_scale, "luminance difference shown as full red (0: the largest)")
      ->check(number_in(0.0, std::numeric_limits<float>::max(), false, "linear luminance"))->capture_default_str();

  render_options reference_settings;
  reference_options reference_choice;
  CLI::App* reference = app.add_subcommand("reference", "render the one-bounce Monte Carlo reference (Embree) of a scene");
  add_render_options(*reference, reference_settings);
  reference->add_option("--method", reference_choice.method,
                         "monte-carlo: one-bounce path tracing of the final image (Embree); rsm-brute-force: every lit RSM texel at every "
                         "receiver of the frame's indirect buffer (the thesis's Fig. 5.1d)")
      ->check(CLI::IsMember({"monte-carlo", "rsm-brute-force"}))->capture_default_str();
  reference->add_option("--visibility", reference_choice.visibility, "rsm-brute-force: exact (a ray per pixel light) or none")
      ->check(CLI::IsMember({"exact", "none"}))->capture_default_str()->each([&](const std::string&) { reference_choice.visibility_given = true; });
  reference->add_option("--receiver-stride", reference_choice.receiver_stride, "rsm-brute-force: compute every N-th receiver per axis (the others are 0 and "
                                                                               "outside the -receivers.pfm mask)")
      ->check(CLI::Range(1, 64))->capture_default_str();
  reference->add_option("--samples", reference_choice.samples, "monte-carlo: bounce rays per pixel")->check(CLI::Range(1, 1 << 20))->capture_default_str()
      ->each([&](const std::string&) { reference_choice.samples_given = true; });
  reference->add_option("--reference-seed", reference_choice.seed, "monte-carlo: seed of the estimate")->capture_default_str();
  reference->add_option("--out", reference_choice.out, "output .pfm (monte-carlo: the final image, with -indirect.pfm and a .png next to it; "
                                                       "rsm-brute-force: the indirect irradiance, with a .png and -receivers.pfm)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& parse_error) {
    // CLI11 prints the message (or the help); its exit codes (105 for a failed check, ...) all
    // become 2, the conventional code for a command line that does not parse.
    return app.exit(parse_error, out, err) == 0 ? 0 : 2;
  }
  const session io{out, mode == command_line_mode::check_only};

  try {
    const int status = [&] {
      if (info->parsed()) return run_info(io, context_kind);
      if (render->parsed()) return run_render(io, render_settings, render_out);
      if (view->parsed()) return run_view(io, view_settings, frames);
      if (compare->parsed()) return run_compare(io, compare_image, compare_reference, compare_mask, compare_error, error_scale);
      if (reference->parsed()) return run_reference(io, reference_settings, reference_choice);
      err << "vplkit: error: a subcommand is required: info, render, view, compare or reference (see vplkit --help)\n";
      return 2;
    }();
    // A GL error that no check point turned into an exception still fails the command.
    if (status == 0 && unchecked_gl_error_count() > 0) {
      err << "vplkit: error: the GL driver reported " << unchecked_gl_error_count()
          << " error(s) through KHR_debug that no check point saw; the output is not trustworthy\n";
      return 1;
    }
    return status;
  } catch (const std::bad_alloc&) {
    err << "vplkit: error: out of memory (the input asks for more than this machine has)\n";
    return 1;
  } catch (const std::exception& failure) {
    err << "vplkit: error: " << failure.what() << "\n";
    return 1;
  }
}

}  // namespace vplkit
