// The quality report: every technique of the three papers rendered at equal settings and
// compared with ground truth, with the cost measured in the same run.
//   build/bench/vplkit_quality_report [--size 96] [--samples 256] [--out output/report]
// Writes report.md, per-scene image strips (render | reference | error) and an error-against-time
// plot (gnuplot, when installed). Generated, not committed.
// Ground truth: the one-bounce Monte Carlo reference (Embree) for the RSM and Light Wave scenes;
// the light-leak mask is where the brute-force RSM gather with exact visibility keeps less than
// 99% of the light it gathers without (pixels whose indirect light is partly occluded); for final
// gathering, the exact per-patch irradiance of the room without self-shadowing.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "frontend/context.hpp"
#include "frontend/error.hpp"
#include "frontend/final_gather_pipeline.hpp"
#include "frontend/image_io.hpp"
#include "frontend/image_metrics.hpp"
#include "frontend/lightwave_pipeline.hpp"
#include "frontend/reference.hpp"
#include "frontend/rsm_cpu_mirror.hpp"
#include "frontend/rsm_pipeline.hpp"

namespace fs = std::filesystem;
using namespace vplkit;

namespace {

struct row {
  std::string scene, technique;
  double ms = 0.0;
  image_metrics metrics;
};

std::string fixed(double value, int digits) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(digits) << value;
  return out.str();
}

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

// render | reference | error, side by side, as one sRGB PNG.
void write_strip(const fs::path& path, const float_image& render, const float_image& reference) {
  const int w = render.width, h = render.height;
  std::vector<std::uint8_t> strip(static_cast<std::size_t>(3 * w) * static_cast<std::size_t>(h) * 4);
  const auto encode = [](float v) {
    v = std::clamp(v, 0.0f, 1.0f);
    return static_cast<std::uint8_t>(std::lround(255.0f * (v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f)));
  };
  const std::vector<std::uint8_t> error = false_colour_error(render, reference, 0.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 4; ++c) {
        const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
        const std::size_t row_start = static_cast<std::size_t>(y) * static_cast<std::size_t>(3 * w);
        strip[(row_start + static_cast<std::size_t>(x)) * 4 + static_cast<std::size_t>(c)] = c == 3 ? 255 : encode(render.pixels[i][c]);
        strip[(row_start + static_cast<std::size_t>(w + x)) * 4 + static_cast<std::size_t>(c)] = c == 3 ? 255 : encode(reference.pixels[i][c]);
        strip[(row_start + static_cast<std::size_t>(2 * w + x)) * 4 + static_cast<std::size_t>(c)] = error[i * 4 + static_cast<std::size_t>(c)];
      }
  write_png(path, 3 * w, h, strip);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"vplkit quality report: every technique against ground truth"};
  int size = 96, samples = 256, repeat = 3;
  std::string out = "output/report";
  app.add_option("--size", size, "image side")->check(CLI::Range(16, 1024))->capture_default_str();
  app.add_option("--samples", samples, "bounce rays per pixel of the Monte Carlo reference")->check(CLI::Range(1, 65536))->capture_default_str();
  app.add_option("--repeat", repeat, "timed frames per technique (median)")->check(CLI::Range(1, 50))->capture_default_str();
  app.add_option("--out", out, "report folder")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    fs::create_directories(out);
    auto context = create_headless_context();
    const shader_library shaders(default_shader_dir());
    std::vector<row> rows;
    std::ostringstream md;
    md << "# vplkit quality report\n\n" << size << "x" << size << " images, one-bounce Monte Carlo reference with " << samples
       << " bounce rays per pixel (Embree), times: median wall clock of " << repeat << " frames with read-back, on:\n\n```\n" << describe_current_context()
       << "\n```\n\nMetrics on linear radiance: RMSE, relative MSE, PSNR, SSIM (luminance), Alg. 1 similarity; light-leak RMSE over the pixels whose "
          "reference indirect light is partly occluded.\n";

    // ---- RSM techniques (paper 000) ----
    for (const std::string scene_name : {"cornell-box", "indirect-shadow"}) {
      const scene source = built_in_scene(scene_name);
      std::cerr << scene_name << ": reference\n";
      const one_bounce_images reference = reference_one_bounce(source, size, size, samples, 1u, hardware_threads());
      // The leak mask: brute-force gather with and without exact visibility at every pixel.
      rsm_pipeline_settings mask_settings;
      mask_settings.width = mask_settings.height = size;
      mask_settings.rsm_size = 64;
      mask_settings.indirect_divisor = 1;
      mask_settings.format = texel_format::rgba32f;
      mask_settings.technique = "rsm-radial";
      rsm_pipeline mask_pipeline(shaders, source, mask_settings);
      mask_pipeline.render();
      const ray_scene rays(source.geometry);
      const image_buffer visible = reference_rsm_gather(rays, mask_pipeline.read_buffers(), mask_pipeline.constants(), true, hardware_threads());
      float_image mask{size, size, std::vector<glm::vec3>(static_cast<std::size_t>(size) * static_cast<std::size_t>(size))};
      std::size_t masked = 0;
      for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
          const bool leak = visible.at(glm::ivec2(x, size - 1 - y)).w < 0.99f;
          mask.pixels[static_cast<std::size_t>(y * size + x)] = glm::vec3(leak ? 1.0f : 0.0f);
          masked += leak;
        }
      md << "\n## " << scene_name << " (RSM, paper 000)\n\n" << masked << " pixels with partly occluded indirect light.\n\n"
         << "| technique | ms | RMSE | rel. MSE | PSNR | SSIM | % similar | leak RMSE |\n|---|---:|---:|---:|---:|---:|---:|---:|\n";
      struct variant {
        std::string label, technique;
        int disk_samples;
      };
      for (const variant& v : std::vector<variant>{{"direct", "direct", 400},
                                                   {"rsm-original (400)", "rsm-original", 400},
                                                   {"rsm-original (150)", "rsm-original", 150},
                                                   {"rsm-radial (150)", "rsm-radial", 400},
                                                   {"rsm-alg3 (150)", "rsm-alg3", 400},
                                                   {"rsm-alg6 (150)", "rsm-alg6", 400}}) {
        rsm_pipeline_settings settings;
        settings.width = settings.height = size;
        settings.rsm_size = 256;
        settings.radial.max_radius = settings.disk.max_radius = 32.0f;
        settings.technique = v.technique;
        settings.disk.samples = v.disk_samples;
        rsm_pipeline pipeline(shaders, source, settings);
        rsm_frame frame = pipeline.render();
        const double ms = median_ms(repeat, [&] { frame = pipeline.render(); });
        const float_image image = float_image_from_rgba(frame.radiance, size, size);
        row r{scene_name, v.label, ms, compare_images(image, reference.radiance, &mask)};
        md << "| " << v.label << metric_cells(ms, r.metrics) << " | " << fixed(*r.metrics.leak_rmse, 4) << " |\n";
        if (v.technique == "rsm-alg6" || v.technique == "rsm-original")
          write_strip(fs::path(out) / (scene_name + "-" + v.technique + (v.disk_samples == 150 ? "-150" : "") + ".png"), image, reference.radiance);
        rows.push_back(r);
      }
      md << "\n![" << scene_name << " rsm-alg6 | reference | error](" << scene_name << "-rsm-alg6.png)\n";
    }

    // ---- Light Wave (paper 003) ----
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
      md << "\n## " << scene_name << " (Light Wave, paper 003)\n\n| technique | ms | RMSE | rel. MSE | PSNR | SSIM | % similar |\n|---|---:|---:|---:|---:|---:|---:|\n";
      for (const lightwave_technique& technique : lightwave_techniques()) {
        lightwave_settings settings;
        settings.technique = technique.name;
        settings.width = settings.height = size;
        lightwave_pipeline pipeline(shaders, source, settings);
        lightwave_frame frame = pipeline.render();
        const double ms = median_ms(repeat, [&] { frame = pipeline.render(); });
        const float_image image = float_image_from_rgba(frame.radiance, size, size);
        row r{scene_name, technique.name, ms, compare_images(image, reference.radiance)};
        md << "| " << technique.name << metric_cells(ms, r.metrics) << " |\n";
        if (technique.mode == lightwave_mode::accurate) write_strip(fs::path(out) / (scene_name + "-lightwave-accurate.png"), image, reference.radiance);
        rows.push_back(r);
      }
      md << "\n![" << scene_name << " lightwave-accurate | reference | error](" << scene_name << "-lightwave-accurate.png)\n";
    }

    // ---- Final gathering (paper 004) ----
    {
      md << "\n## Final gathering (paper 004): the object approaching a wall\n\nIndirect irradiance on the object's pixels against the exact per-patch "
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
            const double gathered = static_cast<double>(frame.indirect[4 * i]) + frame.indirect[4 * i + 1] + frame.indirect[4 * i + 2];
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

    // ---- Error against time ----
    std::ofstream data(fs::path(out) / "error_time.dat");
    for (const row& r : rows)
      if (r.metrics.rmse > 0.0) data << r.ms << " " << r.metrics.rmse << " \"" << r.scene << ": " << r.technique << "\"\n";
    data.close();
    std::ofstream plot(fs::path(out) / "error_time.gnuplot");
    plot << "set terminal pngcairo size 900,600\nset output '" << (fs::path(out) / "error_time.png").string()
         << "'\nset logscale x\nset xlabel 'ms per frame (llvmpipe)'\nset ylabel 'RMSE against the reference'\nset key off\n"
         << "plot '" << (fs::path(out) / "error_time.dat").string() << "' using 1:2 with points pt 7, '' using 1:2:3 with labels offset 0,1 font ',7'\n";
    plot.close();
    const bool plotted = std::system(("gnuplot " + (fs::path(out) / "error_time.gnuplot").string() + " 2>/dev/null").c_str()) == 0;
    md << "\n## Error against time\n\n" << (plotted ? "![RMSE against ms per frame](error_time.png)\n" : "(gnuplot is not installed: the data is in error_time.dat)\n");
    std::ofstream(fs::path(out) / "report.md") << md.str();
    std::cout << md.str() << "\nwrote " << fs::absolute(fs::path(out) / "report.md").string() << "\n";
  } catch (const std::exception& failure) {
    std::cerr << "vplkit_quality_report: error: " << failure.what() << "\n";
    return 1;
  }
  return 0;
}
