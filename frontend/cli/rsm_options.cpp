#include "frontend/cli/rsm_options.hpp"

#include <algorithm>
#include <iomanip>

#include "frontend/cli/output.hpp"
#include "frontend/core/error.hpp"
#include "frontend/core/named_table.hpp"
#include "frontend/gl/context.hpp"

namespace vplkit::cli {

namespace {

const rsm_technique* rsm_technique_named(const std::string& name) {
  for (const rsm_technique& technique : rsm_techniques())
    if (name == technique.name) return &technique;
  return nullptr;
}

bool gathers(const std::string& name) {
  const rsm_technique* technique = rsm_technique_named(name);
  return technique && technique->indirect;
}

bool radial(const std::string& name) { return gathers(name) && rsm_technique_named(name)->pattern == rsm_pattern::radial; }

bool with_visibility(const std::string& name) { return gathers(name) && rsm_technique_named(name)->visibility != rsm_visibility::none; }

}  // namespace

bool is_rsm_technique(const std::string& technique) { return rsm_technique_named(technique) != nullptr; }

void add_rsm_frame_options(CLI::App& command, rsm_options& options, option_scope* only_indirect) {
  command.add_option("--rsm-size", options.rsm_size, "square RSM resolution")->check(CLI::Range(1, max_image_side))->capture_default_str();
  CLI::Option* divisor = command.add_option("--indirect-divisor", options.indirect_divisor, "indirect buffer = image / this per axis (2: half, 1: full)")
                             ->check(CLI::IsMember({1, 2, 4, 8}))->capture_default_str();
  if (only_indirect) only_indirect->add(divisor, "the RSM techniques that gather indirect light (rsm-*)", gathers);
}

void add_rsm_gather_options(CLI::App& command, rsm_options& options, option_scope& scope, bool with_raw_indirect) {
  const std::string gatherers = "the RSM techniques that gather indirect light (rsm-*)";
  const std::string radial_ones = "the radial-pattern techniques (rsm-radial, rsm-alg2, rsm-alg3, rsm-alg6, rsm-alg6-ray)";
  const rsm_gather_preset<float> defaults = default_rsm_gather_preset<float>();
  const rsm_gather_preset<float> thesis = thesis_rsm_gather_preset<float>();
  scope.add(command
                .add_option("--preset", options.preset,
                            "RSM gather: default (radius " + format_number(defaults.radius_fraction) + " of the RSM, " + std::to_string(defaults.paths) + "x" +
                                std::to_string(defaults.samples_per_path) + " samples, " + std::to_string(defaults.slots) +
                                " slots; docs/rsm-study.md) or thesis (" + format_number(thesis.radius_fraction) + ", " + std::to_string(thesis.paths) + "x" +
                                std::to_string(thesis.samples_per_path) + ", " + std::to_string(thesis.slots) + " slots); the options below override it")
                ->check(CLI::IsMember({"default", "thesis"}))->capture_default_str(),
            gatherers, gathers);
  scope.add(command.add_option("--paths", options.paths, "radial pattern: paths [preset]")->check(CLI::Range(1, 256)), radial_ones, radial);
  scope.add(command.add_option("--samples-per-path", options.samples_per_path, "radial pattern: samples per path [preset]")->check(CLI::Range(1, 256)),
            radial_ones, radial);
  scope.add(command.add_option("--radius", options.radius, "sampling radius (radial and disk) as a fraction of the RSM side [preset]")
                ->check(number_in(0.0, 2.0, true, "a fraction of the RSM side")),
            gatherers, gathers);
  scope.add(command.add_option("--max-radius", options.max_radius_texels, "sampling radius in RSM texels (instead of --radius)")
                ->check(positive_number("RSM texels")),
            gatherers, gathers);
  scope.add(command.add_option("--slots", options.slots, "micro linear buffer slots [preset]")->check(CLI::Range(1, 16)),
            "the techniques with the micro linear buffer (rsm-alg2, rsm-alg3, rsm-alg6, rsm-alg6-ray)", with_visibility);
  const auto original = [](const std::string& name) { return name == "rsm-original"; };
  scope.add(command.add_option("--disk-samples", options.disk_samples, "original RSM: samples")->check(CLI::Range(1, 65536))->capture_default_str(),
            "rsm-original", original);
  scope.add(command.add_option("--disk-weights", options.disk_weights,
                               "original RSM: unbiased (xi, the inverse of the samples' density) or printed (the original's xi^2, biased low; "
                               "docs/errata.md RSMV-9)")
                ->check(CLI::IsMember({"unbiased", "printed"}))->capture_default_str(),
            "rsm-original", original);
  scope.add(command.add_option("--coverage-blocks", options.coverage_blocks,
                               "coarse pixel lights per RSM side that light the receivers the pattern cannot reach (behind the light, "
                               "outside its frustum; docs/errata.md RSMV-10); 0: none, as in the thesis")
                ->check(CLI::Range(0, rsm_coverage_max_blocks))->capture_default_str(),
            gatherers, gathers);
  scope.add(command.add_option("--post-filter", options.filter, "bilateral post filter of the indirect light: full 2D kernel or separable")
                ->check(CLI::IsMember({"full", "separable"}))->capture_default_str(),
            gatherers, gathers);
  if (with_raw_indirect)
    scope.add(command.add_flag("--raw-indirect", options.raw_indirect,
                               "also write <out>-raw-indirect.pfm: the unfiltered gather at the indirect buffer's receivers (compare it with "
                               "vplkit reference --method rsm-brute-force)"),
              gatherers, gathers);
}

void add_rsm_sequence_options(CLI::App& command, rsm_options& options, option_scope& scope) {
  scope.add(command.add_option("--poses", options.poses,
                               "render a sequence in one pipeline: a file with one frame per line, each line --camera x,y,z,tx,ty,tz and/or "
                               "--light x,y,z,tx,ty,tz ('#' comments; a pose a line leaves out stays); writes <out>-0001.png, "
                               "<out>-0001-indirect.pfm, ... for every frame, or nothing"),
            "the RSM techniques (direct, rsm-*)", is_rsm_technique);
  scope.add(command.add_option("--temporal-blend", options.temporal_blend,
                               "--poses: temporal accumulation, the weight of each new frame's gather against the history (reprojected, "
                               "clamped to the new frame's neighbourhood; the pattern turns every frame); 1: none (docs/errata.md RSMV-11) [" +
                                   format_number(rsm_pipeline_settings().temporal.blend) + "]")
                ->check(number_in(0.0, 1.0, true, "a weight")),
            "the RSM techniques that gather indirect light (rsm-*) with --poses", gathers);
}

rsm_pipeline_settings make_rsm_settings(const std::string& technique, const common_options& common, const rsm_options& options) {
  rsm_pipeline_settings s;
  s.technique = technique;
  s.width = common.width;
  s.height = common.height;
  s.format = common.texel();
  s.irradiance.min_distance = common.min_distance;
  s.rsm_size = options.rsm_size;
  s.indirect_divisor = options.indirect_divisor;
  s.filter = options.filter == "separable" ? post_filter::separable : post_filter::full;
  s.apply(options.preset == "thesis" ? thesis_rsm_gather_preset<float>() : default_rsm_gather_preset<float>());
  if (options.paths) s.radial.paths = *options.paths;
  if (options.samples_per_path) s.radial.samples_per_path = *options.samples_per_path;
  if (options.slots) s.slots = *options.slots;
  if (options.radius && options.max_radius_texels) throw usage_error("give the sampling radius once: --radius (a fraction of the RSM side) or --max-radius (texels)");
  if (options.radius) s.radius = *options.radius;
  if (options.max_radius_texels) s.radius = *options.max_radius_texels / static_cast<float>(s.rsm_size);
  s.disk.samples = options.disk_samples;
  s.disk.printed_weights = options.disk_weights == "printed";
  s.coverage_blocks = options.coverage_blocks;
  if (options.temporal_blend) {
    if (options.poses.empty()) throw usage_error("--temporal-blend is read with --poses (a sequence), not for one frame");
    s.temporal.blend = *options.temporal_blend;
  }
  s.radial.seed = s.disk.seed = common.seed;
  if (const std::string problem = validate(s); !problem.empty()) throw usage_error(problem);
  return s;
}

namespace {

// "-0001" for frame 1 of a sequence of `count` frames (at least 4 digits, more for longer ones).
std::string frame_suffix(std::size_t frame, std::size_t count) {
  std::string number = std::to_string(frame);
  const std::size_t digits = std::max<std::size_t>(4, std::to_string(count).size());
  return "-" + std::string(digits - std::min(digits, number.size()), '0') + number;
}

// The frames of --poses, rendered in one pipeline; nothing is written unless every frame renders.
int render_rsm_sequence(const session& io, const rsm_technique& technique, const rsm_pipeline_settings& settings, const common_options& common,
                        const rsm_options& options, output_set& files) {
  const std::vector<pose_frame> frames = read_pose_file(options.poses, false);
  // Every frame's files are kept in memory until the end (all or nothing): bound them.
  const double bytes_per_frame = static_cast<double>(settings.width) * settings.height * (options.raw_indirect ? 19.0 : 15.0);
  if (bytes_per_frame * static_cast<double>(frames.size()) > 4.0 * 1024 * 1024 * 1024)
    throw error(options.poses + ": " + std::to_string(frames.size()) + " frames of " + std::to_string(settings.width) + "x" +
                      std::to_string(settings.height) + " would hold more than 4 GiB until they are written; split the pose file");
  const headless_session gl(common);
  const scene source = load_scene(common, common.scene);
  rsm_pipeline pipeline(gl.shaders, source, settings);
  pipeline.render();  // the shader compilers' lazy work, as for one frame
  camera view = source.view;
  scene_light light = source.light;
  double total_ms = 0.0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const pose_frame& frame = frames[i];
    const std::string where = options.poses + ":" + std::to_string(frame.line);
    if (frame.camera) {
      apply_pose(*frame.camera, view, where + ": --camera");
      pipeline.set_camera(view);
    }
    if (frame.light) {
      apply_pose(*frame.light, light, where + ": --light");
      pipeline.set_light(light);
    }
    const rsm_frame rendered = pipeline.render_next();
    for (const pass_time& pass : rendered.pass_times) total_ms += pass.milliseconds;
    const std::string suffix = frame_suffix(i + 1, frames.size());
    files.add_png(files.sibling(suffix, ".png"), rendered.radiance);
    files.add_pfm(files.sibling(suffix + "-indirect", ".pfm"), rendered.indirect);
    if (options.raw_indirect) files.add_pfm(files.sibling(suffix + "-raw-indirect", ".pfm"), pipeline.read_buffers().indirect);
  }
  io.out << "scene " << source.name << " (" << source.geometry.triangle_count() << " triangles), technique " << technique.name << ", "
         << settings.width << "x" << settings.height << ", RSM " << settings.rsm_size << "^2, " << frames.size() << " frames from " << options.poses
         << ", " << std::fixed << std::setprecision(1) << total_ms / static_cast<double>(frames.size()) << " ms per frame (passes)\n";
  files.write(io.out);
  return 0;
}

}  // namespace

int render_rsm(const session& io, const std::string& technique_name, const common_options& common, const rsm_options& options, const std::string& out) {
  const rsm_technique& technique = find_rsm_technique(technique_name);
  const rsm_pipeline_settings settings = make_rsm_settings(technique_name, common, options);
  output_set files(out, "output/" + std::filesystem::path(common.scene).stem().string() + "-" + technique.name + ".png", ".png", "--out");
  if (io.dry_run) return 0;
  if (!options.poses.empty()) return render_rsm_sequence(io, technique, settings, common, options, files);

  const headless_session gl(common);
  const scene source = load_scene(common, common.scene);
  rsm_pipeline pipeline(gl.shaders, source, settings);
  // The first frame pays for the shader compilers' lazy work (llvmpipe's JIT, a driver's first
  // use of a program); the pass table reports a warmed-up frame.
  pipeline.render();
  const rsm_frame frame = pipeline.render();

  // Everything is rendered before anything is written, so a failure leaves no partial set.
  files.add_png(files.main(), frame.radiance);
  if (technique.indirect) {
    const float exposure = percentile_exposure(frame.indirect);
    files.add_png(files.sibling("-indirect", ".png"), frame.indirect, exposure);
    if (technique.visibility != rsm_visibility::none) {
      rsm_pipeline_settings without = settings;
      without.technique = "rsm-radial";
      // One frame: the image does not depend on the JIT warm-up that the timed frame above needs.
      const rsm_frame reference = rsm_pipeline(gl.shaders, source, without).render();
      // Amplified 8x relative to the indirect image's exposure, as in Fig. 5.1c.
      files.add_png(files.sibling("-visibility-difference", ".png"), luminance_difference(reference.indirect, frame.indirect, 8.0f * exposure));
    }
  }
  // The indirect irradiance, linear, at the image's size after the post filter (0 for direct light only).
  files.add_pfm(files.sibling("-indirect", ".pfm"), frame.indirect);
  if (options.raw_indirect) files.add_pfm(files.sibling("-raw-indirect", ".pfm"), pipeline.read_buffers().indirect);

  const glm::ivec2 indirect = pipeline.constants().indirect_size;
  io.out << "scene " << source.name << " (" << source.geometry.triangle_count() << " triangles), technique " << technique.name << ", "
         << settings.width << "x" << settings.height << ", RSM " << settings.rsm_size << "^2, indirect " << indirect.x << "x" << indirect.y << "\n"
         << format_pass_table(frame.pass_times);
  files.write(io.out);
  return 0;
}

}  // namespace vplkit::cli
