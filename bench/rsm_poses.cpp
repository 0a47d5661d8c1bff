// The RSM techniques on any frame (docs/rsm-study.md, "Any frame"): every frame of a pose file
// measured against its ground truth, frame by frame, with the worst frame and the spread.
//   build/bench/vplkit_rsm_poses --poses bench/poses/holdout.txt [--size 256] [--rsm-size 512]
//       [--stride 2] [--seeds 4] [--mc-samples 64] [--cache output/rsm-poses/cache] [--out output/rsm-poses]
// A pose file holds one frame per line, render's options: --scene FILE --camera ... --light ...
// (bench/poses/, written by vplkit_study_set). For each frame:
// - the brute-force gather of every lit RSM texel with and without exact visibility at every
//   stride-th receiver of the indirect buffer that has a surface, covered by the pattern or not
//   (bench/rsm_measure.hpp; cached under --cache, the slow part);
// - the one-bounce Monte Carlo reference of the image (cached);
// - each technique at the defaults, seeds 1..--seeds, raw and filtered.
// Targets (issue 23), per frame: Alg. 6's relative RMSE against exact visibility below the radial
// gather's; |leak-region bias| at most half the radial gather's where the leak region holds >= 2 %
// of the receivers; the filtered indirect irradiance of the whole image within +-15 % of the Monte
// Carlo reference's; rsm-original's |bias| against the unoccluded brute force <= 10 %.
// Writes poses.md (a row per frame, the targets with the worst frame and the spread) and poses.csv.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "bench/rsm_measure.hpp"
#include "frontend/cli/options.hpp"
#include "frontend/core/error.hpp"
#include "frontend/core/files.hpp"
#include "frontend/core/parallel.hpp"
#include "frontend/gl/context.hpp"
#include "frontend/image/image_files.hpp"
#include "frontend/scene/pose.hpp"
#include "frontend/techniques/rsm/rsm_cpu_mirror.hpp"

#include <glm/gtc/matrix_transform.hpp>

namespace fs = std::filesystem;
using namespace vplkit;

namespace {

struct technique_row {
  std::string label, technique;
  bool printed_disk_weights = false;
};

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
image filtered_brute_force(const rsm_pipeline& pipeline, const ray_scene& rays, int threads) {
  const rsm_pass_buffers buffers = pipeline.read_buffers();
  rsm_frame_constants constants = pipeline.constants();
  rsm_brute_force_options options;
  options.exact_visibility = true;
  options.threads = threads;
  image indirect = reference_rsm_gather(rays, buffers, constants, options);
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
  int size = 256, rsm_size = 512, stride = 2, seeds = 4, mc_samples = 64, flicker = 0, every = 1, after_jump = 0;
  float step = 0.5f, jump = 10.0f;
  std::vector<float> blends = {1.0f};
  int timing = 0, timing_size = 512;
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
  app.add_option("--jump", jump, "sequence mode: degrees the light jumps after the sequence")->capture_default_str();
  app.add_option("--after-jump", after_jump, "sequence mode: frames rendered after the jump (0: no jump)")->check(CLI::Range(0, 64))->capture_default_str();
  app.add_option("--temporal-blend", blends, "sequence mode: temporal blends to compare (1: none)")->capture_default_str();
  app.add_option("--timing", timing, "timing mode: frames timed per configuration (median), the default technique with and without "
                                     "coverage, interleaved, on every --every-th frame; 0: the targets table instead")
      ->check(CLI::Range(0, 100))->capture_default_str();
  app.add_option("--timing-size", timing_size, "timing mode: image side (the RSM: --rsm-size)")->check(CLI::Range(16, 4096))->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    const std::vector<pose_frame> frames = read_pose_file(poses, true);
    fs::create_directories(out);
    if (!cache.empty()) fs::create_directories(cache);
    auto context = create_headless_context();
    const shader_library shaders(default_shader_dir());
    const int threads = hardware_threads();
    if (timing > 0) {
      // Timing mode: the cost of the coverage, the default technique with and without it, frames
      // interleaved (A B A B ...), wall clock around glFinish, median.
      std::ostringstream md;
      md << "# The coverage's cost on " << poses << "\n\n" << timing_size << "^2 image, RSM " << rsm_size << "^2, the default technique; wall clock "
         << "around glFinish of one whole frame, median of " << timing << ", the two configurations interleaved, on:\n\n```\n"
         << describe_current_context() << "\n```\n\n| frame | ms without coverage | ms with coverage | ratio |\n|---|---:|---:|---:|\n";
      spread ratios;
      for (std::size_t f = 0; f < frames.size(); f += static_cast<std::size_t>(every)) {
        const pose_frame& frame = frames[f];
        cli::common_options options;
        options.scene = frame.scene;
        options.camera_pose = frame.camera;
        options.light_pose = frame.light;
        const scene source = cli::load_scene(options, frame.scene);
        rsm_pipeline_settings with, without;
        with.width = with.height = timing_size;
        with.rsm_size = rsm_size;
        without = with;
        without.coverage_blocks = 0;
        const std::vector<double> ms = interleaved_frame_ms(shaders, source, {without, with}, timing);
        const std::string label = frame.comment.empty() ? poses + ":" + std::to_string(frame.line) : frame.comment;
        ratios.add(ms[1] / ms[0]);
        md << "| " << label << " | " << fixed(ms[0], 1) << " | " << fixed(ms[1], 1) << " | " << fixed(ms[1] / ms[0], 3) << " |\n";
        std::cerr << label << ": " << fixed(ms[0], 1) << " / " << fixed(ms[1], 1) << " ms\n";
      }
      md << "\nRatio with / without coverage, min / median / max over the frames: " << ratios.describe(3) << "\n";
      write_all_or_nothing({{fs::path(out) / "timing.md", [text = md.str()] { return std::vector<std::uint8_t>(text.begin(), text.end()); }}});
      std::cout << md.str() << "\nwrote " << fs::absolute(fs::path(out) / "timing.md").string() << "\n";
      return 0;
    }
    if (flicker > 0) {
      // Sequence mode: the flicker ratio and the lag after a jump of the default technique.
      std::ostringstream md;
      md << "# Flicker on " << poses << "\n\n" << size << "^2 image, RSM " << rsm_size << "^2; the light tilts by " << step << " degrees per frame over "
         << flicker << " frames, then jumps by " << jump << " degrees for " << after_jump << " frames. Flicker ratio: the mean absolute frame-to-frame "
         << "change of the filtered indirect irradiance over the image, divided by that of the exact brute force (every receiver) after the same post "
         << "filter; raw: the gather's output against the brute force's at the indirect buffer's receivers. Error: relative RMSE of the filtered "
         << "indirect against the filtered brute force over the image, last sequence frame; after the jump, frame by frame.\n\n"
         << "| frame | temporal blend | flicker ratio | raw flicker ratio | error | error after the jump (frames 1, 2, ...) |\n|---|---:|---:|---:|---:|---|\n";
      std::map<float, spread> ratios;
      for (std::size_t f = 0; f < frames.size(); f += static_cast<std::size_t>(every)) {
        const pose_frame& frame = frames[f];
        cli::common_options options;
        options.scene = frame.scene;
        options.camera_pose = frame.camera;
        options.light_pose = frame.light;
        const scene source = cli::load_scene(options, frame.scene);
        const ray_scene rays(source.geometry);
        const std::string label = frame.comment.empty() ? poses + ":" + std::to_string(frame.line) : frame.comment;
        std::cerr << label << "\n";
        rsm_pipeline_settings settings;
        settings.width = settings.height = size;
        settings.rsm_size = rsm_size;
        const int total = flicker + after_jump;
        const auto light_of = [&](int k) { return tilted(source.light, k < flicker ? step * static_cast<float>(k) : step * static_cast<float>(flicker - 1) + jump); };
        // The brute force of every distinct pose (the frames after the jump share one).
        std::vector<image> reference_filtered, reference_raw;
        {
          rsm_pipeline pipeline(shaders, source, settings);
          for (int k = 0; k < total; ++k) {
            if (k > flicker) {
              reference_filtered.push_back(reference_filtered.back());
              reference_raw.push_back(reference_raw.back());
              continue;
            }
            pipeline.set_light(light_of(k));
            pipeline.render();
            reference_filtered.push_back(filtered_brute_force(pipeline, rays, threads));
            rsm_brute_force_options exact;
            exact.exact_visibility = true;
            exact.threads = threads;
            reference_raw.push_back(reference_rsm_gather(rays, pipeline.read_buffers(), pipeline.constants(), exact));
          }
        }
        for (const float blend : blends) {
          rsm_pipeline_settings s = settings;
          s.temporal.blend = blend;
          rsm_pipeline pipeline(shaders, source, s);
          pipeline.render();  // the shader compilers' lazy work
          std::vector<image> filtered, raw;
          for (int k = 0; k < total; ++k) {
            pipeline.set_light(light_of(k));
            const rsm_frame rendered = pipeline.render_next();
            filtered.push_back(rendered.indirect);
            raw.push_back(pipeline.read_buffers().indirect);
          }
          double change = 0.0, reference_change = 0.0, raw_change = 0.0, raw_reference_change = 0.0;
          for (int k = 1; k < flicker; ++k) {
            change += mean_change(filtered[static_cast<std::size_t>(k)], filtered[static_cast<std::size_t>(k - 1)]);
            reference_change += mean_change(reference_filtered[static_cast<std::size_t>(k)], reference_filtered[static_cast<std::size_t>(k - 1)]);
            image a = raw[static_cast<std::size_t>(k)], b = raw[static_cast<std::size_t>(k - 1)];
            for (image* i : {&a, &b})
              for (glm::vec4& v : i->texels) v.w = 0.0f;
            raw_change += mean_change(a, b);
            raw_reference_change += mean_change(reference_raw[static_cast<std::size_t>(k)], reference_raw[static_cast<std::size_t>(k - 1)]);
          }
          const double ratio = reference_change > 0.0 ? change / reference_change : 0.0;
          ratios[blend].add(ratio);
          const auto error_at = [&](int k) {
            return relative_error_of(filtered[static_cast<std::size_t>(k)], reference_filtered[static_cast<std::size_t>(k)]).rmse;
          };
          std::string after;
          for (int k = flicker; k < total; ++k) after += (after.empty() ? "" : ", ") + percent(error_at(k));
          md << "| " << label << " | " << blend << " | " << fixed(ratio, 2) << " | " << fixed(raw_reference_change > 0.0 ? raw_change / raw_reference_change : 0.0, 2)
             << " | " << percent(error_at(flicker - 1)) << " % | " << after << " |\n";
          std::cerr << "  blend " << blend << ": flicker " << fixed(ratio, 2) << ", error " << percent(error_at(flicker - 1)) << " %, after the jump " << after << "\n";
        }
      }
      md << "\n| temporal blend | flicker ratio min / median / max |\n|---:|---:|\n";
      for (const auto& [blend, values] : ratios) md << "| " << blend << " | " << values.describe(2) << " |\n";
      write_all_or_nothing({{fs::path(out) / "flicker.md", [text = md.str()] { return std::vector<std::uint8_t>(text.begin(), text.end()); }}});
      std::cout << md.str() << "\nwrote " << fs::absolute(fs::path(out) / "flicker.md").string() << "\n";
      return 0;
    }
    const std::vector<technique_row> techniques = {
        {"radial", "rsm-radial"}, {"alg6", "rsm-alg6"}, {"original", "rsm-original"}, {"original (printed weights)", "rsm-original", true}};

    std::ostringstream table, csv;
    table << "| frame | receivers (uncovered light) | leak region | Alg. 6 / radial rel. RMSE | leak bias Alg. 6 / radial | filtered indirect / Monte Carlo "
             "| rsm-original bias | printed weights bias |\n|---|---:|---:|---:|---:|---:|---:|---:|\n";
    csv << "frame,receivers,uncovered_share,leak_share,radial_rmse,alg6_rmse,rmse_ratio,radial_leak_bias,alg6_leak_bias,leak_ratio,"
           "alg6_image_ratio,radial_image_ratio,original_bias,original_printed_bias,alg6_bias,alg6_covered_rmse,radial_covered_rmse\n";
    spread rmse_ratio, leak_ratio, image_ratio, original_bias;
    int rmse_met = 0, leak_met = 0, leak_counted = 0, image_met = 0, original_met = 0;
    for (const pose_frame& frame : frames) {
      cli::common_options options;
      options.scene = frame.scene;
      options.camera_pose = frame.camera;
      options.light_pose = frame.light;
      const scene source = cli::load_scene(options, frame.scene);
      const std::string label = frame.comment.empty() ? poses + ":" + std::to_string(frame.line) : frame.comment;
      std::cerr << label << "\n";
      rsm_pipeline_settings settings;
      settings.width = settings.height = size;
      settings.rsm_size = rsm_size;
      // The cache key: the scene's bytes (a file) or name, the poses and the frame.
      std::string identity = frame.scene + "|" + (frame.camera ? format_pose(*frame.camera) : "") + "|" + (frame.light ? format_pose(*frame.light) : "") +
                             "|" + std::to_string(size) + "|" + std::to_string(rsm_size) + "|" + std::to_string(stride);
      if (fs::is_regular_file(frame.scene)) identity += read_file(frame.scene, std::uintmax_t{1} << 30, "scene");
      const std::string key = cache.empty() ? std::string() : (fs::path(cache) / cache_key(identity)).string();
      const frame_reference reference = make_frame_reference(shaders, source, settings, stride, threads, key);
      image monte_carlo;
      const std::string mc_file = key + "-mc" + std::to_string(mc_samples) + ".pfm";
      if (!key.empty() && fs::exists(mc_file)) {
        monte_carlo = read_image_file(mc_file);
      } else {
        monte_carlo = reference_one_bounce(source, size, size, mc_samples, 1u, threads).indirect;
        if (!key.empty()) write_all_or_nothing({{mc_file, [&] { return encode_pfm(monte_carlo); }}});
      }
      const double mc_mean = image_mean(monte_carlo);
      std::map<std::string, technique_errors> errors;
      for (const technique_row& t : techniques) {
        rsm_pipeline_settings s = settings;
        s.technique = t.technique;
        s.disk.printed_weights = t.printed_disk_weights;
        errors[t.label] = measure_technique(shaders, source, s, reference, seeds);
      }
      const technique_errors &radial = errors["radial"], &alg6 = errors["alg6"];
      const double leak_share = reference.receiver_count ? static_cast<double>(reference.leak_count) / static_cast<double>(reference.receiver_count) : 0.0;
      const double ratio = alg6.raw_vs_exact.rmse / radial.raw_vs_exact.rmse;
      const bool leak_counts = leak_share >= 0.02;
      const double leak = radial.raw_leak.bias != 0.0 ? std::fabs(alg6.raw_leak.bias) / std::fabs(radial.raw_leak.bias) : 0.0;
      const double alg6_image = mc_mean > 0.0 ? image_mean(alg6.filtered_image) / mc_mean : 0.0;
      const double radial_image = mc_mean > 0.0 ? image_mean(radial.filtered_image) / mc_mean : 0.0;
      const double original = errors["original"].raw_vs_unoccluded.bias, printed = errors["original (printed weights)"].raw_vs_unoccluded.bias;
      rmse_ratio.add(ratio);
      image_ratio.add(alg6_image);
      original_bias.add(original);
      rmse_met += ratio < 1.0;
      image_met += std::fabs(alg6_image - 1.0) <= 0.15;
      original_met += std::fabs(original) <= 0.10;
      if (leak_counts) {
        leak_ratio.add(leak);
        ++leak_counted;
        leak_met += leak <= 0.5;
      }
      table << "| " << label << " | " << reference.receiver_count << " (" << percent(reference.uncovered_share) << " %) | " << percent(leak_share) << " % | "
            << fixed(ratio, 2) << " (" << percent(alg6.raw_vs_exact.rmse) << " / " << percent(radial.raw_vs_exact.rmse) << " %) | "
            << (leak_counts ? fixed(leak, 2) : std::string("-")) << " (" << percent(alg6.raw_leak.bias) << " / " << percent(radial.raw_leak.bias) << " %) | "
            << fixed(alg6_image, 2) << " | " << percent(original) << " % | " << percent(printed) << " % |\n";
      csv << "\"" << label << "\"," << reference.receiver_count << "," << reference.uncovered_share << "," << leak_share << "," << radial.raw_vs_exact.rmse << ","
          << alg6.raw_vs_exact.rmse << "," << ratio << "," << radial.raw_leak.bias << "," << alg6.raw_leak.bias << "," << leak << "," << alg6_image << ","
          << radial_image << "," << original << "," << printed << "," << alg6.raw_vs_exact.bias << "," << alg6.raw_covered_vs_exact.rmse << ","
          << radial.raw_covered_vs_exact.rmse << "\n";
      std::cerr << "  ratio " << fixed(ratio, 2) << " leak " << fixed(leak, 2) << (leak_counts ? "" : " (region < 2 %)") << " image " << fixed(alg6_image, 2)
                << " original " << percent(original) << " %\n";
    }
    const std::size_t n = frames.size();
    std::ostringstream md;
    md << "# RSM techniques on " << poses << "\n\n" << n << " frames, " << size << "^2 image, RSM " << rsm_size << "^2, brute force at every " << stride
       << "th receiver per axis (every receiver with a surface), seeds 1-" << seeds << ", Monte Carlo " << mc_samples << " bounce rays per pixel, on:\n\n```\n"
       << describe_current_context() << "\n```\n\n## Targets (min / median / max over the frames)\n\n"
       << "| target | frames met | min / median / max |\n|---|---:|---:|\n"
       << "| Alg. 6 rel. RMSE / radial's < 1 | " << rmse_met << " / " << n << " | " << rmse_ratio.describe(2) << " |\n"
       << "| |leak bias| Alg. 6 / radial <= 0.5 (leak region >= 2 %) | " << leak_met << " / " << leak_counted << " | " << leak_ratio.describe(2) << " |\n"
       << "| filtered indirect / Monte Carlo in [0.85, 1.15] | " << image_met << " / " << n << " | " << image_ratio.describe(2) << " |\n"
       << "| rsm-original |bias| <= 10 % | " << original_met << " / " << n << " | " << original_bias.describe(1, true) << " % |\n"
       << "\n## Frame by frame\n\n" << table.str();
    write_all_or_nothing({{fs::path(out) / "poses.md", [text = md.str()] { return std::vector<std::uint8_t>(text.begin(), text.end()); }},
                          {fs::path(out) / "poses.csv", [text = csv.str()] { return std::vector<std::uint8_t>(text.begin(), text.end()); }}});
    std::cout << md.str() << "\nwrote " << fs::absolute(fs::path(out) / "poses.md").string() << "\n";
  } catch (const std::exception& failure) {
    std::cerr << "vplkit_rsm_poses: error: " << failure.what() << "\n";
    return 1;
  }
  return 0;
}
