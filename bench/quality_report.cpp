// The quality report: every technique of the three papers rendered at equal settings and
// compared with ground truth, with the cost measured in the same run.
//   build/bench/vplkit_quality_report [--size 96] [--samples 256] [--rsm-frame 512] [--stride 4]
//                                     [--seeds 4] [--rsm-scenes ...] [--out output/report]
// Writes report.md, image strips (render | reference | error) and an error-against-time plot
// (gnuplot, when installed). Generated, not committed.
// Ground truth, like with like:
// - RSM techniques ([RSMV]): their indirect irradiance against the brute-force gather of every
//   RSM texel with exact visibility on the same RSM and G-buffer (bench/rsm_measure.hpp), raw and
//   filtered, over the covered receivers, mean of --seeds pattern seeds; the leak region is where
//   exact visibility removes >= 20 % of the light. A second table compares final images with the
//   one-bounce Monte Carlo reference.
// - Light Wave ([LW]): final images against the one-bounce Monte Carlo reference.
// - Final gathering ([FG]): the exact per-patch irradiance of the room without self-shadowing.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

#include "bench/rsm_measure.hpp"
#include "frontend/gl/context.hpp"
#include "frontend/core/error.hpp"
#include "frontend/techniques/final_gather/final_gather_pipeline.hpp"
#include "frontend/image/image_files.hpp"
#include "frontend/image/metrics.hpp"
#include "frontend/techniques/lightwave/lightwave_pipeline.hpp"
#include "frontend/reference/final_gather_reference.hpp"
#include "frontend/reference/reference.hpp"
#include "frontend/image/image.hpp"
#include "frontend/techniques/rsm/rsm_cpu_mirror.hpp"
#include "frontend/techniques/rsm/rsm_pipeline.hpp"

namespace fs = std::filesystem;
using namespace vplkit;

namespace {

struct row {
  std::string scene, technique;
  double ms = 0.0;
  image_metrics metrics;
  double rsm_error = 0.0;  ///< RSM rows: filtered rel. RMSE against the exact brute force
};



// "| ms | RMSE | rel. MSE | PSNR | SSIM | % similar" cells of a table row.
std::string metric_cells(double ms, const image_metrics& m) {
  return " | " + fixed(ms, 1) + " | " + fixed(m.rmse, 4) + " | " + fixed(m.relative_mse, 4) + " | " + fixed(m.psnr, 2) + " | " + fixed(m.ssim, 4) +
         " | " + fixed(m.similarity, 2);
}

template <typename Render>
double median_ms(int repeat, Render&& render) {
  std::vector<double> times;
  for (int i = 0; i < repeat; ++i) {
    const auto start = std::chrono::steady_clock::now();
    render();
    times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

// render | reference | error, side by side, as one sRGB PNG: the images scaled by `exposure`,
// each pixel drawn as a `magnify` x `magnify` block.
void write_strip(const fs::path& path, const image& render, const image& reference, float exposure = 1.0f, int magnify = 1) {
  const int w = render.width, h = render.height, big_w = 3 * w * magnify, big_h = h * magnify;
  const std::vector<std::uint8_t> panels[3] = {to_srgb8(render, exposure), to_srgb8(reference, exposure), false_colour_error(render, reference, 0.0f)};
  std::vector<std::uint8_t> strip(static_cast<std::size_t>(big_w) * static_cast<std::size_t>(big_h) * 4);
  for (int y = 0; y < big_h; ++y)
    for (int x = 0; x < big_w; ++x) {
      const int panel = x / (w * magnify), sx = (x % (w * magnify)) / magnify, sy = y / magnify;
      const std::size_t i = (static_cast<std::size_t>(sy) * static_cast<std::size_t>(w) + static_cast<std::size_t>(sx)) * 4;
      const std::size_t o = (static_cast<std::size_t>(y) * static_cast<std::size_t>(big_w) + static_cast<std::size_t>(x)) * 4;
      std::copy_n(panels[panel].begin() + static_cast<std::ptrdiff_t>(i), 4, strip.begin() + static_cast<std::ptrdiff_t>(o));
    }
  write_png(path, big_w, big_h, strip);
}

// The receivers a frame_reference counts (every stride-th texel of the indirect buffer that the
// gather covers; 0 elsewhere) as a small image, for the strips.
image counted_receivers(const image& full, const frame_reference& reference) {
  const int stride = reference.stride;
  image out((full.width + stride - 1) / stride, (full.height + stride - 1) / stride);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      const glm::ivec2 texel(x * stride, y * stride);
      if (reference.receivers.at(texel).x > 0.5f) out.at(x, y) = full.at(texel);
    }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"vplkit quality report: every technique against ground truth"};
  int size = 96, samples = 256, repeat = 3, rsm_frame_size = 512, stride = 4, seeds = 4;
  std::string rsm_scenes_text = "cornell-box,indirect-shadow,occluder,occluder-white,atrium";
  std::string out = "output/report";
  app.add_option("--size", size, "image side")->check(CLI::Range(16, 1024))->capture_default_str();
  app.add_option("--samples", samples, "bounce rays per pixel of the Monte Carlo reference")->check(CLI::Range(1, 65536))->capture_default_str();
  app.add_option("--repeat", repeat, "timed frames per technique (median)")->check(CLI::Range(1, 50))->capture_default_str();
  app.add_option("--out", out, "report folder")->capture_default_str();
  app.add_option("--rsm-frame", rsm_frame_size, "RSM section: image and RSM side of the frame compared with the brute force")
      ->check(CLI::Range(16, 2048))->capture_default_str();
  app.add_option("--stride", stride, "RSM section: every stride-th receiver of the indirect buffer per axis")->check(CLI::Range(1, 64))->capture_default_str();
  app.add_option("--seeds", seeds, "RSM section: pattern seeds per technique (metrics are their mean)")->check(CLI::Range(1, 64))->capture_default_str();
  app.add_option("--rsm-scenes", rsm_scenes_text, "RSM section: comma-separated built-in scenes")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    std::vector<std::string> rsm_scenes;
    {
      std::stringstream in(rsm_scenes_text);
      for (std::string item; std::getline(in, item, ',');) rsm_scenes.push_back(item);
    }
    fs::create_directories(out);
    auto context = create_headless_context();
    const shader_library shaders(default_shader_dir());
    std::vector<row> rows;
    std::ostringstream md;
    md << "# vplkit quality report\n\n" << size << "x" << size << " images, one-bounce Monte Carlo reference with " << samples
       << " bounce rays per pixel (Embree), times: median wall clock of " << repeat << " frames, on:\n\n```\n" << describe_current_context()
       << "\n```\n\nEach section compares a technique with the ground truth of the same thing: the RSM gather's indirect light with the brute-force "
          "gather, final images with the one-bounce Monte Carlo image (metrics on linear radiance: RMSE, relative MSE, PSNR, SSIM on luminance, "
          "Alg. 1 similarity), final gathering with the exact per-patch irradiance.\n";

    // ---- RSM techniques ([RSMV]): the indirect light against the brute force of the same frame ----
    md << "\n## RSM gather against the brute force ([RSMV], Fig. 5.1d)\n\n"
       << "The indirect irradiance of each technique against the brute-force gather of every lit RSM texel with exact (ray-cast) visibility, on "
          "the same RSM and G-buffer: a " << rsm_frame_size << "^2 frame (indirect " << (rsm_frame_size + 1) / 2 << "^2), RSM " << rsm_frame_size
       << "^2, at every " << stride << "th receiver of the indirect buffer per axis that the gather covers (in front of the light, inside its "
          "frustum), mean of " << seeds << " pattern seeds. Relative RMSE and bias are divided by the reference's mean over the pixels counted. "
          "Leak region: receivers where exact visibility removes >= 20 % of the unoccluded brute force. Raw: the gather's output; filtered: after "
          "the bilateral post filter, at the same receivers. ms: wall clock around glFinish of one whole frame at " << rsm_frame_size
       << "^2, median of " << repeat << ", interleaved. All techniques use the default settings (radius " << default_rsm_gather_preset<float>().radius_fraction
       << " of the RSM, " << default_rsm_gather_preset<float>().paths << "x" << default_rsm_gather_preset<float>().samples_per_path << " samples, "
       << default_rsm_gather_preset<float>().slots << " slots; the disk pattern with the same radius).\n";
    std::ostringstream targets;
    targets << "\n## RSM targets at the defaults\n\n| scene | radial bias vs unoccluded (target |b| <= 10 %) | rel. RMSE vs exact: Alg. 6 / radial (target < 1) "
               "| leak bias: Alg. 6 / radial (target <= 0.5) | ms: Alg. 6 / radial / original 400 |\n|---|---:|---:|---:|---:|\n";
    for (const std::string& scene_name : rsm_scenes) {
      const scene source = built_in_scene(scene_name);
      std::cerr << scene_name << ": brute-force references\n";
      rsm_pipeline_settings frame_settings;
      frame_settings.width = frame_settings.height = rsm_frame_size;
      frame_settings.rsm_size = rsm_frame_size;
      const frame_reference reference = make_frame_reference(shaders, source, frame_settings, stride, hardware_threads());
      md << "\n### " << scene_name << "\n\n" << describe(reference) << "\n\n"
         << "| technique | ms | raw rel. RMSE | raw rel. bias | raw leak rel. RMSE | raw leak bias | filtered rel. RMSE | filtered leak bias |\n"
            "|---|---:|---:|---:|---:|---:|---:|---:|\n";
      struct variant {
        std::string label, technique;
        int disk_samples;
      };
      const std::vector<variant> variants{{"direct", "direct", 400},       {"rsm-original (400)", "rsm-original", 400},
                                          {"rsm-original (150)", "rsm-original", 150}, {"rsm-radial", "rsm-radial", 400},
                                          {"rsm-alg2", "rsm-alg2", 400},   {"rsm-alg3", "rsm-alg3", 400},
                                          {"rsm-alg6", "rsm-alg6", 400}};
      std::vector<rsm_pipeline_settings> timed;
      for (const variant& v : variants) {
        rsm_pipeline_settings settings = frame_settings;
        settings.technique = v.technique;
        settings.disk.samples = v.disk_samples;
        timed.push_back(settings);
      }
      const std::vector<double> times = interleaved_frame_ms(shaders, source, timed, repeat);
      std::map<std::string, technique_errors> errors;
      std::map<std::string, double> ms;
      for (std::size_t i = 0; i < variants.size(); ++i) {
        const technique_errors e = measure_technique(shaders, source, timed[i], reference, seeds);
        errors[variants[i].label] = e;
        ms[variants[i].label] = times[i];
        md << "| " << variants[i].label << " | " << fixed(times[i], 0) << " | " << percent(e.raw_vs_exact.rmse) << " % | " << percent(e.raw_vs_exact.bias)
           << " % | " << percent(e.raw_leak.rmse) << " % | " << percent(e.raw_leak.bias) << " % | " << percent(e.filtered_vs_exact.rmse) << " % | "
           << percent(e.filtered_leak.bias) << " % |\n";
        rows.push_back({scene_name, variants[i].label, times[i], {}, e.filtered_vs_exact.rmse});
      }
      // Where the error of Alg. 6 comes from: the radius (the brute force cut to the radius against
      // all texels, no visibility), sampling noise (one seed against the mean of the seeds), and the
      // visibility approximation (Alg. 6 against the same samples ray-cast).
      rsm_pipeline_settings alg6_settings = frame_settings;
      alg6_settings.technique = "rsm-alg6";
      const float radius_texels = alg6_settings.radius * static_cast<float>(alg6_settings.rsm_size);
      const relative_error radius_error =
          relative_error_of(brute_force_within(reference, radius_texels, hardware_threads()), reference.unoccluded, &reference.receivers);
      const image ray_cast = ray_cast_gather(reference, alg6_settings, seeds, hardware_threads());
      const relative_error visibility_error = relative_error_of(errors["rsm-alg6"].mean_raw, ray_cast, &reference.receivers);
      const relative_error visibility_leak = relative_error_of(errors["rsm-alg6"].mean_raw, ray_cast, &reference.leak);
      const relative_error ray_cast_error = relative_error_of(ray_cast, reference.exact, &reference.receivers);
      md << "\nError split of rsm-alg6 (raw): radius " << fixed(radius_texels, 0) << " texels: the brute force within it has bias "
         << percent(radius_error.bias) << " % against all texels; sampling noise of one seed: " << percent(errors["rsm-alg6"].raw_noise)
         << " % rel. RMSE; the same samples ray-cast have bias " << percent(ray_cast_error.bias) << " % against the exact brute force (mean of "
         << seeds << " seeds); visibility: Alg. 6 against those ray-cast samples, bias " << percent(visibility_error.bias) << " % over all receivers, "
         << percent(visibility_leak.bias) << " % in the leak region (rel. RMSE of the seed means " << percent(visibility_error.rmse) << " %).\n";
      const technique_errors& radial = errors["rsm-radial"];
      const technique_errors& alg6 = errors["rsm-alg6"];
      targets << "| " << scene_name << " | " << percent(radial.raw_vs_unoccluded.bias) << " % | " << fixed(alg6.raw_vs_exact.rmse / radial.raw_vs_exact.rmse, 2)
              << " (" << percent(alg6.raw_vs_exact.rmse) << " / " << percent(radial.raw_vs_exact.rmse) << " %) | "
              << fixed(alg6.raw_leak.bias / radial.raw_leak.bias, 2) << " (" << percent(alg6.raw_leak.bias) << " / " << percent(radial.raw_leak.bias)
              << " %) | " << fixed(ms["rsm-alg6"], 0) << " / " << fixed(ms["rsm-radial"], 0) << " / " << fixed(ms["rsm-original (400)"], 0) << " |\n";
      // The strip: the filtered indirect of rsm-alg6 | the exact brute force | the error.
      const image strip_reference = counted_receivers(reference.exact, reference);
      write_strip(fs::path(out) / (scene_name + "-rsm-alg6-indirect.png"), counted_receivers(errors["rsm-alg6"].filtered_mean, reference), strip_reference,
                  percentile_exposure(strip_reference), 4);
      md << "\n![" << scene_name << ": rsm-alg6 filtered indirect (mean of seeds) | exact brute force | error, at the receivers counted](" << scene_name
         << "-rsm-alg6-indirect.png)\n";
    }
    md << targets.str();

    // ---- RSM techniques, final images against the one-bounce Monte Carlo reference ----
    md << "\n## RSM final images against the one-bounce Monte Carlo reference\n\nDirect plus indirect light, " << size << "x" << size
       << " images, against the path-traced one-bounce image (" << samples << " bounce rays per pixel, Embree). Receivers the RSM does not cover "
          "(behind the light) get no indirect light from any RSM technique.\n";
    for (const std::string scene_name : {"cornell-box", "indirect-shadow"}) {
      const scene source = built_in_scene(scene_name);
      std::cerr << scene_name << ": Monte Carlo reference\n";
      const one_bounce_images reference = reference_one_bounce(source, size, size, samples, 1u, hardware_threads());
      md << "\n### " << scene_name << "\n\n| technique | ms | RMSE | rel. MSE | PSNR | SSIM | % similar |\n|---|---:|---:|---:|---:|---:|---:|\n";
      for (const char* technique : {"direct", "rsm-original", "rsm-radial", "rsm-alg3", "rsm-alg6"}) {
        rsm_pipeline_settings settings;
        settings.width = settings.height = size;
        settings.technique = technique;
        rsm_pipeline pipeline(shaders, source, settings);
        rsm_frame frame = pipeline.render();
        const double ms = median_ms(repeat, [&] { frame = pipeline.render(); });
        const image image = frame.radiance;
        const image_metrics m = compare_images(image, reference.radiance);
        md << "| " << technique << metric_cells(ms, m) << " |\n";
      }
    }

    // ---- Light Wave ([LW]) ----
    for (const std::string scene_name : {"boxes", "teapot"}) {
      scene source;
      try {
        source = built_in_scene(scene_name);
      } catch (const error& failure) {
        md << "\n(" << scene_name << " skipped: " << failure.what() << ")\n";
        continue;
      }
      std::cerr << scene_name << ": reference\n";
      const one_bounce_images reference = reference_one_bounce(source, size, size, samples, 1u, hardware_threads());
      md << "\n## " << scene_name << " (Light Wave, [LW])\n\n| technique | ms | RMSE | rel. MSE | PSNR | SSIM | % similar | factor < 0.95 |\n"
            "|---|---:|---:|---:|---:|---:|---:|---:|\n";
      // Every technique, and the accurate shadows in the thesis's own variant; the last column is
      // the share of surface pixels whose indirect shadow factor is below 0.95.
      struct variant {
        std::string label;
        const lightwave_technique* technique;
        lightwave_shadow_variant shadows;
      };
      std::vector<variant> variants;
      for (const lightwave_technique& technique : lightwave_techniques()) variants.push_back({technique.name, &technique, lightwave_shadow_variant::importance});
      variants.push_back({"lightwave-accurate (thesis variant)", &find_lightwave_technique("lightwave-accurate"), lightwave_shadow_variant::thesis});
      std::map<std::string, double> rmse_of;
      for (const variant& v : variants) {
        lightwave_settings settings;
        settings.technique = v.technique->name;
        settings.shadow_variant = v.shadows;
        settings.width = settings.height = size;
        lightwave_pipeline pipeline(shaders, source, settings);
        lightwave_frame frame = pipeline.render();
        const double ms = median_ms(repeat, [&] { frame = pipeline.render(); });
        const image image = frame.radiance;
        row r{scene_name, v.label, ms, compare_images(image, reference.radiance)};
        std::size_t shadowed = 0, surface = 0;
        for (std::size_t i = 0; i < frame.indirect_shadow.texels.size(); ++i) {
          const glm::vec4& radiance = frame.radiance.texels[i];
          const bool covered = radiance.r + radiance.g + radiance.b > 0.0f;
          surface += covered;
          shadowed += covered && frame.indirect_shadow.texels[i].r < 0.95f;
        }
        md << "| " << v.label << metric_cells(ms, r.metrics) << " | " << percent(surface ? static_cast<double>(shadowed) / static_cast<double>(surface) : 0.0)
           << " % |\n";
        if (v.label == "lightwave-accurate") write_strip(fs::path(out) / (scene_name + "-lightwave-accurate.png"), image, reference.radiance);
        rmse_of[v.label] = r.metrics.rmse;
        rows.push_back(r);
      }
      md << "\nAgainst the physical one-bounce image, lightwave-accurate is " << (rmse_of["lightwave-accurate"] < rmse_of["lightwave-unshadowed"] ? "nearer" : "not nearer")
         << " than lightwave-unshadowed (RMSE " << fixed(rmse_of["lightwave-accurate"], 4) << " against " << fixed(rmse_of["lightwave-unshadowed"], 4)
         << "). With the default --vpl-energy flux each VPL carries the flux its patch of the spot's cone brings, so the level is the physical "
            "one and the accurate shadows have no seed; bench/lightwave_study (docs/lightwave-shadows.md) measures them over scenes and seeds.\n";
      md << "\n![" << scene_name << " lightwave-accurate | reference | error](" << scene_name << "-lightwave-accurate.png)\n";
    }

    // ---- Final gathering ([FG]) ----
    {
      md << "\n## Final gathering ([FG]): the object approaching a wall\n\nIndirect irradiance on the object's pixels against the exact per-patch "
            "reference (no self-shadowing, the paper's assumption), relative error max and mean; and how much the "
            "object itself changes its irradiance on average (Monte Carlo, Embree: it blocks part of its view of the room and reflects its own "
            "direct light into its concavities), the effect the paper's assumption leaves out.\n\n"
            "| object | gap to the wall | technique | ms | max error | mean error | with the object itself |\n|---|---:|---|---:|---:|---:|---:|\n";
      const std::string object = fs::exists("meshes/bunny.obj") ? "meshes/bunny.obj" : "sphere";
      const float radius = make_final_gather_scene(object, glm::vec3(0.0f, 0.8f, 0.0f), 0.6f).object_radius;
      for (float gap : {0.5f, 0.2f, 0.1f, 0.05f}) {
        const float x_position = 1.0f - radius - gap;
        const final_gather_scene source = make_final_gather_scene(object, glm::vec3(x_position, 0.8f, 0.0f), 0.6f);
        mesh room_and_object = source.room;
        for (std::uint32_t index : source.object.indices) room_and_object.indices.push_back(index + static_cast<std::uint32_t>(source.room.vertices.size()));
        room_and_object.vertices.insert(room_and_object.vertices.end(), source.object.vertices.begin(), source.object.vertices.end());
        const ray_scene room_rays(source.room), shadowing_rays(room_and_object);
        scene_light room_light;
        room_light.spot = source.light;
        double self_shadowing = 0.0;
        bool have_self_shadowing = false;
        for (const final_gather_technique& technique : final_gather_techniques()) {
          final_gather_settings settings;
          settings.technique = technique.name;
          settings.width = settings.height = size;
          final_gather_pipeline pipeline(shaders, source, settings);
          final_gather_frame frame = pipeline.render();
          const double ms = median_ms(repeat, [&] { frame = pipeline.render(); });
          const final_gather_buffers buffers = pipeline.read_buffers();
          double worst = 0.0, sum = 0.0, shadowed_sum = 0.0, unshadowed_sum = 0.0;
          std::size_t pixels = 0;
          for (std::size_t i = 0; i < buffers.gbuffer[0].texels.size(); i += 3) {  // every third object pixel keeps the report quick
            const glm::vec4 position_kind = buffers.gbuffer[0].texels[i];
            if (position_kind.w < 1.5f) continue;
            const double exact = final_gather_reference(source, glm::dvec3(position_kind), glm::dvec3(buffers.gbuffer[1].texels[i]), 12);
            if (exact < 1e-3) continue;
            const glm::vec4& indirect = frame.indirect.texels[i];
            const double gathered = static_cast<double>(indirect.r) + indirect.g + indirect.b;
            const double error = std::fabs(gathered / exact - 1.0);
            worst = std::max(worst, error);
            sum += error;
            ++pixels;
            if (!have_self_shadowing && pixels % 4 == 1) {  // once per position, on a quarter of the sampled pixels
              const glm::vec3 p(position_kind), n(buffers.gbuffer[1].texels[i]);
              const glm::vec3 with = one_bounce_irradiance(shadowing_rays, room_rays, room_light, {}, p + n * 1e-3f, n, 256, 5u, static_cast<std::uint32_t>(i));
              const glm::vec3 without = one_bounce_irradiance(room_rays, room_rays, room_light, {}, p + n * 1e-3f, n, 256, 5u, static_cast<std::uint32_t>(i));
              shadowed_sum += with.x + with.y + with.z;
              unshadowed_sum += without.x + without.y + without.z;
            }
          }
          if (!have_self_shadowing) {
            self_shadowing = unshadowed_sum > 0.0 ? shadowed_sum / unshadowed_sum - 1.0 : 0.0;
            have_self_shadowing = true;
          }
          md << "| " << source.name << " | " << fixed(1.0 - x_position - source.object_radius, 2) << " | " << technique.name << " | " << fixed(ms, 1)
             << " | " << fixed(worst, 3) << " | " << fixed(pixels ? sum / static_cast<double>(pixels) : 0.0, 3) << " | "
             << (self_shadowing >= 0.0 ? "+" : "") << fixed(100.0 * self_shadowing, 1) << "% |\n";
          rows.push_back({source.name + " gap " + fixed(1.0 - x_position - source.object_radius, 2), technique.name, ms, {}});
        }
      }
    }

    // ---- Error against time: the RSM techniques, filtered indirect light against the exact brute force ----
    std::ofstream data(fs::path(out) / "error_time.dat");
    for (const row& r : rows)
      if (r.rsm_error > 0.0) data << r.ms << " " << 100.0 * r.rsm_error << " \"" << r.scene << ": " << r.technique << "\"\n";
    data.close();
    std::ofstream plot(fs::path(out) / "error_time.gnuplot");
    plot << "set terminal pngcairo size 1000,650\nset output '" << (fs::path(out) / "error_time.png").string()
         << "'\nset logscale x\nset xlabel 'ms per frame, " << rsm_frame_size << "^2, wall clock'\nset ylabel 'filtered indirect, rel. RMSE vs exact brute force (%)'\n"
         << "set key off\nset grid\nplot '" << (fs::path(out) / "error_time.dat").string()
         << "' using 1:2 with points pt 7, '' using 1:2:3 with labels offset 0,1 font ',7'\n";
    plot.close();
    const bool plotted = std::system(("gnuplot " + (fs::path(out) / "error_time.gnuplot").string() + " 2>/dev/null").c_str()) == 0;
    md << "\n## Error against time (RSM techniques)\n\n"
       << (plotted ? "![filtered rel. RMSE against ms per frame](error_time.png)\n" : "(gnuplot is not installed: the data is in error_time.dat)\n");
    std::ofstream(fs::path(out) / "report.md") << md.str();
    std::cout << md.str() << "\nwrote " << fs::absolute(fs::path(out) / "report.md").string() << "\n";
  } catch (const std::exception& failure) {
    std::cerr << "vplkit_quality_report: error: " << failure.what() << "\n";
    return 1;
  }
  return 0;
}
