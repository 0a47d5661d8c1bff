// vplkit reference: the ground truths that the techniques are measured against.
// - monte-carlo: one-bounce path tracing (Embree) of a scene's final image and indirect light;
// - rsm-brute-force: every lit RSM texel gathered at every receiver of the frame's indirect
//   buffer, with ray-cast or no visibility (the thesis's Fig. 5.1d), for `render --raw-indirect`.
#include <algorithm>
#include <iostream>

#include "frontend/cli/commands.hpp"
#include "frontend/cli/output.hpp"
#include "frontend/cli/technique_options.hpp"
#include "frontend/core/parallel.hpp"
#include "frontend/core/text.hpp"
#include "frontend/reference/reference.hpp"
#include "frontend/techniques/rsm/rsm_cpu_mirror.hpp"

namespace vplkit::cli {

namespace {

namespace fs = std::filesystem;

struct reference_state {
  std::string method = "monte-carlo";
  std::string visibility = "exact";
  std::string receivers = "all";
  reference_options options = [] {
    reference_options every_receiver;
    every_receiver.receiver_stride = 1;  // the reference command computes every receiver unless told
    return every_receiver;
  }();
  std::string out;
  double max_seconds = 0.0;
  common_options common;
  given_settings given;  ///< the frame's settings: --size, and for the brute force --format, --min-distance, --rsm-size, --indirect-divisor
  option_scope scope;
};

// The frame's settings, as `vplkit render` makes them for an RSM technique.
std::unique_ptr<technique_settings> frame_settings(const reference_state& s) { return make_technique_settings(s.given, "rsm-radial"); }

std::string stem_of(const std::string& scene_name) { return fs::path(scene_name).stem().string(); }

// Long work, announced and bounded: the cost before the work starts (rays, and seconds from a
// calibration), refused when it does not fit --max-seconds (counted from the command's start),
// and progress on stderr (plain lines every 5 s, or $VPLKIT_PROGRESS_SECONDS, when it is not a
// terminal) with the deadline.
progress_settings announce(const reference_state& s, const reference_cost& cost, double started, int threads) {
  std::cerr << "vplkit reference: " << cost.what << ": " << (cost.rays > 0.0 ? "at most " + count_text(cost.rays) + " rays" : std::string("no rays"))
            << ", estimated " << duration_text(cost.seconds) << " on " << threads << " thread" << (threads == 1 ? "" : "s") << "\n";
  progress_settings progress = progress_on_stderr();
  if (s.max_seconds > 0.0) {
    const double elapsed = steady_seconds() - started;
    if (elapsed + cost.seconds > s.max_seconds)
      throw error("reference: the estimate (" + duration_text(cost.seconds) + ", after " + duration_text(elapsed) + " of preparation) exceeds --max-seconds " +
                  format_number(static_cast<float>(s.max_seconds)) + "; nothing is written (fewer --samples, a smaller --size or a larger --receiver-stride)");
    progress.deadline = started + s.max_seconds;
    progress.deadline_name = "--max-seconds " + format_number(static_cast<float>(s.max_seconds));
  }
  return progress;
}

// The brute-force RSM gather of the frame `vplkit render` draws with the same scene, size, RSM
// size, indirect divisor and format, at the receivers of its indirect buffer.
int run_rsm_brute_force(const session& io, const reference_state& s) {
  // The RSM and the G-buffer do not depend on the gather: any radial technique gives them.
  const std::unique_ptr<technique_settings> frame = frame_settings(s);
  const rsm_pipeline_settings& settings = settings_struct<rsm_pipeline_settings, rsm_technique>(*frame);
  const std::string scene_name = drawn_scene_name(s.common, *frame);
  output_set files(s.out, "output/" + stem_of(scene_name) + "-rsm-brute-force-" + s.visibility + ".pfm", ".pfm", "--out",
                   "a .png and -receivers.pfm go next to it");
  if (io.dry_run) return 0;
  const double started = steady_seconds();
  const headless_session gl(s.common);
  const scene source = load_scene(s.common, scene_name);
  rsm_pipeline pipeline(gl.shaders, source, settings);
  pipeline.render();
  const rsm_pass_buffers buffers = pipeline.read_buffers();
  const ray_scene rays(source.geometry);
  rsm_brute_force_options brute_force;
  brute_force.exact_visibility = s.visibility == "exact";
  brute_force.receiver_stride = s.options.receiver_stride;
  brute_force.threads = hardware_threads();
  const progress_settings progress =
      announce(s, estimate_rsm_gather(rays, pipeline, brute_force), started, brute_force.threads);
  const image gathered = reference_rsm_gather(rays, pipeline, brute_force, progress);  // every light's, summed
  // The mask: every computed receiver with a surface (all), or those the pattern covers.
  const std::vector<std::uint8_t> covered = rsm_covered_receivers(pipeline, s.options.receiver_stride);
  image mask(gathered.width, gathered.height);
  std::size_t counted = 0, counted_covered = 0;
  for (int y = 0; y < mask.height; y += s.options.receiver_stride)
    for (int x = 0; x < mask.width; x += s.options.receiver_stride) {
      const std::size_t i = mask.index(x, y);
      const bool surface = gather_receiver_at(glm::ivec2(x, y), buffers, pipeline.constants()).has_value();
      const bool counts = s.receivers == "all" ? surface : covered[i] != 0;
      mask.texels[i] = glm::vec4(counts ? 1.0f : 0.0f);
      counted += surface;
      counted_covered += covered[i] != 0;
    }
  files.add_pfm(files.main(), gathered);
  files.add_png(files.sibling("", ".png"), gathered, percentile_exposure(gathered));
  const fs::path receivers = files.sibling("-receivers", ".pfm");
  files.add_pfm(receivers, mask);
  io.out << "scene " << source.name << ", brute-force RSM gather with " << (brute_force.exact_visibility ? "exact (ray-cast)" : "no") << " visibility, RSM "
         << settings.rsm_size << "^2, at the " << gathered.width << "x" << gathered.height << " receivers of the indirect buffer of a " << settings.width
         << "x" << settings.height << " frame (every " << s.options.receiver_stride << ". per axis): " << counted << " with a surface, "
         << counted_covered << " of them covered by the pattern (in front of the light, inside its frustum); -receivers.pfm marks "
         << (s.receivers == "all" ? "every one with a surface" : "the covered ones") << "\n"
         << "compare with `vplkit render --raw-indirect` of the same frame: vplkit compare <out>-raw-indirect.pfm " << files.main().string() << " --mask "
         << receivers.string() << "\n";
  files.write(io.out);
  return 0;
}

int run_monte_carlo(const session& io, const reference_state& s) {
  const std::unique_ptr<technique_settings> frame = frame_settings(s);
  const std::string scene_name = drawn_scene_name(s.common, *frame);
  output_set files(s.out, "output/" + stem_of(scene_name) + "-reference.pfm", ".pfm", "--out", "a .png, -indirect.pfm and -direct.pfm go next to it");
  if (io.dry_run) return 0;
  const double started = steady_seconds();
  const scene source = load_scene(s.common, scene_name);
  const rsm_pipeline_settings& settings = settings_struct<rsm_pipeline_settings, rsm_technique>(*frame);
  const int w = settings.width, h = settings.height;
  const int threads = hardware_threads();
  const ray_scene rays(source.geometry);
  const progress_settings progress =
      announce(s, estimate_one_bounce(rays, source, w, h, s.options.samples, s.options.seed, threads), started, threads);
  const one_bounce_images images = reference_one_bounce(rays, source, w, h, s.options.samples, s.options.seed, threads, progress);
  // PFM and PNG of the final image, PFMs of the indirect and the direct irradiance (the quantities
  // of render's -indirect.pfm and -direct.pfm): written only after all is done.
  files.add_pfm(files.main(), images.radiance);
  files.add_pfm(files.sibling("-indirect", ".pfm"), images.indirect);
  files.add_pfm(files.sibling("-direct", ".pfm"), images.direct);
  files.add_png(files.sibling("", ".png"), images.radiance, exposure_scale(s.common, images.radiance, io.out));
  io.out << "scene " << source.name << ", one-bounce Monte Carlo reference, " << w << "x" << h << ", " << s.options.samples << " bounce rays per pixel, seed "
         << s.options.seed << "\n";
  if (images.back_facing_pixels > 0) {
    const double share = 100.0 * static_cast<double>(images.back_facing_pixels) / (static_cast<double>(w) * static_cast<double>(h));
    io.out << "note: " << images.back_facing_pixels << " pixels (" << fixed(share, 1)
           << " %) see the back of a surface (its normal faces away from the camera); the reference, like every technique, lights a surface on "
              "the side its normal faces, so these show only the light that side receives: reversed faces in the mesh if they are dark\n";
  }
  files.write(io.out);
  return 0;
}

}  // namespace

command add_reference_command(CLI::App& app) {
  auto state = std::make_shared<reference_state>();
  CLI::App* reference = app.add_subcommand("reference", "render a ground truth: the one-bounce Monte Carlo reference (Embree) or the brute-force RSM gather");
  const auto brute_force = [](const std::string& method) { return method == "rsm-brute-force"; };
  const auto monte_carlo = [](const std::string& method) { return method == "monte-carlo"; };
  reference->add_option("--method", state->method,
                        "monte-carlo: one-bounce path tracing of the final image (Embree); rsm-brute-force: every lit RSM texel at every "
                        "receiver of the frame's indirect buffer (the thesis's Fig. 5.1d)")
      ->check(CLI::IsMember({"monte-carlo", "rsm-brute-force"}))->capture_default_str();
  add_scene_option(*reference, state->common, "cornell-box");
  add_pose_options(*reference, state->common);
  state->scope.add(add_exposure_option(*reference, state->common), "--method monte-carlo", monte_carlo);
  const common_option_handles frame = add_common_options(*reference, state->common);
  for (CLI::Option* option : {frame.shader_dir, frame.context, frame.device}) state->scope.add(option, "--method rsm-brute-force", brute_force);
  // The frame `vplkit render` draws: its size for both methods, the rest for the brute force.
  add_setting_options(*reference, state->given, {"size"});
  for (CLI::Option* option : add_setting_options(*reference, state->given, {"format", "min-distance", "rsm-size", "indirect-divisor"}))
    state->scope.add(option, "--method rsm-brute-force", brute_force);
  state->scope.add(reference->add_option("--visibility", state->visibility, "rsm-brute-force: exact (a ray per pixel light) or none")
                       ->check(CLI::IsMember({"exact", "none"}))->capture_default_str(),
                   "--method rsm-brute-force", brute_force);
  state->scope.add(reference->add_option("--receivers", state->receivers,
                                         "rsm-brute-force: the receivers -receivers.pfm marks: all (every receiver with a surface, the light's first "
                                         "bounce reaches it whether the RSM's projection covers it or not) or covered (in front of the light, "
                                         "projecting inside the RSM: what the pattern alone reaches)")
                       ->check(CLI::IsMember({"all", "covered"}))->capture_default_str(),
                   "--method rsm-brute-force", brute_force);
  add_reference_options(*reference, state->options, state->scope, "--method");
  reference->add_option("--max-seconds", state->max_seconds,
                        "refuse when the estimated time (printed before the work starts) exceeds this, and stop, writing nothing, when the "
                        "run takes longer; counted from the start; 0: no limit")
      ->check(number_in(0.0, 1e9, false, "seconds"))->capture_default_str();
  reference->add_option("--out", state->out, "output .pfm (monte-carlo: the final image, with -indirect.pfm, -direct.pfm and a .png next to it; "
                                             "rsm-brute-force: the indirect irradiance, with a .png and -receivers.pfm)");
  return {reference, [state](const session& io) {
            state->scope.require_read_by(state->method, "method");
            return state->method == "rsm-brute-force" ? run_rsm_brute_force(io, *state) : run_monte_carlo(io, *state);
          }, restorer(state)};
}

}  // namespace vplkit::cli
