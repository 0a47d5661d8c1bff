#include "frontend/cli/lightwave_options.hpp"

#include <iomanip>

#include "frontend/cli/output.hpp"
#include "frontend/core/named_table.hpp"

namespace vplkit::cli {

namespace {

std::function<bool(const std::string&)> one_of(std::vector<lightwave_mode> modes) {
  return [modes = std::move(modes)](const std::string& name) {
    for (const lightwave_technique& technique : lightwave_techniques())
      if (name == technique.name) return std::find(modes.begin(), modes.end(), technique.mode) != modes.end();
    return false;
  };
}

}  // namespace

bool is_lightwave_technique(const std::string& technique) { return has_name(lightwave_techniques(), technique); }

void add_lightwave_options(CLI::App& command, lightwave_options& options, option_scope& scope) {
  lightwave_settings& lw = options.settings;
  const std::string all = "the Light Wave techniques (lightwave-*)";
  scope.add(command.add_option("--ray-angle", lw.angle_deg, "Light Wave: degrees between VPL rays (divides 90 and 360)")
                ->check(CLI::Range(1, 90))->capture_default_str(),
            all, is_lightwave_technique);
  scope.add(command.add_option("--vpls-per-ray", lw.per_ray, "Light Wave: VPLs per ray (stacked hemispheres)")->check(CLI::Range(1, 32))->capture_default_str(),
            all, is_lightwave_technique);
  scope.add(command.add_option("--vpl-energy", options.energy,
                               "Light Wave: flux (each VPL reflects the flux its patch of the spot's cone brings to the surface its ray meets, "
                               "with a diffuse bounce's falloff) or thesis (Eq. 4.5: VPLs on hemispheres in space, no flux, no falloff; Tables 5.x)")
                ->check(CLI::IsMember({"flux", "thesis"}))->capture_default_str(),
            "lightwave-unshadowed, lightwave-accurate and lightwave-integrated",
            one_of({lightwave_mode::unshadowed, lightwave_mode::accurate, lightwave_mode::integrated}));
  scope.add(command.add_option("--vpl-max-distance", lw.max_distance, "Light Wave, --vpl-energy thesis: distance the hemispheres approach (0: from the scene's size)")
                ->check(number_in(0.0, max_scene_coordinate, false, "scene units"))->capture_default_str(),
            all, is_lightwave_technique);
  scope.add(command.add_option("--shadow-maps", lw.accurate_maps, "Light Wave: VPL shadow maps of the accurate shadows (0: none)")
                ->check(CLI::Range(0, lightwave_max_shadow_maps))->capture_default_str(),
            "lightwave-unshadowed, lightwave-accurate and lightwave-integrated",
            one_of({lightwave_mode::unshadowed, lightwave_mode::accurate, lightwave_mode::integrated}));
  scope.add(command.add_option("--shadow-variant", options.shadow_variant,
                               "Light Wave: importance (VPLs drawn by their light on the scene, maps aimed at it, lookups weighted by each VPL's "
                               "light) or thesis (uniform VPLs, maps along their normals, the plain mean)")
                ->check(CLI::IsMember({"importance", "thesis"}))->capture_default_str(),
            "lightwave-accurate", one_of({lightwave_mode::accurate}));
  scope.add(command.add_option("--integrated-steps", lw.integrated_steps, "Light Wave: in-between lookups per pair of maps")
                ->check(CLI::Range(0, 64))->capture_default_str(),
            "lightwave-integrated", one_of({lightwave_mode::integrated}));
  scope.add(command.add_option("--shadow-map-scale", lw.shadow_map_scale, "Light Wave: shadow map size in screens")
                ->check(number_in(0.0, 16.0, true, "screens"))->capture_default_str(),
            all, is_lightwave_technique);
  scope.add(command.add_option("--faked-multiplier", lw.faked_multiplier, "Light Wave: m of Eq. 5.2 (the thesis uses 1.1 to 1.5)")
                ->check(number_in(0.5, 4.0, false, "Eq. 5.2"))->capture_default_str(),
            "lightwave-faked", one_of({lightwave_mode::faked}));
}

lightwave_settings make_lightwave_settings(const std::string& technique, const common_options& common, const lightwave_options& options) {
  lightwave_settings lw = options.settings;
  lw.technique = technique;
  if (common.size_given) {
    lw.width = common.width;
    lw.height = common.height;
  }
  lw.format = common.texel();
  lw.irradiance.min_distance = common.min_distance;
  lw.seed = common.seed;
  lw.shadow_variant = options.shadow_variant == "thesis" ? lightwave_shadow_variant::thesis : lightwave_shadow_variant::importance;
  lw.energy = options.energy == "thesis" ? lightwave_energy::thesis : lightwave_energy::flux;
  if (lw.energy == lightwave_energy::flux && lw.max_distance != 0.0f)
    throw usage_error("--vpl-max-distance places the thesis's hemispheres and is read with --vpl-energy thesis; the flux energy puts its VPLs "
                      "where its rays meet the scene");
  if (const std::string problem = validate(lw); !problem.empty()) throw usage_error(problem);
  return lw;
}

std::string lightwave_scene_name(const common_options& common) { return common.scene_given ? common.scene : "boxes"; }

int render_lightwave(const session& io, const std::string& technique, const common_options& common, const lightwave_options& options,
                     const std::string& out) {
  const lightwave_settings settings = make_lightwave_settings(technique, common, options);
  const std::string scene_name = lightwave_scene_name(common);
  output_set files(out, "output/" + std::filesystem::path(scene_name).stem().string() + "-" + settings.technique + ".png", ".png", "--out");
  if (io.dry_run) return 0;
  const headless_session gl(common);
  const scene source = load_scene(common, scene_name);
  lightwave_pipeline pipeline(gl.shaders, source, settings);
  // The first frame pays for the shader compilers' lazy work; the light is then "moved" onto itself to time a rebuild, and a third frame has nothing to rebuild.
  pipeline.render();
  pipeline.set_light(source.light.spot);
  const lightwave_frame first = pipeline.render();
  const lightwave_frame frame = pipeline.render();
  files.add_png(files.main(), frame.radiance);
  // The indirect shadow factor as grey, linear (1 = white = not shadowed).
  if (!pipeline.shadow_casters().empty()) files.add_png(files.sibling("-indirect-shadow", ".png"), red_as_grey(frame.indirect_shadow));
  // The indirect radiance added to the direct light, linear (0 for lightwave-direct).
  files.add_pfm(files.sibling("-indirect", ".pfm"), frame.indirect);
  const double mebibytes = static_cast<double>(pipeline.shadow_map_bytes()) / (1024.0 * 1024.0);
  io.out << "scene " << source.name << " (" << source.geometry.triangle_count() << " triangles), technique " << settings.technique << ", "
         << settings.width << "x" << settings.height << ", " << pipeline.vpl_count() << " VPLs (" << settings.angle_deg << " degrees, " << settings.per_ray
         << " per ray" << (settings.energy == lightwave_energy::flux ? ", flux energy: " + std::to_string(pipeline.lit_vpl_count()) + " carry light" : std::string())
         << ")\nshadow maps: " << std::fixed << std::setprecision(2) << mebibytes << " MB (Eq. 5.4/5.5)\n"
         << "a frame after the light moved (VPLs and shadow maps rebuilt):\n"
         << format_pass_table(first.pass_times) << "next frames (nothing moved):\n"
         << format_pass_table(frame.pass_times);
  files.write(io.out);
  return 0;
}

}  // namespace vplkit::cli
