// The study behind the RSM gather's defaults ([RSMV]): radius x paths x samples x slots,
// measured against the brute-force gather of the same frame (the thesis's Fig. 5.1d), with
// and without exact visibility, and timed in the same run.
//   build/bench/vplkit_rsm_study [--scenes cornell-box,indirect-shadow,occluder,occluder-white,atrium]
//       [--size 512] [--rsm-size 512] [--stride 4] [--seeds 4] [--quick] [--out output/study]
// What is compared: the indirect irradiance of the gather (raw, and after the bilateral filter)
// against the brute force on the same RSM and G-buffer, over every receiver with a surface
// (covered by the pattern or not) on a grid of every `stride`-th texel of the indirect buffer per axis; each number is
// the mean over `seeds` pattern seeds. The leak region: receivers where exact visibility removes
// >= 20 % of the unoccluded brute force. Time: wall clock around glFinish of one whole frame
// (median of --repeat, configurations interleaved), at --size on --timing-scene.
// Writes study.md, study.csv and a Pareto plot (gnuplot, when installed) into --out.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "bench/rsm_measure.hpp"
#include "frontend/gl/context.hpp"
#include "frontend/core/error.hpp"
#include "frontend/core/parallel.hpp"

namespace fs = std::filesystem;
using namespace vplkit;

namespace {

struct configuration {
  float radius;
  int paths, samples, slots;
  std::string label() const {
    std::ostringstream out;
    out << radius << " " << paths << "x" << samples << " B" << slots;
    return out.str();
  }
};

std::vector<float> parse_floats(const std::string& text) {
  std::vector<float> values;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) values.push_back(std::stof(item));
  return values;
}

std::vector<std::pair<int, int>> parse_sample_counts(const std::string& text) {
  std::vector<std::pair<int, int>> values;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    const std::size_t x = item.find('x');
    if (x == std::string::npos) throw error("--samples: expected PxS items, got '" + item + "'");
    values.emplace_back(std::stoi(item.substr(0, x)), std::stoi(item.substr(x + 1)));
  }
  return values;
}

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> values;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) values.push_back(item);
  return values;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"RSM gather study ([RSMV]): radius x paths x samples x slots against the brute force, with cost"};
  std::string scenes_text = "cornell-box,indirect-shadow,occluder,occluder-white,atrium", out = "output/study", timing_scene = "atrium";
  std::string radii_text = "0.0625,0.125,0.25,0.5,0.75,1", samples_text = "15x10,20x15,30x20", slots_text = "4,5,8,12,16";
  int size = 512, rsm_size = 512, stride = 4, seeds = 4, repeat = 3;
  float min_radius = radial_pattern_settings<float>{}.min_radius;
  bool quick = false;
  app.add_option("--scenes", scenes_text, "comma-separated built-in scenes")->capture_default_str();
  app.add_option("--size", size, "image side (indirect buffer: half)")->check(CLI::Range(16, 2048))->capture_default_str();
  app.add_option("--rsm-size", rsm_size, "RSM side")->check(CLI::Range(16, 4096))->capture_default_str();
  app.add_option("--stride", stride, "reference receivers: every stride-th texel of the indirect buffer per axis")->check(CLI::Range(1, 64))->capture_default_str();
  app.add_option("--seeds", seeds, "pattern seeds per configuration (metrics are their mean)")->check(CLI::Range(1, 64))->capture_default_str();
  app.add_option("--radii", radii_text, "radii as fractions of the RSM side")->capture_default_str();
  app.add_option("--samples", samples_text, "paths x samples per path")->capture_default_str();
  app.add_option("--slots", slots_text, "micro linear buffer slots")->capture_default_str();
  app.add_option("--timing-scene", timing_scene, "scene of the timings")->capture_default_str();
  app.add_option("--repeat", repeat, "timed frames per configuration (median)")->check(CLI::Range(1, 50))->capture_default_str();
  app.add_option("--min-radius", min_radius, "r_min of the radial pattern, texels")->capture_default_str();
  app.add_flag("--quick", quick, "two radii, two sample counts, two slot counts");
  app.add_option("--out", out, "output folder")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    std::vector<float> radii = parse_floats(radii_text);
    std::vector<std::pair<int, int>> counts = parse_sample_counts(samples_text);
    std::vector<float> slot_values = parse_floats(slots_text);
    if (quick) {
      radii = {radii.front(), radii.back()};
      counts = {counts.front(), counts.back()};
      slot_values = {slot_values.front(), slot_values.back()};
    }
    std::vector<configuration> configurations;
    for (float radius : radii)
      for (const auto& [paths, samples] : counts)
        for (float slots : slot_values) configurations.push_back({radius, paths, samples, static_cast<int>(slots)});

    fs::create_directories(out);
    auto context = create_headless_context();
    const shader_library shaders(default_shader_dir());
    std::ofstream csv(fs::path(out) / "study.csv");
    csv << "scene,radius,paths,samples,slots,technique,raw_bias_vs_unoccluded,raw_rmse_vs_unoccluded,raw_rmse_vs_exact,raw_leak_bias,raw_leak_rmse,"
           "filtered_rmse_vs_exact,filtered_leak_bias,filtered_leak_rmse,ms\n";
    std::ostringstream md;
    md << "# RSM gather study\n\n" << size << "x" << size << " image, indirect " << (size + 1) / 2 << "^2, RSM " << rsm_size << "^2. Metrics: the "
       << "indirect irradiance against the brute force of the same frame, over every receiver on every " << stride
       << "th indirect texel per axis, mean of " << seeds << " seeds; relative to the reference mean. Time: wall clock around glFinish, one frame, "
       << "median of " << repeat << ", on " << timing_scene << ":\n\n```\n" << describe_current_context() << "\n```\n";

    // Timing first, on one scene: every configuration's Alg. 6 frame and the radial frame, interleaved.
    std::map<std::string, double> ms;
    {
      const scene source = built_in_scene(timing_scene);
      std::vector<rsm_pipeline_settings> timed;
      std::vector<std::string> keys;
      for (const configuration& c : configurations)
        for (const char* technique : {"rsm-radial", "rsm-alg6"}) {
          if (std::string(technique) == "rsm-radial" && c.slots != static_cast<int>(slot_values.front())) continue;
          rsm_pipeline_settings settings;
          settings.width = settings.height = size;
          settings.rsm_size = rsm_size;
          settings.apply({c.radius, c.paths, c.samples, c.slots});
          settings.technique = technique;
          timed.push_back(settings);
          keys.push_back(c.label() + " " + technique);
        }
      for (const char* technique : {"rsm-original", "direct"}) {
        rsm_pipeline_settings settings;
        settings.width = settings.height = size;
        settings.rsm_size = rsm_size;
        settings.apply(thesis_rsm_gather_preset<float>());
        settings.technique = technique;
        timed.push_back(settings);
        keys.push_back(technique);
      }
      std::cerr << "timing " << timed.size() << " configurations on " << timing_scene << "\n";
      const std::vector<double> times = interleaved_frame_ms(shaders, source, timed, repeat);
      for (std::size_t i = 0; i < keys.size(); ++i) ms[keys[i]] = times[i];
    }

    std::vector<std::string> pareto_rows;
    // Per configuration, over the scenes: the targets of the defaults and the mean error.
    struct summary {
      double worst_radial_bias = 0.0;     // max |radial bias vs unoccluded|
      double worst_rmse_ratio = 0.0;      // max Alg. 6 / radial rel. RMSE vs exact (raw)
      double worst_leak_ratio = -1e30;    // max Alg. 6 / radial leak bias (raw)
      double filtered_rmse_sum = 0.0;     // Alg. 6 filtered rel. RMSE vs exact, summed over scenes
      int scenes = 0;
    };
    std::map<std::string, summary> summaries;
    for (const std::string& scene_name : split(scenes_text)) {
      const scene source = built_in_scene(scene_name);
      std::cerr << scene_name << ": references\n";
      rsm_pipeline_settings frame_settings;
      frame_settings.width = frame_settings.height = size;
      frame_settings.rsm_size = rsm_size;
      const frame_reference reference = make_frame_reference(shaders, source, frame_settings, stride, hardware_threads());
      md << "\n## " << scene_name << "\n\n" << describe(reference) << "\n\n"
         << "| radius | P x S | slots | radial bias vs unoccluded | radial rel. RMSE vs exact | Alg. 6 rel. RMSE vs exact | radial leak bias | Alg. 6 leak bias "
            "| filtered: radial / Alg. 6 rel. RMSE | ms radial / Alg. 6 |\n|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
      std::map<std::string, technique_errors> radial_errors;  // by radius and P x S: the radial gather has no slots
      for (const configuration& c : configurations) {
        rsm_pipeline_settings settings = frame_settings;
        settings.apply({c.radius, c.paths, c.samples, c.slots});
        settings.radial.min_radius = min_radius;
        const configuration radial_configuration{c.radius, c.paths, c.samples, static_cast<int>(slot_values.front())};
        const std::string radial_key = radial_configuration.label() + " rsm-radial";
        if (!radial_errors.count(radial_key)) {
          settings.technique = "rsm-radial";
          radial_errors[radial_key] = measure_technique(shaders, source, settings, reference, seeds);
        }
        const technique_errors& radial = radial_errors[radial_key];
        settings.technique = "rsm-alg6";
        const technique_errors alg6 = measure_technique(shaders, source, settings, reference, seeds);
        const double radial_ms = ms[radial_key], alg6_ms = ms[c.label() + " rsm-alg6"];
        md << "| " << c.radius << " | " << c.paths << "x" << c.samples << " | " << c.slots << " | " << percent(radial.raw_vs_unoccluded.bias) << " % | "
           << percent(radial.raw_vs_exact.rmse) << " % | " << percent(alg6.raw_vs_exact.rmse) << " % | " << percent(radial.raw_leak.bias) << " % | "
           << percent(alg6.raw_leak.bias) << " % | " << percent(radial.filtered_vs_exact.rmse) << " / " << percent(alg6.filtered_vs_exact.rmse) << " % | "
           << fixed(radial_ms, 0) << " / " << fixed(alg6_ms, 0) << " |\n";
        for (const auto& [name, errors, time] : {std::tuple{"rsm-radial", &radial, radial_ms}, std::tuple{"rsm-alg6", &alg6, alg6_ms}}) {
          csv << scene_name << "," << c.radius << "," << c.paths << "," << c.samples << "," << c.slots << "," << name << "," << errors->raw_vs_unoccluded.bias
              << "," << errors->raw_vs_unoccluded.rmse << "," << errors->raw_vs_exact.rmse << "," << errors->raw_leak.bias << "," << errors->raw_leak.rmse << ","
              << errors->filtered_vs_exact.rmse << "," << errors->filtered_leak.bias << "," << errors->filtered_leak.rmse << "," << time << "\n";
        }
        pareto_rows.push_back(fixed(alg6_ms, 2) + " " + fixed(100.0 * alg6.filtered_vs_exact.rmse, 3) + " \"" + scene_name + "\" \"" + c.label() + "\"");
        summary& sum = summaries[c.label()];
        sum.worst_radial_bias = std::max(sum.worst_radial_bias, std::fabs(radial.raw_vs_unoccluded.bias));
        sum.worst_rmse_ratio = std::max(sum.worst_rmse_ratio, alg6.raw_vs_exact.rmse / radial.raw_vs_exact.rmse);
        sum.worst_leak_ratio = std::max(sum.worst_leak_ratio, radial.raw_leak.bias > 0.0 ? alg6.raw_leak.bias / radial.raw_leak.bias : 1e30);
        sum.filtered_rmse_sum += alg6.filtered_vs_exact.rmse;
        ++sum.scenes;
        csv.flush();
      }
    }

    // The summary: which configurations meet every target on every scene, and at what cost.
    md << "\n## Summary over the scenes\n\nTargets: |radial bias vs unoccluded| <= 10 %, Alg. 6 rel. RMSE below the radial pattern's (ratio < 1), "
          "Alg. 6 leak bias at most half of the radial pattern's (ratio <= 0.5); each the worst scene. ms on " << timing_scene << ".\n\n"
          "| radius | P x S | slots | worst |radial bias| | worst RMSE ratio | worst leak-bias ratio | mean filtered Alg. 6 rel. RMSE | ms Alg. 6 | all targets |\n"
          "|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
    for (const configuration& c : configurations) {
      const summary& sum = summaries[c.label()];
      if (sum.scenes == 0) continue;
      const bool met = sum.worst_radial_bias <= 0.1 && sum.worst_rmse_ratio < 1.0 && sum.worst_leak_ratio <= 0.5;
      md << "| " << c.radius << " | " << c.paths << "x" << c.samples << " | " << c.slots << " | " << percent(sum.worst_radial_bias) << " % | "
         << fixed(sum.worst_rmse_ratio, 2) << " | " << fixed(sum.worst_leak_ratio, 2) << " | " << percent(sum.filtered_rmse_sum / sum.scenes) << " % | "
         << fixed(ms[c.label() + " rsm-alg6"], 0) << " | " << (met ? "yes" : "no") << " |\n";
    }

    // The Pareto plot: filtered rel. RMSE of Alg. 6 against ms, one series per scene.
    {
      std::ofstream data(fs::path(out) / "pareto.dat");
      for (const std::string& row : pareto_rows) data << row << "\n";
    }
    std::ofstream plot(fs::path(out) / "pareto.gnuplot");
    plot << "set terminal pngcairo size 1000,650\nset output '" << (fs::path(out) / "pareto.png").string()
         << "'\nset xlabel 'ms per frame (" << size << "^2, wall clock)'\nset ylabel 'Alg. 6 filtered rel. RMSE vs exact brute force (%)'\n"
         << "set key outside right\nset grid\nplot ";
    const std::vector<std::string> scene_names = split(scenes_text);
    for (std::size_t i = 0; i < scene_names.size(); ++i)
      plot << (i ? ", " : "") << "'" << (fs::path(out) / "pareto.dat").string() << "' using 1:(strcol(3) eq '" << scene_names[i]
           << "' ? $2 : 1/0) with points pt 7 title '" << scene_names[i] << "'";
    plot << "\n";
    plot.close();
    const bool plotted = std::system(("gnuplot " + (fs::path(out) / "pareto.gnuplot").string() + " 2>/dev/null").c_str()) == 0;
    md << "\n## Error against time\n\n" << (plotted ? "![Alg. 6 error against ms](pareto.png)\n" : "(gnuplot is not installed: pareto.dat)\n");
    md << "\nReference frames: rsm-original (400 samples, radius 1/8) " << fixed(ms["rsm-original"], 0) << " ms, direct light only " << fixed(ms["direct"], 0)
       << " ms.\n";
    std::ofstream(fs::path(out) / "study.md") << md.str();
    std::cout << md.str() << "\nwrote " << fs::absolute(fs::path(out) / "study.md").string() << "\n";
  } catch (const std::exception& failure) {
    std::cerr << "vplkit_rsm_study: error: " << failure.what() << "\n";
    return 1;
  }
  return 0;
}
