// vplkit info: the GL version and renderer of a context, the library version, the shaders used.
#include <vplkit/version.hpp>

#include "frontend/cli/commands.hpp"
#include "frontend/gl/context.hpp"
#include "frontend/gl/program.hpp"

namespace vplkit::cli {

command add_info_command(CLI::App& app) {
  auto context_kind = std::make_shared<std::string>("headless");
  CLI::App* info = app.add_subcommand("info", "print the GL version and renderer and the library version");
  info->add_option("--context", *context_kind, "which context to open")->check(CLI::IsMember({"headless", "window"}))->capture_default_str();
  return {info, [context_kind](const session& io) {
            if (io.dry_run) return 0;
            std::unique_ptr<gl_context> context;
            if (*context_kind == "window") context = std::make_unique<window_context>(64, 64, "vplkit info");
            else context = create_headless_context();
            io.out << "vplkit " << version_string << "\ncontext     " << context->kind() << "\n"
                   << describe_current_context() << "\nshaders     " << default_shader_dir().string() << "\n";
            return 0;
          }};
}

}  // namespace vplkit::cli
