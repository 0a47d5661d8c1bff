// vplkit info: the GL version and renderer of a context, the library version, the shaders used.
#include <vplkit/version.hpp>
#include <vplkit/gl/program.hpp>

#include "frontend/cli/commands.hpp"
#include "frontend/gl/context.hpp"
#include "frontend/gl/pass_timer.hpp"
#include "frontend/window/window_context.hpp"

namespace vplkit::cli {

command add_info_command(CLI::App& app) {
  struct info_state {
    std::string context = "auto";
    int device = -1;
  };
  auto state = std::make_shared<info_state>();
  CLI::App* info = app.add_subcommand("info", "list the GL contexts and devices available, open one, and print its GL version and renderer");
  std::vector<std::string> choices = headless_api_names();
  choices.push_back("window");
  info->add_option("--context", state->context, "which context to open: auto ($VPLKIT_CONTEXT, else EGL, else OSMesa), egl, egl-surfaceless, osmesa or window")
      ->check(CLI::IsMember(choices))->capture_default_str();
  info->add_option("--device", state->device, "EGL device index (default: $VPLKIT_EGL_DEVICE, else the first GPU, else software)")->check(CLI::Range(0, 1024));
  return {info, [state](const session& io) {
            if (state->device >= 0 && (state->context == "osmesa" || state->context == "egl-surfaceless" || state->context == "window"))
              throw usage_error("--device picks an EGL device; --context " + state->context + " has none");
            if (io.dry_run) return 0;
            io.out << "vplkit " << version_string << "\navailable headless contexts:\n";
            for (const std::string& line : available_headless_contexts()) io.out << "  " << line << "\n";
            std::unique_ptr<gl_context> context;
            if (state->context == "window") {
              context = std::make_unique<window_context>(64, 64, "vplkit info");
            } else {
              headless_request request;
              request.api = headless_api_from_name(state->context, "--context");
              request.device = state->device;
              context = create_headless_context(request);
            }
            io.out << "using       " << context->kind() << "\n" << describe_current_context() << "\ntiming      "
                   << describe(timing_method_for_current_context()) << "\nshaders     " << default_shader_dir().string() << "\n";
            return 0;
          }};
}

}  // namespace vplkit::cli
