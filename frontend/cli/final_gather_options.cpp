#include "frontend/cli/final_gather_options.hpp"

#include "frontend/cli/output.hpp"
#include "frontend/core/named_table.hpp"

namespace vplkit::cli {

bool is_final_gather_technique(const std::string& technique) { return has_name(final_gather_techniques(), technique); }

void add_final_gather_options(CLI::App& command, final_gather_options& options, option_scope& scope) {
  const std::string readers = "the final-gathering techniques (finalgather-*, envmap)";
  final_gather_settings& fg = options.settings;
  scope.add(command.add_option("--object", options.object, "final gathering: the dynamic object, sphere or an .obj file (meshes/bunny.obj)")
                ->capture_default_str(),
            readers, is_final_gather_technique);
  scope.add(command
                .add_option("--object-position", options.object_position_text,
                            "final gathering: the object's centre x,y,z (the room is [-1,1]x[0,2]x[-1,1]; each within +-" + format_number(max_object_coordinate) + ")")
                ->check(CLI::Validator([&options](std::string& text) { return parse_position(text, options.object_position, max_object_coordinate); }, "x,y,z"))
                ->capture_default_str(),
            readers, is_final_gather_technique);
  scope.add(command.add_option("--object-size", options.object_size, "final gathering: the object's size across (the room is 2 wide)")
                ->check(number_in(0.0, 10.0, true, "scene units"))->capture_default_str(),
            readers, is_final_gather_technique);
  scope.add(command.add_option("--cube-resolution", fg.resolution, "final gathering: M, the small cube map's face resolution (4 or 2)")
                ->check(CLI::Range(1, 64))->capture_default_str(),
            readers, is_final_gather_technique);
  scope.add(command.add_option("--face-size", fg.face_size, "final gathering: the cube map's face size before averaging (its six faces lie side by side "
                                                            "in one texture: at most " + std::to_string(max_cube_face_size) + ")")
                ->check(CLI::Range(1, max_cube_face_size))->capture_default_str(),
            readers, is_final_gather_technique);
}

final_gather_settings make_final_gather_settings(const std::string& technique, const common_options& common, const final_gather_options& options) {
  final_gather_settings settings = options.settings;
  settings.technique = technique;
  settings.width = common.width;
  settings.height = common.height;
  settings.irradiance.min_distance = common.min_distance;
  settings.format = common.texel();
  if (const std::string problem = validate(settings); !problem.empty()) throw usage_error(problem);
  return settings;
}

int render_final_gather(const session& io, const std::string& technique, const common_options& common, const final_gather_options& options,
                        const std::string& out) {
  const final_gather_settings settings = make_final_gather_settings(technique, common, options);
  output_set files(out, "output/" + std::filesystem::path(options.object).stem().string() + "-" + settings.technique + ".png", ".png", "--out");
  if (io.dry_run) return 0;
  const headless_session gl(common);
  final_gather_scene source = make_final_gather_scene(options.object, options.object_position, options.object_size);
  apply_poses(common, source.view, source.light);
  final_gather_pipeline pipeline(gl.shaders, source, settings);
  pipeline.render();  // warm-up: the shader compilers' lazy work
  const final_gather_frame frame = pipeline.render();
  files.add_png(files.main(), frame.radiance);
  files.add_png(files.sibling("-indirect", ".png"), frame.indirect, percentile_exposure(frame.indirect));
  // The object's indirect irradiance, linear (0 elsewhere).
  files.add_pfm(files.sibling("-indirect", ".pfm"), frame.indirect);
  io.out << "object " << source.name << " (" << source.object.triangle_count() << " triangles) at (" << source.reference_point.x << ", "
         << source.reference_point.y << ", " << source.reference_point.z << "), technique " << settings.technique << ", " << settings.width << "x"
         << settings.height << ", cube map 6 x " << settings.face_size << "^2 -> 6 x " << settings.resolution << "^2\n"
         << format_pass_table(frame.pass_times);
  files.write(io.out);
  return 0;
}

}  // namespace vplkit::cli
