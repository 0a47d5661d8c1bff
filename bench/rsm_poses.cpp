// The RSM techniques on any frame (docs/rsm-study.md, "Any frame"): every frame of a pose file
// measured against its ground truth, frame by frame, with the worst frame and the spread.
//   build/bench/vplkit_rsm_poses --poses bench/poses/holdout.txt [--size 256] [--rsm-size 512]
//       [--stride 2] [--seeds 4] [--mc-samples 64] [--cache output/rsm-poses/cache] [--out output/rsm-poses]
// A pose file holds one frame per line, render's options: --scene FILE --camera ... --light ...
// (bench/poses/, written by vplkit_study_set). For each frame:
// - the brute-force gather of every lit RSM texel with and without exact visibility at every
//   stride-th receiver of the indirect buffer that has a surface, covered by the pattern or not
//   (frontend/reference/rsm_measure.hpp; cached under --cache, the slow part);
// - the one-bounce Monte Carlo reference of the image (cached);
// - each technique at the defaults, seeds 1..--seeds, raw and filtered.
// Targets (issue 23), per frame: Alg. 6's relative RMSE against exact visibility below the radial
// gather's; |leak-region bias| at most half the radial gather's where the leak region holds >= 2 %
// of the receivers; the filtered indirect irradiance of the whole image within +-15 % of the Monte
// Carlo reference's; rsm-original's |bias| against the unoccluded brute force <= 10 %.
// Writes poses.md (a row per frame, the targets with the worst frame and the spread) and poses.csv.
// --voxel: rsm-voxel's targets against rsm-radial frame by frame, its cost against rsm-radial and
// rsm-alg6, where its time goes (marches per receiver, fetches per march) and the moonshot (the
// filtered image's per-pixel error against the Monte Carlo image, the reference's noise taken out,
// from a second Monte Carlo image of another seed); writes voxel.md and voxel.csv (full precision).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include <iomanip>
#include <memory>

#include "bench/study_cache.hpp"
#include "frontend/reference/rsm_measure.hpp"
#include "frontend/cli/options.hpp"
#include "frontend/core/error.hpp"
#include "frontend/core/text.hpp"
#include "frontend/core/files.hpp"
#include "frontend/core/parallel.hpp"
#include "frontend/gl/context.hpp"
#include "frontend/image/image_files.hpp"
#include "frontend/image/reference_noise.hpp"
#include "frontend/scene/pose.hpp"
#include "frontend/techniques/rsm/rsm_cpu_mirror.hpp"

#include <glm/gtc/matrix_transform.hpp>

namespace fs = std::filesystem;
using namespace vplkit;

namespace {

std::string percent(double fraction) { return fixed(100.0 * fraction, 1); }

// The median wall-clock ms of a whole frame for each configuration, the configurations interleaved
// (A B A B ...), each after a warm-up frame (the shader compilers' lazy work).
std::vector<double> interleaved_frame_ms(const shader_library& shaders, const scene& source, const std::vector<rsm_pipeline_settings>& configurations,
                                         int repeat) {
  std::vector<std::unique_ptr<rsm_pipeline>> pipelines;
  for (const rsm_pipeline_settings& settings : configurations) {
    pipelines.push_back(std::make_unique<rsm_pipeline>(shaders, source, settings));
    pipelines.back()->draw_wall_clock_ms();
  }
  std::vector<std::vector<double>> times(configurations.size());
  for (int i = 0; i < repeat; ++i)
    for (std::size_t c = 0; c < pipelines.size(); ++c) times[c].push_back(pipelines[c]->draw_wall_clock_ms());
  std::vector<double> medians;
  for (std::vector<double>& values : times) {
    std::sort(values.begin(), values.end());
    medians.push_back(values[values.size() / 2]);
  }
  return medians;
}

// A technique's errors on one frame, each the mean over seeds 1..n (measure_frame per seed).
struct technique_errors {
  relative_error raw_vs_unoccluded, raw_vs_exact, raw_leak, raw_covered_vs_exact, raw_uncovered_vs_unoccluded;
  double raw_bias_min = 0.0, raw_bias_max = 0.0;  ///< raw_vs_exact's bias: the lowest and the highest of the seeds
  image filtered_image;  ///< the filtered indirect irradiance of the whole image (what the user sees), mean of the seeds
  image first_filtered;  ///< seed 1's alone: one frame as the user sees it (the moonshot's image)
};

void accumulate(relative_error& sum, const relative_error& value, int seeds) {
  sum.rmse += value.rmse / seeds;
  sum.bias += value.bias / seeds;
  sum.pixels = value.pixels;
}

technique_errors measure_technique(const shader_library& shaders, const scene& source, const rsm_pipeline_settings& settings,
                                   const frame_reference& reference, int seeds) {
  technique_errors errors;
  for (int seed = 1; seed <= seeds; ++seed) {
    rsm_pipeline_settings seeded = settings;
    seeded.radial.seed = static_cast<std::uint32_t>(seed);
    seeded.disk.seed = static_cast<std::uint32_t>(seed);
    rsm_pipeline pipeline(shaders, source, seeded);
    const rsm_frame frame = pipeline.render();
    const frame_errors e = measure_frame(pipeline, reference);
    accumulate(errors.raw_vs_unoccluded, e.raw_vs_unoccluded, seeds);
    accumulate(errors.raw_vs_exact, e.raw_vs_exact, seeds);
    accumulate(errors.raw_leak, e.raw_leak, seeds);
    accumulate(errors.raw_covered_vs_exact, e.raw_covered_vs_exact, seeds);
    accumulate(errors.raw_uncovered_vs_unoccluded, e.raw_uncovered_vs_unoccluded, seeds);
    errors.raw_bias_min = seed == 1 ? e.raw_vs_exact.bias : std::min(errors.raw_bias_min, e.raw_vs_exact.bias);
    errors.raw_bias_max = seed == 1 ? e.raw_vs_exact.bias : std::max(errors.raw_bias_max, e.raw_vs_exact.bias);
    if (seed == 1) {
      errors.filtered_image = image(frame.indirect.width, frame.indirect.height);
      errors.first_filtered = frame.indirect;
    }
    for (std::size_t i = 0; i < frame.indirect.texels.size(); ++i) errors.filtered_image.texels[i] += frame.indirect.texels[i] / static_cast<float>(seeds);
  }
  return errors;
}

// The coverage's settings as the reports name them.
std::string describe_coverage(int blocks, int interleave) {
  if (blocks <= 0) return "no coverage";
  return "coverage " + std::to_string(blocks) + " x " + std::to_string(blocks) + " blocks interleaved over " + std::to_string(interleave) + " x " +
         std::to_string(interleave) + " pixels";
}

struct technique_row {
  std::string label, technique;
  bool as_printed = false;  ///< rsm-original as printed: the xi1^2 weights and the same samples for every pixel
  int coverage_blocks = default_coverage_blocks;
};

// A frame of the pose file: its scene with the frame's camera and light, and its label (the
// line's comment, else the file and line).
struct posed_frame {
  scene source;
  std::string label;
};

posed_frame load_frame(const pose_frame& frame, const std::string& poses) {
  cli::common_options options;
  options.scene = frame.scene;
  options.camera_pose = frame.camera;
  options.light_pose = frame.light;
  return {cli::load_scene(options, frame.scene), frame.comment.empty() ? poses + ":" + std::to_string(frame.line) : frame.comment};
}

// A frame's references, each cached under `cache` when it is not empty: the brute force of the
// frame's own RSM (exact and unoccluded), the one-bounce Monte Carlo image (seed 1) and, when
// asked for, a second one of seed 2, from which the first's per-pixel noise is estimated
// (frontend/image/reference_noise.hpp). The key is the scene (its bytes, the posed camera and
// light) and the frame; the Monte Carlo files add their samples, revision and seed.
struct frame_references {
  frame_reference brute_force;
  image monte_carlo, monte_carlo_second;
};

// The one-bounce Monte Carlo image of `seed`, read from `file` when it is there, else computed
// (and written when `file` is not empty).
image cached_one_bounce(const scene& source, const rsm_pipeline_settings& settings, int mc_samples, std::uint32_t seed, int threads,
                        const std::string& file) {
  if (!file.empty() && fs::exists(file)) return read_image_file(file);
  image computed = reference_one_bounce(source, settings.width, settings.height, mc_samples, seed, threads).indirect;
  if (!file.empty()) write_all_or_nothing({{file, [&] { return encode_pfm(computed); }}});
  return computed;
}

frame_references load_references(const shader_library& shaders, const pose_frame& frame, const scene& source, const rsm_pipeline_settings& settings,
                                 int stride, int threads, int mc_samples, const std::string& cache, bool second_monte_carlo = false) {
  const std::string identity = study::scene_identity(frame.scene, source) + "\nframe " + std::to_string(settings.width) + " rsm " +
                               std::to_string(settings.rsm_size) + " stride " + std::to_string(stride);
  const std::string key = cache.empty() ? std::string() : (fs::path(cache) / cache_key(identity)).string();
  frame_references references{make_frame_reference(shaders, source, settings, stride, threads, key), image{}, image{}};
  // Seed 1's file keeps the name it had before the second seed existed, so caches stay valid.
  const std::string mc_file = key.empty() ? std::string() : key + "-mc" + std::to_string(mc_samples) + "-r" + std::to_string(monte_carlo_revision);
  references.monte_carlo = cached_one_bounce(source, settings, mc_samples, 1u, threads, mc_file.empty() ? mc_file : mc_file + ".pfm");
  if (second_monte_carlo)
    references.monte_carlo_second = cached_one_bounce(source, settings, mc_samples, 2u, threads, mc_file.empty() ? mc_file : mc_file + "-seed2.pfm");
  return references;
}

// Mean of the three channels over every pixel of an image.
double image_mean(const image& values) {
  double sum = 0.0;
  for (const glm::vec4& v : values.texels) sum += static_cast<double>(v.x) + v.y + v.z;
  return values.texels.empty() ? 0.0 : sum / (3.0 * static_cast<double>(values.texels.size()));
}

// The light of `source` tilted by `degrees` about the horizontal axis across its direction (a spot
// keeps its position; a sun's direction tilts the same way).
scene_light tilted(const scene_light& light, float degrees) {
  scene_light out = light;
  glm::vec3& direction = light.kind == light_kind::spot ? out.spot.direction : out.directional.direction;
  glm::vec3 axis = glm::cross(direction, glm::vec3(0, 1, 0));
  if (glm::length(axis) < 1e-3f) axis = glm::vec3(1, 0, 0);
  direction = glm::normalize(glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(degrees), glm::normalize(axis)) * glm::vec4(direction, 0.0f)));
  return out;
}

// The exact brute force at every receiver of the frame the pipeline drew last, through the same
// post filter (the CPU mirror of the blur passes): the filtered indirect irradiance it would show.
image filtered_brute_force(const rsm_pipeline& pipeline, const ray_scene& rays, int threads, image* raw = nullptr) {
  const rsm_pass_buffers buffers = pipeline.read_buffers();
  rsm_frame_constants constants = pipeline.constants();
  rsm_brute_force_options options;
  options.exact_visibility = true;
  options.threads = threads;
  image indirect = reference_rsm_gather(rays, buffers, constants, options);
  if (raw) *raw = indirect;  // before the filter's depth goes into .w
  for (int y = 0; y < indirect.height; ++y)  // the filter reads the camera depth from .w, as in the indirect buffer
    for (int x = 0; x < indirect.width; ++x) indirect.at(x, y).w = buffers.gbuffer[0].at(gbuffer_texel_of(glm::ivec2(x, y), constants)).w;
  const image input = constants.filter == post_filter::separable ? cpu_blur_x_pass(indirect, buffers, constants, threads) : indirect;
  return cpu_post_pass(input, buffers, constants, threads).indirect;
}

// Mean over the pixels and channels of |a - b|.
double mean_change(const image& a, const image& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.texels.size(); ++i) {
    const glm::vec4 d = glm::abs(a.texels[i] - b.texels[i]);
    sum += static_cast<double>(d.x) + d.y + d.z;
  }
  return sum / (3.0 * static_cast<double>(a.texels.size()));
}

// Where rsm-voxel's time goes: the C++ twin of the gather over every receiver of the frame the
// pipeline drew last, its grid read through a fetch that counts. A march is a visibility call
// that read the grid (the tangent planes let it through); every fetch is one step of the march.
struct march_counts {
  double receivers = 0.0, marches = 0.0, fetches = 0.0, hidden = 0.0;
};

march_counts count_voxel_marches(const rsm_pipeline& pipeline) {
  const rsm_pass_buffers buffers = pipeline.read_buffers();
  const rsm_frame_constants constants = pipeline.constants();
  const voxel_grid& grid = *buffers.voxels;
  const std::vector<rsm_texel<float>> rsm = unpack_rsm(buffers, constants);
  const std::vector<coarse_light<float>> coarse = coarse_lights_of(buffers);
  const int blocks = buffers.coarse[0].width;
  const auto fetch = [&](glm::ivec2 texel) { return rsm[static_cast<std::size_t>(texel.y) * static_cast<std::size_t>(buffers.rsm.width) + static_cast<std::size_t>(texel.x)]; };
  const auto coarse_fetch = [&](glm::ivec2 block) { return coarse[static_cast<std::size_t>(block.y) * static_cast<std::size_t>(blocks) + static_cast<std::size_t>(block.x)]; };
  march_counts counts;
  std::size_t fetches = 0;
  const auto counting_fetch = [&](glm::ivec2 texel) {
    ++fetches;
    return voxel_grid_fetch{&grid}(texel);
  };
  struct counting_visibility {
    voxel_rsm_visibility<float, decltype(counting_fetch)> march;
    std::size_t& fetches;
    march_counts& counts;
    void begin_path() {}
    int samples_per_march() const { return march.samples_per_march(); }  // the gather groups the samples as the pipeline's does
    float count(std::size_t before, float seen) {  // before: the fetches before the call (read first: argument order is unspecified)
      if (fetches > before) {
        counts.marches += 1.0;
        counts.hidden += seen == 0.0f ? 1.0 : 0.0;
      }
      return seen;
    }
    float operator()(const gather_receiver<float>& receiver, const rsm_texel<float>& light) {
      const std::size_t before = fetches;
      return count(before, march(receiver, light));
    }
    float coarse(const gather_receiver<float>& receiver, const coarse_light<float>& light) {
      const std::size_t before = fetches;
      return count(before, march.coarse(receiver, light));
    }
  };
  counting_visibility visibility{{counting_fetch, grid.shape, constants.voxel_march, voxel_cells_from(grid.shape, constants.light_view_inverse)}, fetches, counts};
  for (int y = 0; y < constants.indirect_size.y; ++y)
    for (int x = 0; x < constants.indirect_size.x; ++x) {
      const std::optional<gather_receiver<float>> receiver = gather_receiver_at(glm::ivec2(x, y), buffers, constants);
      if (!receiver) continue;
      counts.receivers += 1.0;
      if (coarse.empty()) (void)gather_rsm_with<rsm_pattern::radial>(*receiver, fetch, constants.gather, visibility);
      else (void)gather_rsm_with<rsm_pattern::radial>(*receiver, fetch, coarse_fetch, constants.gather, visibility);
    }
  counts.fetches = static_cast<double>(fetches);
  return counts;
}

struct spread {
  std::vector<double> values;
  void add(double value) { values.push_back(value); }
  std::string describe(int digits, bool as_percent = false) const {
    if (values.empty()) return "-";
    std::vector<double> sorted = values;
    std::sort(sorted.begin(), sorted.end());
    const auto show = [&](double v) { return as_percent ? percent(v) : fixed(v, digits); };
    return show(sorted.front()) + " / " + show(sorted[sorted.size() / 2]) + " / " + show(sorted.back());
  }
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"RSM techniques on every frame of a pose file, against the brute force and the Monte Carlo reference"};
  std::string poses, cache = "output/rsm-poses/cache", out = "output/rsm-poses";
  int size = 256, rsm_size = 512, stride = 2, seeds = 4, mc_samples = 64, flicker = 0, every = 1, after_jump = 0, warmup = 8;
  std::vector<std::string> sequence_techniques = {rsm_pipeline_settings().technique};
  float step = 0.5f, jump = 10.0f;
  std::vector<float> blends = {1.0f};
  int timing = 0, timing_size = 512, coverage_blocks = default_coverage_blocks, coverage_interleave = default_coverage_interleave;
  app.add_option("--poses", poses, "pose file: one frame per line, --scene FILE --camera ... --light ...")->required();
  app.add_option("--size", size, "image side (the indirect buffer: half)")->check(CLI::Range(16, 2048))->capture_default_str();
  app.add_option("--rsm-size", rsm_size, "RSM side")->check(CLI::Range(16, 4096))->capture_default_str();
  app.add_option("--stride", stride, "brute force at every stride-th receiver of the indirect buffer per axis")->check(CLI::Range(1, 64))->capture_default_str();
  app.add_option("--seeds", seeds, "pattern seeds per technique (metrics are their mean)")->check(CLI::Range(1, 64))->capture_default_str();
  app.add_option("--mc-samples", mc_samples, "bounce rays per pixel of the Monte Carlo reference")->check(CLI::Range(1, 65536))->capture_default_str();
  app.add_option("--cache", cache, "folder of the cached references (empty: no cache)")->capture_default_str();
  app.add_option("--out", out, "output folder")->capture_default_str();
  app.add_option("--flicker", flicker, "sequence mode: frames per sequence (the light tilted by --step degrees per frame); 0: the targets "
                                       "table instead")->check(CLI::Range(0, 64))->capture_default_str();
  app.add_option("--every", every, "sequence mode: a sequence from every N-th frame of the pose file")->check(CLI::Range(1, 1000))->capture_default_str();
  app.add_option("--step", step, "sequence mode: degrees the light tilts per frame")->capture_default_str();
  app.add_option("--warmup", warmup, "sequence mode: frames before the measured ones (the history settles)")->check(CLI::Range(0, 256))->capture_default_str();
  app.add_option("--technique", sequence_techniques, "sequence mode: the techniques")->capture_default_str();
  app.add_option("--jump", jump, "sequence mode: degrees the light jumps after the sequence")->capture_default_str();
  app.add_option("--after-jump", after_jump, "sequence mode: frames rendered after the jump (0: no jump)")->check(CLI::Range(0, 64))->capture_default_str();
  app.add_option("--temporal-blend", blends, "sequence mode: temporal blends to compare (1: none)")->capture_default_str();
  app.add_option("--timing", timing, "timing mode: frames timed per configuration (median), the default technique with and without "
                                     "coverage, interleaved, on every --every-th frame; 0: the targets table instead")
      ->check(CLI::Range(0, 100))->capture_default_str();
  app.add_option("--coverage-blocks", coverage_blocks, "the coverage's blocks per RSM side of every technique with coverage (targets), of every "
                                                     "sequence (sequence mode; 0: no coverage) and of the timed configuration with it (timing)")
      ->check(CLI::Range(0, rsm_coverage_max_blocks))->capture_default_str();
  app.add_option("--coverage-interleave", coverage_interleave, "the coverage's interleave side of every configuration with coverage (all modes)")
      ->check(CLI::Range(1, rsm_coverage_max_interleave))->capture_default_str();
  std::string disk_pattern = "per-pixel";
  app.add_option("--disk-pattern", disk_pattern, "targets: rsm-original's disk pattern (render's --disk-pattern); the \"as printed\" column keeps "
                                                 "the original's fixed pattern and weights")
      ->check(CLI::IsMember({"per-pixel", "fixed"}))->capture_default_str();
  bool voxel = false;
  app.add_flag("--voxel", voxel, "voxel mode (docs/rsm-study.md, \"Beyond one RSM\"): rsm-voxel against rsm-radial on every frame: the filtered "
                                 "indirect / Monte Carlo, the leak-region bias and the raw RMSE against the brute force relative to rsm-radial's, "
                                 "the frame's cost against rsm-radial's and rsm-alg6's (--timing frames, default 5; the grid's build apart) and "
                                 "the C++ twin's marches per receiver and grid fetches per march, and the moonshot: seed 1's filtered indirect against "
                                 "the Monte Carlo image per pixel, its noise (from a second Monte Carlo image, seed 2) taken out");
  voxel_grid_settings<float> grid_settings;
  voxel_march_settings<float> voxel_march;
  app.add_option("--voxel-resolution", grid_settings.resolution, "voxel mode: rsm-voxel's grid cells along the scene's longest side")
      ->check(CLI::Range(1, voxel_grid_max_resolution))->capture_default_str();
  app.add_option("--voxel-offset", voxel_march.start_offset, "voxel mode: rsm-voxel's start and end offsets (cells)")
      ->check(CLI::Range(0.0, 16.0))->capture_default_str();
  app.add_option("--voxel-group", voxel_march.group, "voxel mode: rsm-voxel's samples of a path per march")
      ->check(CLI::Range(1, voxel_max_group))->capture_default_str();
  app.add_option("--timing-size", timing_size, "timing mode: image side (the RSM: --rsm-size)")->check(CLI::Range(16, 4096))->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  if (coverage_blocks == 0 && flicker == 0) {
    // The targets and the timing compare techniques with the coverage against those without it.
    std::cerr << "vplkit_rsm_poses: error: --coverage-blocks 0 (no coverage) is for sequence mode (--flicker N) only\n";
    return 2;
  }
  try {
    const std::vector<pose_frame> frames = read_pose_file(poses, true);
    fs::create_directories(out);
    if (!cache.empty()) fs::create_directories(cache);
    auto context = create_headless_context();
    const shader_library shaders(default_shader_dir());
    const int threads = hardware_threads();
    if (timing > 0 && !voxel) {  // voxel mode reads --timing as its own repeat count
      // Timing mode: the cost of the coverage, the default technique with and without it, frames
      // interleaved (A B A B ...), wall clock around glFinish, median.
      std::ostringstream md;
      md << "# The coverage's cost on " << poses << "\n\n" << timing_size << "^2 image, RSM " << rsm_size << "^2, the default technique, "
         << describe_coverage(coverage_blocks, coverage_interleave) << "; wall clock "
         << "around glFinish of one whole frame, median of " << timing << ", the two configurations interleaved, on:\n\n```\n"
         << describe_current_context() << "\n```\n\n| frame | ms without coverage | ms with coverage | ratio |\n|---|---:|---:|---:|\n";
      spread ratios;
      for (std::size_t f = 0; f < frames.size(); f += static_cast<std::size_t>(every)) {
        const posed_frame posed = load_frame(frames[f], poses);
        const scene& source = posed.source;
        const std::string& label = posed.label;
        rsm_pipeline_settings with, without;
        with.width = with.height = timing_size;
        with.rsm_size = rsm_size;
        with.coverage_blocks = coverage_blocks;
        with.coverage_interleave = coverage_interleave;
        without = with;
        without.coverage_blocks = 0;
        const std::vector<double> ms = interleaved_frame_ms(shaders, source, {without, with}, timing);
        ratios.add(ms[1] / ms[0]);
        md << "| " << label << " | " << fixed(ms[0], 1) << " | " << fixed(ms[1], 1) << " | " << fixed(ms[1] / ms[0], 3) << " |\n";
        std::cerr << label << ": " << fixed(ms[0], 1) << " / " << fixed(ms[1], 1) << " ms\n";
      }
      md << "\nRatio with / without coverage, min / median / max over the frames: " << ratios.describe(3) << "\n";
      write_all_or_nothing({{fs::path(out) / "timing.md", [text = md.str()] { return std::vector<std::uint8_t>(text.begin(), text.end()); }}});
      std::cout << md.str() << "\nwrote " << fs::absolute(fs::path(out) / "timing.md").string() << "\n";
      return 0;
    }
    if (voxel) {
      // Voxel mode: the targets for rsm-voxel, frame by frame, against rsm-radial (the same
      // pattern without visibility): the image within +-15 % of the Monte Carlo reference, the leak
      // region's bias at most 1/4 of the radial gather's (region >= 2 %), the raw RMSE against
      // exact visibility below the radial gather's, the frame at most 2x the radial gather's.
      const int repeat = timing > 0 ? timing : 5;
      std::ostringstream md, rows, csv;
      // voxel.csv: every number of a frame's row at full precision (the table rounds to 2 digits,
      // and a ratio printed 0.85 may be just outside the image target), and the share of the
      // unoccluded light on receivers the pattern cannot reach (the coverage's coarse lights
      // light them alone: where a frame's misses come from).
      csv << std::setprecision(9) << "frame,leak_share,image_voxel,image_radial,leak_ratio,leak_bias_voxel,leak_bias_radial,rmse_ratio,rmse_voxel,rmse_radial,"
             "ms_radial,ms_alg6,ms_voxel,cost_radial,cost_alg6,grid_build_ms,marches_per_receiver,fetches_per_march,hidden_share,moonshot,"
             "moonshot_se,moonshot_radial,monte_carlo_noise,uncovered_share\n";
      int image_met = 0, leak_met = 0, leak_counted = 0, rmse_met = 0, cost_met = 0, cost_alg6_met = 0, counted = 0, moonshot_met = 0, moonshot_radial_met = 0;
      spread image_ratios, leak_ratios, rmse_ratios, cost_ratios, cost_alg6_ratios, build_ms, marched, steps, moonshots, moonshots_radial, mc_noise;
      for (const pose_frame& frame : frames) {
        const posed_frame posed = load_frame(frame, poses);
        const scene& source = posed.source;
        const std::string& label = posed.label;
        std::cerr << label << "\n";
        rsm_pipeline_settings settings;
        settings.coverage_blocks = coverage_blocks;
        settings.coverage_interleave = coverage_interleave;
        settings.width = settings.height = size;
        settings.rsm_size = rsm_size;
        const frame_references references = load_references(shaders, frame, source, settings, stride, threads, mc_samples, cache, true);
        const frame_reference& reference = references.brute_force;
        const image& monte_carlo = references.monte_carlo;
        const double mc_mean = image_mean(monte_carlo);
        if (!(mc_mean > 0.0) || !(image_mean(reference.exact) > 0.0)) {
          rows << "| " << label << " | no indirect light in view (left out) |||||||||\n";
          csv << csv_quoted(label) << ",no indirect light in view\n";
          continue;
        }
        ++counted;
        rsm_pipeline_settings radial_settings = settings, voxel_settings = settings;
        radial_settings.technique = "rsm-radial";
        voxel_settings.technique = "rsm-voxel";
        voxel_settings.voxel_grid = grid_settings;
        voxel_settings.voxel_march.start_offset = voxel_settings.voxel_march.end_offset = voxel_march.start_offset;
        voxel_settings.voxel_march.group = voxel_march.group;
        const technique_errors radial = measure_technique(shaders, source, radial_settings, reference, seeds);
        const technique_errors voxels = measure_technique(shaders, source, voxel_settings, reference, seeds);
        // rsm-alg6 (the thesis's visibility) timed beside them: the cost is also stated against it.
        rsm_pipeline_settings alg6_settings = settings;
        alg6_settings.technique = "rsm-alg6";
        const std::vector<double> ms = interleaved_frame_ms(shaders, source, {radial_settings, voxel_settings, alg6_settings}, repeat);
        const rsm_pipeline built(shaders, source, voxel_settings);
        const voxel_grid& grid = *built.voxels();
        const double image_voxel = image_mean(voxels.filtered_image) / mc_mean, image_radial = image_mean(radial.filtered_image) / mc_mean;
        const double leak_share = reference.receiver_count ? static_cast<double>(reference.leak_count) / static_cast<double>(reference.receiver_count) : 0.0;
        const bool leak_counts = leak_share >= 0.02;
        const double leak = radial.raw_leak.bias != 0.0 ? std::fabs(voxels.raw_leak.bias) / std::fabs(radial.raw_leak.bias) : 0.0;
        const double rmse = voxels.raw_vs_exact.rmse / radial.raw_vs_exact.rmse;
        const double cost = ms[1] / ms[0], cost_alg6 = ms[1] / ms[2];
        image_met += std::fabs(image_voxel - 1.0) <= 0.15;
        if (leak_counts) {
          ++leak_counted;
          leak_met += leak <= 0.25;
          leak_ratios.add(leak);
        }
        rmse_met += rmse < 1.0;
        cost_met += cost <= 2.0;
        cost_alg6_met += cost_alg6 <= 2.0;
        cost_alg6_ratios.add(cost_alg6);
        image_ratios.add(image_voxel);
        rmse_ratios.add(rmse);
        cost_ratios.add(cost);
        build_ms.add(built.voxel_build_ms());
        // The moonshot (issue 39): one frame's filtered indirect (seed 1, as the user sees it)
        // against the Monte Carlo image per pixel, the reference's own noise taken out (its
        // variance estimated from a second Monte Carlo image of another seed): without that, a
        // 32-ray reference's noise alone would put every frame far above the 10 % target.
        const image variance = variance_of_two(monte_carlo, references.monte_carlo_second);
        const reference_noise moonshot = reference_noise_of(voxels.first_filtered, monte_carlo, variance),
                              moonshot_radial = reference_noise_of(radial.first_filtered, monte_carlo, variance);
        if (!moonshot.defined) throw error(label + ": the moonshot metric is undefined: " + moonshot.why_undefined);
        moonshots.add(moonshot.rmse_corrected);
        moonshots_radial.add(moonshot_radial.rmse_corrected);
        mc_noise.add(moonshot.noise);
        moonshot_met += moonshot.rmse_corrected <= 0.10;
        moonshot_radial_met += moonshot_radial.rmse_corrected <= 0.10;
        rsm_pipeline counted_pipeline(shaders, source, voxel_settings);
        (void)counted_pipeline.render();
        const march_counts marches = count_voxel_marches(counted_pipeline);
        const double marches_per_receiver = marches.marches / std::max(marches.receivers, 1.0);
        const double fetches_per_march = marches.fetches / std::max(marches.marches, 1.0);
        marched.add(marches_per_receiver);
        steps.add(fetches_per_march);
        rows << "| " << label << " | " << percent(leak_share) << " % | " << fixed(image_voxel, 2) << " (" << fixed(image_radial, 2) << ") | "
             << (leak_counts ? fixed(leak, 2) : std::string("-")) << " (" << percent(voxels.raw_leak.bias) << " % / " << percent(radial.raw_leak.bias)
             << " %) | " << fixed(rmse, 2) << " (" << percent(voxels.raw_vs_exact.rmse) << " % / " << percent(radial.raw_vs_exact.rmse) << " %) | "
             << fixed(ms[0], 1) << " / " << fixed(ms[2], 1) << " / " << fixed(ms[1], 1) << " (" << fixed(cost, 2) << ", " << fixed(cost_alg6, 2) << ") | " << grid.shape.cells.x << "x" << grid.shape.cells.y << "x"
             << grid.shape.cells.z << ", " << grid.bytes() / 1024 << " KiB, " << fixed(built.voxel_build_ms(), 1) << " ms | " << fixed(marches_per_receiver, 1)
             << ", " << fixed(fetches_per_march, 1) << ", " << percent(marches.hidden / std::max(marches.marches, 1.0)) << " % | " << percent(moonshot.rmse_corrected)
             << " +- " << percent(moonshot.rmse_se) << " % (" << percent(moonshot_radial.rmse_corrected) << " %; " << percent(moonshot.noise) << " %) |\n";
        csv << csv_quoted(label) << "," << leak_share << "," << image_voxel << "," << image_radial << ",";
        if (leak_counts) csv << leak;  // empty where the region holds < 2 % (not counted)
        csv << "," << voxels.raw_leak.bias << "," << radial.raw_leak.bias << "," << rmse << "," << voxels.raw_vs_exact.rmse << "," << radial.raw_vs_exact.rmse << ","
            << ms[0] << "," << ms[2] << "," << ms[1] << "," << cost << "," << cost_alg6 << "," << built.voxel_build_ms() << "," << marches_per_receiver << ","
            << fetches_per_march << "," << marches.hidden / std::max(marches.marches, 1.0) << "," << moonshot.rmse_corrected << "," << moonshot.rmse_se << ","
            << moonshot_radial.rmse_corrected << "," << moonshot.noise << "," << reference.uncovered_share << "\n";
        std::cerr << "  image " << fixed(image_voxel, 2) << " (radial " << fixed(image_radial, 2) << "), leak " << fixed(leak, 2)
                  << (leak_counts ? "" : " (region < 2 %)") << ", rmse " << fixed(rmse, 2) << ", cost " << fixed(cost, 2) << " (rsm-alg6's " << fixed(cost_alg6, 2)
                  << "), moonshot " << percent(moonshot.rmse_corrected) << " % (radial " << percent(moonshot_radial.rmse_corrected) << " %)\n";
      }
      md << "# rsm-voxel on " << poses << "\n\n" << counted << " frames, " << size << "^2 image, RSM " << rsm_size << "^2, brute force at every "
         << stride << "th receiver per axis, seeds 1-" << seeds << ", Monte Carlo " << mc_samples << " bounce rays per pixel, "
         << describe_coverage(coverage_blocks, coverage_interleave) << ", the grid " << grid_settings.resolution << " cells along the scene's longest side, "
         << "offsets " << fixed(voxel_march.start_offset, 2) << " cells, " << voxel_march.group << " samples of a path per march; frame cost: wall clock around glFinish, median of "
         << repeat << ", rsm-radial, rsm-voxel and rsm-alg6 interleaved; the grid's build (CPU, once per scene) apart; on:\n\n```\n" << describe_current_context()
         << "\n```\n\n| target | frames met | min / median / max |\n|---|---:|---:|\n"
         << "| filtered indirect / Monte Carlo in [0.85, 1.15] | " << image_met << " / " << counted << " | " << image_ratios.describe(2) << " |\n"
         << "| leak-region bias / radial's <= 0.25 (region >= 2 %) | " << leak_met << " / " << leak_counted << " | " << leak_ratios.describe(2) << " |\n"
         << "| raw rel. RMSE vs exact / radial's < 1 | " << rmse_met << " / " << counted << " | " << rmse_ratios.describe(2) << " |\n"
         << "| frame ms / radial's <= 2 | " << cost_met << " / " << counted << " | " << cost_ratios.describe(2) << " |\n"
         << "| frame ms / rsm-alg6's <= 2 | " << cost_alg6_met << " / " << counted << " | " << cost_alg6_ratios.describe(2) << " |\n"
         << "| moonshot: filtered per-pixel rel. RMSE vs Monte Carlo, its noise out, <= 10 % (median <= 15 %) | " << moonshot_met << " / " << counted << " | "
         << moonshots.describe(1, true) << " % |\n"
         << "\nThe moonshot's image is seed 1's filtered indirect (one frame as the user sees it); the Monte Carlo image's noise (its variance per pixel "
            "from a second image of seed 2, taken out of the mean squared error) is " << mc_noise.describe(1, true) << " % of its mean (min / median / max); "
            "that variance, from two images, has long tails with few rays (32 rays read 14-482 points off 256 on 15 of 163 frames, "
            "docs/rsm-study.md): read the moonshot at --mc-samples 256 or more. "
            "rsm-radial on the same metric: " << moonshot_radial_met << " / " << counted << " frames <= 10 %, " << moonshots_radial.describe(1, true) << " %.\n"
         << "\nGrid build (ms, min / median / max): " << build_ms.describe(1) << ". Marches per receiver (the C++ twin on seed 1's frame, "
            "every receiver of the indirect buffer): " << marched.describe(1) << "; grid fetches per march: " << steps.describe(1) << ".\n\n## Frame by frame\n\n"
         << "| frame | leak region | filtered / MC: voxel (radial) | leak bias / radial's (voxel / radial) | raw rel. RMSE / radial's (voxel / radial) "
            "| frame ms: radial / alg6 / voxel (voxel / radial, voxel / alg6) | grid: cells, memory, build | marches per receiver, fetches per march, hidden "
            "| moonshot: voxel +- the standard error the reference's noise leaves (radial; Monte Carlo's noise) |\n"
            "|---|---:|---:|---:|---:|---:|---|---:|---:|\n"
         << rows.str();
      write_all_or_nothing({{fs::path(out) / "voxel.md", [text = md.str()] { return std::vector<std::uint8_t>(text.begin(), text.end()); }},
                            {fs::path(out) / "voxel.csv", [text = csv.str()] { return std::vector<std::uint8_t>(text.begin(), text.end()); }}});
      std::cout << md.str() << "\nwrote " << fs::absolute(fs::path(out) / "voxel.md").string() << "\n";
      return 0;
    }
    if (flicker > 0) {
      // Sequence mode: the flicker ratio and the lag after a jump. The light tilts by --step degrees
      // per frame: --warmup frames (no reference: the history settles), then --flicker measured
      // frames, then it jumps by --jump degrees and stays for --after-jump frames.
      std::ostringstream md;
      md << "# Flicker on " << poses << "\n\n" << size << "^2 image, RSM " << rsm_size << "^2, "
         << describe_coverage(coverage_blocks, coverage_interleave) << "; the light tilts by " << step
         << " degrees per frame: " << warmup << " frames to settle, " << flicker << " measured, then it jumps by " << jump << " degrees and stays for "
         << after_jump << " frames. Flicker ratio: the mean absolute frame-to-frame change of the filtered indirect irradiance over the image (what "
         << "the user sees of the indirect light), divided by that of the exact brute force at every receiver after the same post filter; raw: the "
         << "post filter's input (the gather, or its accumulation) against the brute force at the indirect buffer's receivers. Error: relative RMSE of the filtered indirect against the "
         << "filtered brute force over the image, on the last measured frame; after the jump, frame by frame. Lag: frames after the jump until the "
         << "error is within 10 % of what the same technique without accumulation makes on that frame.\n\n"
         << "| frame | technique | temporal blend | flicker ratio | raw flicker ratio | error | error after the jump (frames 1, 2, ...) | lag |\n"
            "|---|---|---:|---:|---:|---:|---|---:|\n";
      std::map<std::pair<std::string, float>, spread> ratios, errors_at_rest, lags;
      for (std::size_t f = 0; f < frames.size(); f += static_cast<std::size_t>(every)) {
        const posed_frame posed = load_frame(frames[f], poses);
        const scene& source = posed.source;
        const std::string& label = posed.label;
        const ray_scene rays(source.geometry);
        std::cerr << label << "\n";
        rsm_pipeline_settings settings;
        settings.coverage_blocks = coverage_blocks;
        settings.coverage_interleave = coverage_interleave;
        settings.width = settings.height = size;
        settings.rsm_size = rsm_size;
        const int measured_end = warmup + flicker, total = measured_end + after_jump;
        const auto light_of = [&](int k) {
          return tilted(source.lights[0], k < measured_end ? step * static_cast<float>(k) : step * static_cast<float>(measured_end - 1) + jump);
        };
        // The brute force of the measured frames and of the pose after the jump.
        std::vector<image> reference_filtered(static_cast<std::size_t>(total)), reference_raw(static_cast<std::size_t>(total));
        {
          rsm_pipeline pipeline(shaders, source, settings);
          for (int k = warmup; k < total; ++k) {
            const std::size_t i = static_cast<std::size_t>(k);
            if (k > measured_end) {
              reference_filtered[i] = reference_filtered[i - 1];
              continue;
            }
            pipeline.set_light(0, light_of(k));
            pipeline.render();
            reference_filtered[i] = filtered_brute_force(pipeline, rays, threads, &reference_raw[i]);
          }
        }
        for (const std::string& technique : sequence_techniques) {
        std::vector<double> errors_without;  // after the jump, without accumulation (blend 1), frame by frame
        std::vector<float> order = blends;
        std::stable_sort(order.begin(), order.end(), [](float a, float b) { return a > b; });  // blend 1 first
        for (const float blend : order) {
          rsm_pipeline_settings s = settings;
          s.technique = technique;
          s.temporal.blend = blend;
          rsm_pipeline pipeline(shaders, source, s);
          pipeline.render();  // the shader compilers' lazy work
          std::vector<image> filtered(static_cast<std::size_t>(total)), raw(static_cast<std::size_t>(total));
          for (int k = 0; k < total; ++k) {
            pipeline.set_light(0, light_of(k));
            const rsm_frame rendered = pipeline.render_next();
            if (k < warmup) continue;
            filtered[static_cast<std::size_t>(k)] = rendered.indirect;
            const rsm_pass_buffers buffers = pipeline.read_buffers();  // the filter's input: accumulated, or the gather
            raw[static_cast<std::size_t>(k)] = buffers.accumulated.texels.empty() ? buffers.indirect : buffers.accumulated;
          }
          double change = 0.0, reference_change = 0.0, raw_change = 0.0, raw_reference_change = 0.0;
          for (int k = warmup + 1; k < measured_end; ++k) {
            const std::size_t i = static_cast<std::size_t>(k);
            change += mean_change(filtered[i], filtered[i - 1]);
            reference_change += mean_change(reference_filtered[i], reference_filtered[i - 1]);
            image a = raw[i], b = raw[i - 1];
            for (image* each : {&a, &b})
              for (glm::vec4& v : each->texels) v.w = 0.0f;
            raw_change += mean_change(a, b);
            raw_reference_change += mean_change(reference_raw[i], reference_raw[i - 1]);
          }
          const double ratio = reference_change > 0.0 ? change / reference_change : 0.0;
          const auto error_at = [&](int k) {
            return relative_error_of(filtered[static_cast<std::size_t>(k)], reference_filtered[static_cast<std::size_t>(k)]).rmse;
          };
          std::string after;
          std::vector<double> jump_errors;
          for (int k = measured_end; k < total; ++k) {
            jump_errors.push_back(error_at(k));
            after += (after.empty() ? "" : ", ") + percent(jump_errors.back());
          }
          if (blend >= 1.0f) errors_without = jump_errors;
          int lag = 0;
          if (!errors_without.empty()) {
            lag = static_cast<int>(jump_errors.size());
            for (std::size_t k = 0; k < jump_errors.size(); ++k)
              if (jump_errors[k] <= 1.1 * errors_without[k]) {
                lag = static_cast<int>(k);
                break;
              }
          }
          ratios[{technique, blend}].add(ratio);
          errors_at_rest[{technique, blend}].add(error_at(measured_end - 1));
          lags[{technique, blend}].add(lag);
          md << "| " << label << " | " << technique << " | " << blend << " | " << fixed(ratio, 2) << " | " << fixed(raw_reference_change > 0.0 ? raw_change / raw_reference_change : 0.0, 2)
             << " | " << percent(error_at(measured_end - 1)) << " % | " << after << " | " << lag << " |\n";
          std::cerr << "  " << technique << " blend " << blend << ": flicker " << fixed(ratio, 2) << ", error " << percent(error_at(measured_end - 1))
                    << " %, after the jump " << after << ", lag " << lag << "\n";
        }
        }
      }
      md << "\n| technique | temporal blend | flicker ratio min / median / max | error min / median / max | lag (frames) min / median / max |\n"
            "|---|---:|---:|---:|---:|\n";
      for (const auto& [key, values] : ratios)
        md << "| " << key.first << " | " << key.second << " | " << values.describe(2) << " | " << errors_at_rest[key].describe(1, true) << " % | "
           << lags[key].describe(0) << " |\n";
      write_all_or_nothing({{fs::path(out) / "flicker.md", [text = md.str()] { return std::vector<std::uint8_t>(text.begin(), text.end()); }}});
      std::cout << md.str() << "\nwrote " << fs::absolute(fs::path(out) / "flicker.md").string() << "\n";
      return 0;
    }
    const std::vector<technique_row> techniques = {{"radial", "rsm-radial", false, coverage_blocks},
                                                   {"alg6", "rsm-alg6", false, coverage_blocks},
                                                   {"alg6-ray", "rsm-alg6-ray", false, coverage_blocks},
                                                   {"alg6-ray without coverage", "rsm-alg6-ray", false, 0},
                                                   {"original", "rsm-original", false, coverage_blocks},
                                                   {"original (as printed)", "rsm-original", true, coverage_blocks}};
    // The targets of a candidate for the default technique, frame by frame.
    struct targets {
      spread rmse_ratio, leak_ratio, image_ratio;
      int rmse_met = 0, rmse_counted = 0, leak_met = 0, leak_counted = 0, image_met = 0;
    };
    // Frames without indirect light in view (the reference and the Monte Carlo image are 0 over
    // the image): no ratio exists; listed, left out of the targets.
    std::vector<std::string> empty_frames;
    std::map<std::string, targets> candidates{{"alg6", {}}, {"alg6-ray", {}}};
    spread original_bias, printed_bias, uncovered, missed, missed_without, image_without, coverage_bias;
    // Over-occlusion: each visibility's most negative bias against exact visibility over every
    // receiver (the mean of the seeds, and the lowest and highest seed on that frame), and the
    // frames where it is below -10 %.
    struct darkest_frame {
      double bias = 0.0, lowest = 0.0, highest = 0.0;
      std::string frame;
      int below_10 = 0;
    };
    std::map<std::string, darkest_frame> darkest{{"radial", {}}, {"alg6", {}}, {"alg6-ray", {}}};
    int original_met = 0;

    std::ostringstream table, csv;
    table << "| frame | uncovered light | leak region | rel. RMSE / radial's: Alg. 6, alg6-ray (radial's) | leak bias / radial's: Alg. 6, alg6-ray "
             "(radial's) | filtered indirect / Monte Carlo: alg6-ray (without coverage) | alg6-ray bias, all receivers (without coverage) "
             "| rsm-original bias (as printed: its weights and fixed pattern) |\n|---|---:|---:|---:|---:|---:|---:|---:|\n";
    csv << "frame,receivers,uncovered_share,leak_share,radial_rmse,radial_leak_bias,mc_mean";
    for (const technique_row& t : techniques)
      csv << "," << t.label << " rmse," << t.label << " bias," << t.label << " leak bias," << t.label << " covered rmse," << t.label << " image ratio,"
          << t.label << " uncovered bias vs unoccluded," << t.label << " uncovered rmse vs unoccluded," << t.label << " bias lowest seed," << t.label
          << " bias highest seed";
    csv << "\n";
    for (const pose_frame& frame : frames) {
      const posed_frame posed = load_frame(frame, poses);
      const scene& source = posed.source;
      const std::string& label = posed.label;
      std::cerr << label << "\n";
      rsm_pipeline_settings settings;
      settings.coverage_interleave = coverage_interleave;
      settings.width = settings.height = size;
      settings.rsm_size = rsm_size;
      const frame_references references = load_references(shaders, frame, source, settings, stride, threads, mc_samples, cache);
      const frame_reference& reference = references.brute_force;
      const image& monte_carlo = references.monte_carlo;
      const double mc_mean = image_mean(monte_carlo);
      if (!(mc_mean > 0.0) || !(image_mean(reference.exact) > 0.0)) {
        empty_frames.push_back(label);
        table << "| " << label << " | no indirect light in view (left out) ||||||||\n";
        std::cerr << "  no indirect light in view: left out\n";
        continue;
      }
      std::map<std::string, technique_errors> errors;
      for (const technique_row& t : techniques) {
        rsm_pipeline_settings s = settings;
        s.technique = t.technique;
        s.disk.printed_weights = t.as_printed;
        s.disk.per_pixel_shift = !t.as_printed && disk_pattern == "per-pixel";
        s.coverage_blocks = t.coverage_blocks;
        errors[t.label] = measure_technique(shaders, source, s, reference, seeds);
      }
      const auto image_ratio = [&](const technique_errors& e) { return mc_mean > 0.0 ? image_mean(e.filtered_image) / mc_mean : 0.0; };
      const technique_errors& radial = errors["radial"];
      const double leak_share = reference.receiver_count ? static_cast<double>(reference.leak_count) / static_cast<double>(reference.receiver_count) : 0.0;
      const bool leak_counts = leak_share >= 0.02;
      std::map<std::string, std::pair<double, double>> ratios;  // rmse ratio, leak ratio
      for (auto& [name, t] : candidates) {
        const technique_errors& e = errors[name];
        const double ratio = e.raw_vs_exact.rmse / radial.raw_vs_exact.rmse;
        const double leak = radial.raw_leak.bias != 0.0 ? std::fabs(e.raw_leak.bias) / std::fabs(radial.raw_leak.bias) : 0.0;
        const double image = image_ratio(e);
        ratios[name] = {ratio, leak};
        t.rmse_ratio.add(ratio);
        t.image_ratio.add(image);
        // Where exact visibility removes < 2 % of the light, every visibility test can only match
        // the radial gather (ratio 1 when the pattern covers nothing): such frames are not counted.
        if (reference.occluded_share >= 0.02) {
          ++t.rmse_counted;
          t.rmse_met += ratio < 1.0;
        }
        t.image_met += std::fabs(image - 1.0) <= 0.15;
        if (leak_counts) {
          t.leak_ratio.add(leak);
          ++t.leak_counted;
          t.leak_met += leak <= 0.5;
        }
      }
      for (auto& [name, d] : darkest) {
        const technique_errors& e = errors[name];
        if (d.frame.empty() || e.raw_vs_exact.bias < d.bias) d = {e.raw_vs_exact.bias, e.raw_bias_min, e.raw_bias_max, label, d.below_10};
        d.below_10 += e.raw_vs_exact.bias < -0.10;
      }
      const technique_errors &ray = errors["alg6-ray"], &ray_without = errors["alg6-ray without coverage"];
      const double original = errors["original"].raw_vs_unoccluded.bias, printed = errors["original (as printed)"].raw_vs_unoccluded.bias;
      original_bias.add(original);
      printed_bias.add(printed);
      original_met += std::fabs(original) <= 0.10;
      uncovered.add(reference.uncovered_share);
      missed.add(ray.raw_vs_exact.bias);
      missed_without.add(ray_without.raw_vs_exact.bias);
      image_without.add(image_ratio(ray_without));
      // The coverage's own bias: the gather without visibility, whose off-map receivers' pattern
      // samples remove no light (a visibility test's would count as coverage bias).
      if (reference.uncovered_share >= 0.02) coverage_bias.add(radial.raw_uncovered_vs_unoccluded.bias);
      table << "| " << label << " | " << percent(reference.uncovered_share) << " % | " << percent(leak_share) << " % | " << fixed(ratios["alg6"].first, 2) << ", "
            << fixed(ratios["alg6-ray"].first, 2) << " (" << percent(radial.raw_vs_exact.rmse) << " %) | "
            << (leak_counts ? fixed(ratios["alg6"].second, 2) + ", " + fixed(ratios["alg6-ray"].second, 2) : std::string("-")) << " ("
            << percent(radial.raw_leak.bias) << " %) | " << fixed(image_ratio(ray), 2) << " (" << fixed(image_ratio(ray_without), 2) << ") | "
            << percent(ray.raw_vs_exact.bias) << " % (" << percent(ray_without.raw_vs_exact.bias) << " %) | " << percent(original) << " % ("
            << percent(printed) << " %) |\n";
      csv << "\"" << label << "\"," << reference.receiver_count << "," << reference.uncovered_share << "," << leak_share << "," << radial.raw_vs_exact.rmse << ","
          << radial.raw_leak.bias << "," << mc_mean;
      for (const technique_row& t : techniques) {
        const technique_errors& e = errors[t.label];
        csv << "," << e.raw_vs_exact.rmse << "," << e.raw_vs_exact.bias << "," << e.raw_leak.bias << "," << e.raw_covered_vs_exact.rmse << "," << image_ratio(e)
            << "," << e.raw_uncovered_vs_unoccluded.bias << "," << e.raw_uncovered_vs_unoccluded.rmse << "," << e.raw_bias_min << "," << e.raw_bias_max;
      }
      csv << "\n";
      std::cerr << "  rmse ratio alg6 " << fixed(ratios["alg6"].first, 2) << " alg6-ray " << fixed(ratios["alg6-ray"].first, 2) << ", leak "
                << fixed(ratios["alg6"].second, 2) << " / " << fixed(ratios["alg6-ray"].second, 2) << (leak_counts ? "" : " (region < 2 %)") << ", image "
                << fixed(image_ratio(ray), 2) << " (" << fixed(image_ratio(ray_without), 2) << " without coverage), original " << percent(original) << " %\n";
    }
    const std::size_t n = frames.size() - empty_frames.size();  // the frames counted
    std::ostringstream md;
    md << "# RSM techniques on " << poses << "\n\n" << n << " frames, " << size << "^2 image, RSM " << rsm_size << "^2, brute force at every " << stride
       << "th receiver per axis (every receiver with a surface, covered by the pattern or not), seeds 1-" << seeds << ", Monte Carlo " << mc_samples
       << " bounce rays per pixel, " << describe_coverage(coverage_blocks, coverage_interleave) << ", on:\n\n```\n" << describe_current_context() << "\n```\n\n## Targets (min / median / max over the frames)\n\n"
       << "| target | technique | frames met | min / median / max |\n|---|---|---:|---:|\n";
    for (const auto& [name, t] : candidates)
      md << "| rel. RMSE vs exact / radial's < 1 (visibility removes >= 2 %) | " << name << " | " << t.rmse_met << " / " << t.rmse_counted << " | "
         << t.rmse_ratio.describe(2) << " |\n"
         << "| leak-region bias / radial's <= 0.5 (region >= 2 %) | " << name << " | " << t.leak_met << " / " << t.leak_counted << " | "
         << t.leak_ratio.describe(2) << " |\n"
         << "| filtered indirect / Monte Carlo in [0.85, 1.15] | " << name << " | " << t.image_met << " / " << n << " | " << t.image_ratio.describe(2)
         << " |\n";
    std::string left_out;
    for (const std::string& e : empty_frames) left_out += (left_out.empty() ? "" : ", ") + e;
    md << "| rsm-original |bias| vs unoccluded <= 10 % | rsm-original | " << original_met << " / " << n << " | " << original_bias.describe(1, true) << " % |\n"
       << "\nLeft out, no indirect light in view: " << (left_out.empty() ? std::string("none") : left_out) << ".\n"
       << "\nrsm-original as printed (its weights, the same samples for every pixel): bias " << printed_bias.describe(1, true) << " %. Light on receivers the pattern cannot reach: "
       << uncovered.describe(1, true) << " % of the unoccluded light. alg6-ray's bias against exact visibility over every receiver: "
       << missed.describe(1, true) << " % with coverage, " << missed_without.describe(1, true) << " % without; its filtered image / Monte Carlo "
       << "without coverage: " << image_without.describe(2) << ". On the receivers the pattern cannot reach (frames where they hold >= 2 % of the "
       << "light), the coverage's bias against the unoccluded brute force (rsm-radial, no visibility): " << coverage_bias.describe(1, true) << " %.\n\n"
       << "## Over-occlusion\n\nThe most negative bias against exact visibility over every receiver (mean of the seeds; the lowest and the "
          "highest seed on that frame), and the frames where it is below -10 %:\n\n| technique | darkest frame | bias | seeds | frames below -10 % |\n"
          "|---|---|---:|---:|---:|\n";
    for (const auto& [name, d] : darkest)
      md << "| " << name << " | " << d.frame << " | " << percent(d.bias) << " % | " << percent(d.lowest) << " to " << percent(d.highest) << " % | "
         << d.below_10 << " / " << n << " |\n";
    md << "\n## Frame by frame\n\n"
       << table.str();
    write_all_or_nothing({{fs::path(out) / "poses.md", [text = md.str()] { return std::vector<std::uint8_t>(text.begin(), text.end()); }},
                          {fs::path(out) / "poses.csv", [text = csv.str()] { return std::vector<std::uint8_t>(text.begin(), text.end()); }}});
    std::cout << md.str() << "\nwrote " << fs::absolute(fs::path(out) / "poses.md").string() << "\n";
  } catch (const std::exception& failure) {
    std::cerr << "vplkit_rsm_poses: error: " << failure.what() << "\n";
    return 1;
  }
  return 0;
}
