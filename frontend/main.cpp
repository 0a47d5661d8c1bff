// The vplkit executable: `info`, `render` (headless, the main job) and `view` (a window).
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <regex>

#include <vplkit/version.hpp>

#include "frontend/context.hpp"
#include "frontend/debug_output.hpp"
#include "frontend/direct_renderer.hpp"
#include "frontend/error.hpp"
#include "frontend/image_io.hpp"
#include "frontend/program.hpp"
#include "frontend/scene.hpp"

namespace {

// Largest image side the CLI accepts before asking GL; GL_MAX_TEXTURE_SIZE is checked later.
constexpr int max_image_side = 16384;

struct image_size {
  int width = 512;
  int height = 512;
};

// "512" or "640x480".
std::string parse_size(const std::string& text, image_size& size) {
  static const std::regex pattern(R"((\d{1,6})(?:x(\d{1,6}))?)");
  std::smatch match;
  if (!std::regex_match(text, match, pattern)) return "expected N or WxH (for example 512 or 640x480), got '" + text + "'";
  const int width = std::stoi(match[1]);
  const int height = match[2].matched ? std::stoi(match[2]) : width;
  if (width < 1 || height < 1 || width > max_image_side || height > max_image_side)
    return "each side must be in [1, " + std::to_string(max_image_side) + "], got '" + text + "'";
  size = {width, height};
  return {};
}

struct common_options {
  std::string scene_name = "cornell-box";
  image_size size;
  std::string size_text = "512";
  int shadow_map_size = 1024;
  std::string format = "rgba16f";
  float min_distance = vplkit::irradiance_settings<float>{}.min_distance;
  std::string shader_dir;
};

void add_common_options(CLI::App& command, common_options& options) {
  std::vector<std::string> scenes = vplkit::built_in_scene_names();
  command.add_option("--scene", options.scene_name, "built-in scene")->check(CLI::IsMember(scenes))->capture_default_str();
  command.add_option("--size", options.size_text, "final image size, N or WxH")
      ->check(CLI::Validator([&](std::string& text) { return parse_size(text, options.size); }, "N|WxH"))
      ->capture_default_str();
  command.add_option("--shadow-map-size", options.shadow_map_size, "square shadow map resolution")
      ->check(CLI::Range(1, max_image_side))->capture_default_str();
  command.add_option("--format", options.format, "float format of the render targets")
      ->check(CLI::IsMember({"rgba16f", "rgba32f"}))->capture_default_str();
  command.add_option("--min-distance", options.min_distance,
                     "distance clamp of the light terms, scene units (irradiance_settings::min_distance)")
      ->check(CLI::Validator(
          [](std::string& text) {
            float value = 0.0f;
            return CLI::detail::lexical_cast(text, value) && value > 0.0f && std::isfinite(value)
                       ? std::string()
                       : "must be a number > 0 (scene units), got '" + text + "'";
          },
          "> 0"))
      ->capture_default_str();
  command.add_option("--shader-dir", options.shader_dir, "folder with the vplkit shaders (default: $VPLKIT_SHADER_DIR, then the built-in path)");
}

vplkit::direct_settings to_settings(const common_options& options) {
  vplkit::direct_settings settings;
  settings.width = options.size.width;
  settings.height = options.size.height;
  settings.shadow_map_size = options.shadow_map_size;
  settings.target_format = options.format == "rgba32f" ? vplkit::texel_format::rgba32f : vplkit::texel_format::rgba16f;
  settings.irradiance.min_distance = options.min_distance;
  return settings;
}

std::filesystem::path shader_dir(const common_options& options) {
  return options.shader_dir.empty() ? vplkit::default_shader_dir() : std::filesystem::path(options.shader_dir);
}

int run_info(const std::string& context_kind) {
  std::unique_ptr<vplkit::gl_context> context;
  if (context_kind == "window") context = std::make_unique<vplkit::window_context>(64, 64, "vplkit info");
  else context = vplkit::create_headless_context();
  std::cout << "vplkit " << vplkit::version_string << "\ncontext     " << context->kind() << "\n"
            << vplkit::describe_current_context() << "\nshaders     " << vplkit::default_shader_dir().string() << "\n";
  return 0;
}

int run_render(const common_options& options, const std::string& out) {
  // Check the output location before spending time on rendering.
  const std::filesystem::path out_path(out);
  if (out_path.extension() != ".png") throw vplkit::error("--out must name a .png file, got '" + out + "'");
  auto context = vplkit::create_headless_context();
  const vplkit::shader_library shaders(shader_dir(options));
  vplkit::direct_renderer renderer(shaders, vplkit::built_in_scene(options.scene_name), to_settings(options));
  // The first frame pays for llvmpipe's shader JIT, and llvmpipe's first GL_TIME_ELAPSED query
  // reads a garbage start time (seen: 282 s); the pass table reports a warmed-up frame.
  renderer.render();
  const vplkit::frame image = renderer.render();
  vplkit::write_png(out_path, image.width, image.height, vplkit::to_srgb8(image.radiance, image.width, image.height));
  std::cout << "scene " << options.scene_name << ", technique direct, " << image.width << "x" << image.height << "\n"
            << vplkit::format_pass_table(image.pass_times) << "wrote " << std::filesystem::absolute(out_path).string() << "\n";
  return 0;
}

int run_view(const common_options& options, int frames) {
  vplkit::window_context window(options.size.width, options.size.height, "vplkit - " + options.scene_name);
  const vplkit::shader_library shaders(shader_dir(options));
  vplkit::direct_renderer renderer(shaders, vplkit::built_in_scene(options.scene_name), to_settings(options));
  vplkit::program present = vplkit::load_program(shaders, "present.vert", "present.frag");
  vplkit::gl_vertex_array empty_vertex_array(vplkit::generate_vertex_array());
  for (int frame = 0; (frames == 0 || frame < frames) && !window.should_close(); ++frame) {
    renderer.render();
    const auto [width, height] = window.framebuffer_size();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, width, height);
    present.set("image", 0);
    renderer.output().bind(0);
    present.use();
    glBindVertexArray(empty_vertex_array.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    vplkit::check_gl("presenting a frame");
    window.swap_and_poll();
  }
  std::cout << "closed the window after showing scene " << options.scene_name << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"vplkit: real-time one-bounce indirect illumination (RSM with visibility, Light Wave, "
               "robust final gathering)"};
  // At most one subcommand; an unknown word is then reported by name as an unexpected argument
  // (require_subcommand(1) would only say that a subcommand is required).
  app.require_subcommand(0, 1);
  app.set_version_flag("--version", vplkit::version_string);

  std::string context_kind = "headless";
  CLI::App* info = app.add_subcommand("info", "print the GL version and renderer and the library version");
  info->add_option("--context", context_kind, "which context to open")->check(CLI::IsMember({"headless", "window"}))->capture_default_str();

  common_options render_options;
  std::string out = "output/cornell-box.png";
  CLI::App* render = app.add_subcommand("render", "render a scene headless (OSMesa) to a PNG");
  add_common_options(*render, render_options);
  render->add_option("--out", out, "output PNG path (folders are created)")->capture_default_str();

  common_options view_options;
  int frames = 0;
  CLI::App* view = app.add_subcommand("view", "show a scene in a window (use xvfb-run without a display)");
  add_common_options(*view, view_options);
  view->add_option("--frames", frames, "close after this many frames (0: when the window is closed)")
      ->check(CLI::NonNegativeNumber)->capture_default_str();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& parse_error) {
    return app.exit(parse_error);
  }

  try {
    if (info->parsed()) return run_info(context_kind);
    if (render->parsed()) return run_render(render_options, out);
    if (view->parsed()) return run_view(view_options, frames);
    std::cerr << "vplkit: error: a subcommand is required: info, render or view (see vplkit --help)\n";
    return 2;
  } catch (const std::exception& failure) {
    std::cerr << "vplkit: error: " << failure.what() << "\n";
    return 1;
  }
  return 1;
}
