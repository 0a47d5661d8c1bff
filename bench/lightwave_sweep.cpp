// Light Wave sweep ([LW], chapter 5) on the current GL implementation: the structure of
// Tables 5.1-5.9 (FPS and % similarity to the default configuration while varying the ray angle,
// VPLs per ray, resolution and indirect shadow maps, and the alternative methods), Table 5.10's
// ranking (Eq. 5.3), Tables 5.11-5.13 (integrated shadows over the steps) and 5.14-5.15 (scene
// complexity). Times: the wall clock of a whole frame in which nothing moved (VPLs and shadow maps
// are rebuilt only when the light moves), read-back included, median of --repeat frames; the
// rebuild is the extra time of a frame after the light moved. The whole frame, not the per-pass
// table: the sweep compares configurations by what a frame costs (the pass table of
// frontend/gl/pass_timer.hpp, wall clock on llvmpipe and timer queries on a GPU, is in
// `vplkit render`). Similarity: Alg. 1 (lightwave_similarity) on 8-bit
// sRGB images, a smaller render stretched to the default size first, as the thesis does for
// Table 5.7, next to the thesis's own numbers (Tables 5.5-5.9) and the RMSE of the 8-bit images.
// Every image uses the thesis's VPLs (--vpl-energy thesis), whose tables these are; --energy flux
// sweeps vplkit's default instead.
// --seeds N adds the seed table: Table 5.8's and 5.9's rows against the default configuration of
// the same seed, for seeds --first-seed .. --first-seed + N - 1, with their mean and spread
// (largest - smallest); the accurate shadows' VPLs are the only thing a seed draws.
//   build/bench/vplkit_lightwave_sweep [--width 320] [--height 180] [--repeat 3] [--quick] [--energy thesis]
//       [--seeds 0] [--first-seed 1] [--seed-table-only] [--out output/bench]
// The thesis's 1280 x 720 is the default of `vplkit render`; llvmpipe needs the sweep smaller:
// --width/--height scale every resolution of the tables by the same factor.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

#include "frontend/gl/context.hpp"
#include "frontend/core/error.hpp"
#include "frontend/image/image_files.hpp"
#include "frontend/techniques/lightwave/lightwave_pipeline.hpp"

namespace fs = std::filesystem;
using namespace vplkit;

namespace {

struct result {
  std::string table, label;
  lightwave_settings settings;
  double main_ms = 0.0, rebuild_ms = 0.0, similarity = 100.0;
  std::size_t triangles = 0;
  double thesis_similarity = -1.0;  ///< the thesis's % similar for this row (Tables 5.5-5.9), -1: none
  double rmse8 = 0.0;               ///< RMSE against the default on 8-bit images, values / 255
  double fps() const { return 1000.0 / std::max(main_ms, 1e-6); }
};

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values.empty() ? 0.0 : values[values.size() / 2];
}

// Nearest-neighbour stretch of an sRGB8 RGBA image to width x height ("stretching", Table 5.7).
std::vector<std::uint8_t> stretch(const std::vector<std::uint8_t>& image, int w, int h, int width, int height) {
  std::vector<std::uint8_t> out(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const int sx = std::min(w - 1, x * w / width), sy = std::min(h - 1, y * h / height);
      for (int c = 0; c < 4; ++c)
        out[(static_cast<std::size_t>(y) * width + x) * 4 + c] = image[(static_cast<std::size_t>(sy) * w + sx) * 4 + c];
    }
  return out;
}

// RGB channels only: Alg. 1 compares colour components.
double similarity_rgb(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
  std::vector<std::uint8_t> ra, rb;
  for (std::size_t i = 0; i < a.size(); i += 4)
    for (int c = 0; c < 3; ++c) {
      ra.push_back(a[i + static_cast<std::size_t>(c)]);
      rb.push_back(b[i + static_cast<std::size_t>(c)]);
    }
  return lightwave_similarity(ra.data(), rb.data(), ra.size());
}

std::string fixed(double value, int digits) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(digits) << value;
  return out.str();
}

// The seed table: Table 5.8's rows (maps) and Table 5.9's (no maps, direct light, faked indirect)
// against the default of each seed, by Alg. 1 on 8-bit sRGB images of the boxes.
std::string seed_table(const shader_library& shaders, const scene& boxes, const lightwave_settings& defaults, std::uint32_t first_seed, int seeds) {
  const auto image_of = [&](const lightwave_settings& settings) {
    lightwave_pipeline pipeline(shaders, boxes, settings);
    return to_srgb8(pipeline.render().radiance);
  };
  struct seed_row {
    std::string label;
    lightwave_settings settings;
    bool seeded;
    std::vector<double> similarity;
  };
  std::vector<seed_row> rows;
  for (int maps : {15, 10, 5, 1}) {
    lightwave_settings s = defaults;
    s.accurate_maps = maps;
    rows.push_back({std::to_string(maps) + " maps", s, true, {}});
  }
  lightwave_settings s = defaults;
  s.shadow_variant = lightwave_shadow_variant::thesis;  // the printed method: its VPLs drawn with the seed
  rows.push_back({std::to_string(defaults.accurate_maps) + " maps, the thesis's shadow variant", s, true, {}});
  s = defaults;
  s.technique = "lightwave-unshadowed";
  rows.push_back({"0 maps (lightwave-unshadowed)", s, false, {}});
  s.technique = "lightwave-direct";
  rows.push_back({"direct lighting only", s, false, {}});
  for (float m : {1.1f, 1.3f, 1.5f}) {
    s.technique = "lightwave-faked";
    s.faked_multiplier = m;
    rows.push_back({"faked indirect " + fixed(m, 1) + "x", s, false, {}});
  }
  std::map<std::size_t, std::vector<std::uint8_t>> unseeded;
  for (int k = 0; k < seeds; ++k) {
    const std::uint32_t seed = first_seed + static_cast<std::uint32_t>(k);
    lightwave_settings reference_settings = defaults;
    reference_settings.seed = seed;
    const std::vector<std::uint8_t> reference = image_of(reference_settings);
    for (std::size_t r = 0; r < rows.size(); ++r) {
      lightwave_settings settings = rows[r].settings;
      settings.seed = seed;
      if (!rows[r].seeded && !unseeded.count(r)) unseeded[r] = image_of(settings);
      const std::vector<std::uint8_t> image = rows[r].seeded ? image_of(settings) : unseeded[r];
      rows[r].similarity.push_back(similarity_rgb(reference, image));
      std::cerr << "  seed " << seed << ": " << rows[r].label << " " << fixed(rows[r].similarity.back(), 3) << "% similar\n";
    }
  }
  std::ostringstream md;
  md << "\n## Seeds: Tables 5.8 and 5.9 against the default of each seed\n\nBoxes, " << defaults.width << "x" << defaults.height << ", --vpl-energy "
     << (defaults.energy == lightwave_energy::thesis ? "thesis" : "flux") << ", % similar (Alg. 1, 8-bit sRGB, every pixel) to the default (accurate, "
     << defaults.accurate_maps << " maps) rendered with the same seed; seeds " << first_seed << "-" << first_seed + static_cast<std::uint32_t>(seeds) - 1
     << ". Spread: largest - smallest; worst: the seed furthest from the mean.\n\n| configuration |";
  for (int k = 0; k < seeds; ++k) md << " seed " << first_seed + static_cast<std::uint32_t>(k) << " |";
  md << " mean | spread | worst |\n|---|";
  for (int k = 0; k < seeds + 3; ++k) md << "---:|";
  md << "\n";
  for (const seed_row& row : rows) {
    md << "| " << row.label << " |";
    double sum = 0.0;
    for (double value : row.similarity) {
      md << " " << fixed(value, 3) << " |";
      sum += value;
    }
    const auto [low, high] = std::minmax_element(row.similarity.begin(), row.similarity.end());
    const double mean = sum / static_cast<double>(row.similarity.size());
    const double worst = mean - *low > *high - mean ? *low : *high;
    md << " " << fixed(mean, 3) << " | " << fixed(*high - *low, 3) << " | " << fixed(worst, 3) << " |\n";
  }
  return md.str();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Light Wave sweep ([LW], Tables 5.1-5.15)"};
  int width = 320, height = 180, repeat = 3, seeds = 0;
  std::uint32_t first_seed = 1;
  bool quick = false, seed_table_only = false;
  std::string out = "output/bench", energy = "thesis";
  app.add_option("--width", width, "default width (the thesis: 1280)")->check(CLI::Range(16, 4096))->capture_default_str();
  app.add_option("--height", height, "default height (the thesis: 720)")->check(CLI::Range(16, 4096))->capture_default_str();
  app.add_option("--repeat", repeat, "timed frames per configuration (median)")->check(CLI::Range(1, 50))->capture_default_str();
  app.add_flag("--quick", quick, "skip the teapot scenes and the integrated-shadow tables");
  app.add_option("--energy", energy, "--vpl-energy of every image (the thesis's tables: thesis)")->check(CLI::IsMember({"thesis", "flux"}))->capture_default_str();
  app.add_option("--seeds", seeds, "seeds of the seed table (0: none)")->check(CLI::Range(0, 64))->capture_default_str();
  app.add_option("--first-seed", first_seed, "the seed table's first seed")->capture_default_str();
  app.add_flag("--seed-table-only", seed_table_only, "only the seed table (with --seeds)");
  app.add_option("--out", out, "folder for lightwave_sweep.csv and lightwave_sweep.md")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  try {
    auto context = create_headless_context();
    const shader_library shaders(default_shader_dir());
    std::map<std::string, scene> scenes;
    scenes["boxes"] = make_boxes_scene();

    lightwave_settings defaults;
    defaults.width = width;
    defaults.height = height;
    defaults.energy = energy == "flux" ? lightwave_energy::flux : lightwave_energy::thesis;
    std::ostringstream seed_md;
    if (seeds > 0) seed_md << seed_table(shaders, scenes.at("boxes"), defaults, first_seed, seeds);
    if (seed_table_only) {
      fs::create_directories(out);
      std::ofstream(fs::path(out) / "lightwave_seeds.md") << seed_md.str();
      std::cout << seed_md.str() << "\nwrote " << fs::absolute(fs::path(out) / "lightwave_seeds.md").string() << "\n";
      return 0;
    }
    std::vector<std::uint8_t> reference;
    std::vector<result> results;

    const auto run = [&](const std::string& table, const std::string& label, lightwave_settings settings, const std::string& scene_name,
                         double thesis_similarity = -1.0) {
      const scene& source = scenes.at(scene_name);
      lightwave_pipeline pipeline(shaders, source, settings);
      pipeline.render();  // warm-up: shader JIT
      pipeline.set_light(source.light.spot);
      result r{table, label, settings, 0.0, 0.0, 100.0, source.geometry.triangle_count()};
      const auto timed = [&](lightwave_frame& frame) {
        const auto start = std::chrono::steady_clock::now();
        frame = pipeline.render();  // returns after reading the image back: the frame is done
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      };
      lightwave_frame frame;
      const double with_rebuild = timed(frame);
      std::vector<double> times;
      for (int i = 0; i < repeat; ++i) times.push_back(timed(frame));
      r.main_ms = median(times);
      r.rebuild_ms = std::max(0.0, with_rebuild - r.main_ms);
      std::vector<std::uint8_t> image = to_srgb8(frame.radiance);
      if (frame.radiance.width != width || frame.radiance.height != height) image = stretch(image, frame.radiance.width, frame.radiance.height, width, height);
      if (scene_name == "boxes") {
        if (reference.empty()) reference = image;
        r.similarity = similarity_rgb(reference, image);
        double squared = 0.0;
        for (std::size_t i = 0; i < image.size(); ++i)
          if (i % 4 != 3) squared += std::pow((static_cast<double>(image[i]) - static_cast<double>(reference[i])) / 255.0, 2.0);
        r.rmse8 = std::sqrt(squared / (0.75 * static_cast<double>(image.size())));
      }
      r.thesis_similarity = thesis_similarity;
      std::cerr << "  " << table << " " << label << ": " << fixed(r.main_ms, 2) << " ms, " << fixed(r.similarity, 3) << "% similar\n";
      results.push_back(r);
      return r;
    };

    // The default configuration first: every similarity is against it.
    const result base = run("default", "default (accurate, 5 deg, 5 per ray, 20 maps)", defaults, "boxes");
    // The thesis's % similar to its default (Tables 5.5-5.9), side by side.
    const std::map<int, double> thesis_angle = {{10, 97.945}, {30, 97.956}, {45, 95.440}, {90, 92.676}};
    const std::map<int, double> thesis_per_ray = {{4, 92.973}, {3, 93.458}, {2, 90.318}, {1, 91.591}, {6, 96.509}};
    const std::map<int, double> thesis_resolution = {{1120, 99.547}, {960, 99.541}, {800, 99.418}, {640, 99.483}, {1440, 99.741}};
    const std::map<int, double> thesis_maps = {{15, 99.475}, {10, 98.853}, {5, 93.611}, {1, 90.897}};
    const std::map<std::string, double> thesis_alternatives = {{"direct", 84.426}, {"unshadowed", 98.563}, {"1.1", 88.217}, {"1.2", 90.675},
                                                               {"1.3", 91.847}, {"1.4", 91.393}, {"1.5", 90.161}};
    for (int angle : {10, 30, 45, 90}) {
      lightwave_settings s = defaults;
      s.angle_deg = angle;
      run("5.1/5.5 ray angle", std::to_string(angle) + " degrees, " + std::to_string(lightwave_vpl_count(angle, 5)) + " VPLs", s, "boxes",
          thesis_angle.at(angle));
    }
    for (int per_ray : {4, 3, 2, 1, 6}) {
      lightwave_settings s = defaults;
      s.per_ray = per_ray;
      run("5.2/5.6 VPLs per ray", std::to_string(per_ray) + " per ray, " + std::to_string(lightwave_vpl_count(5, per_ray)) + " VPLs", s, "boxes",
          thesis_per_ray.at(per_ray));
    }
    for (const auto& [w, h] : std::vector<std::pair<int, int>>{{1120, 630}, {960, 540}, {800, 450}, {640, 360}, {1440, 810}}) {
      lightwave_settings s = defaults;
      s.width = w * width / 1280;
      s.height = h * height / 720;
      run("5.3/5.7 resolution", std::to_string(w) + "x" + std::to_string(h) + " scaled: " + std::to_string(s.width) + "x" + std::to_string(s.height), s, "boxes",
          thesis_resolution.at(w));
    }
    for (int maps : {15, 10, 5, 1}) {
      lightwave_settings s = defaults;
      s.accurate_maps = maps;
      run("5.4/5.8 indirect shadow maps", std::to_string(maps) + " maps", s, "boxes", thesis_maps.at(maps));
    }
    {
      lightwave_settings s = defaults;
      s.accurate_maps = 0;
      run("5.4/5.8 indirect shadow maps", "0 maps (no indirect shadows)", s, "boxes", thesis_alternatives.at("unshadowed"));
      s.technique = "lightwave-direct";
      run("5.9 alternatives", "direct lighting only", s, "boxes", thesis_alternatives.at("direct"));
      for (float m : {1.1f, 1.2f, 1.3f, 1.4f, 1.5f}) {
        s.technique = "lightwave-faked";
        s.faked_multiplier = m;
        run("5.9 alternatives", "faked indirect " + fixed(m, 1) + "x", s, "boxes", thesis_alternatives.at(fixed(m, 1)));
      }
      // The same tables with the thesis's own accurate shadows, for comparison.
      lightwave_settings plain = defaults;
      plain.shadow_variant = lightwave_shadow_variant::thesis;
      run("5.8, thesis variant", "20 maps, thesis variant (uniform VPLs, maps along the normals, plain mean)", plain, "boxes");
    }
    if (!quick) {
      for (int steps : {2, 4, 6, 10}) {
        lightwave_settings s = defaults;
        s.technique = "lightwave-integrated";
        s.integrated_steps = steps;
        run("5.11 integrated steps", std::to_string(steps) + " steps, " + std::to_string(lightwave_integrated_shadow_count(steps, 5)) + " shadows", s, "boxes");
        s.width = width / 2;
        s.height = height / 2;
        run("5.12 integrated steps, half resolution", std::to_string(steps) + " steps", s, "boxes");
        s = defaults;
        s.technique = "lightwave-integrated";
        s.integrated_steps = steps;
        s.angle_deg = 30;
        run("5.13 integrated steps, 185 VPLs", std::to_string(steps) + " steps", s, "boxes");
      }
      for (const char* name : {"teapot", "teapots"}) {
        try {
          scenes[name] = built_in_scene(name);
        } catch (const error& failure) {
          std::cerr << "skipping scene " << name << ": " << failure.what() << "\n";
          continue;
        }
        for (const char* technique : {"lightwave-accurate", "lightwave-unshadowed", "lightwave-direct", "lightwave-integrated"}) {
          lightwave_settings s = defaults;
          s.technique = technique;
          run(std::string("5.14/5.15 scene ") + name, technique, s, name);
        }
        lightwave_settings s = defaults;
        s.angle_deg = 30;
        run(std::string("5.14/5.15 scene ") + name, "lightwave-accurate, 30 degrees (185 VPLs)", s, name);
      }
    }

    std::ostringstream md;
    md << "# Light Wave sweep\n\nDefault " << width << "x" << height << " (the thesis: 1280x720, scaled for llvmpipe), --vpl-energy " << energy
       << ", shadow maps " << defaults.shadow_map_scale << "x the screen, median wall clock of " << repeat
       << " frames with nothing moving (read-back included) on:\n\n```\n"
       << describe_current_context() << "\n```\n\n| table | configuration | triangles | frame ms | FPS | rebuild ms | % similar | the thesis's % similar | RMSE vs default (8-bit) | rank (Eq. 5.3) |\n"
          "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    std::ofstream csv_file;
    std::ostringstream csv;
    csv << "table,configuration,technique,width,height,angle,per_ray,vpls,accurate_maps,integrated_steps,triangles,main_ms,fps,rebuild_ms,similarity,thesis_similarity,rmse8,rank\n";
    std::vector<const result*> ranked;
    for (const result& r : results) {
      const double gain = r.fps() - base.fps();
      const bool rankable = &r != &results.front() && r.similarity < 100.0 && r.triangles == base.triangles;
      const double rank = rankable ? lightwave_rank(gain, r.similarity) : 0.0;
      if (rankable) ranked.push_back(&r);
      md << "| " << r.table << " | " << r.label << " | " << r.triangles << " | " << fixed(r.main_ms, 2) << " | " << fixed(r.fps(), 1) << " | "
         << fixed(r.rebuild_ms, 1) << " | " << (r.triangles == base.triangles ? fixed(r.similarity, 3) : std::string("-")) << " | "
         << (r.thesis_similarity >= 0.0 ? fixed(r.thesis_similarity, 3) : std::string("-")) << " | "
         << (r.triangles == base.triangles ? fixed(r.rmse8, 5) : std::string("-")) << " | " << (rankable ? fixed(rank, 2) : std::string("-")) << " |\n";
      csv << r.table << ",\"" << r.label << "\"," << r.settings.technique << "," << r.settings.width << "," << r.settings.height << ","
          << r.settings.angle_deg << "," << r.settings.per_ray << "," << lightwave_vpl_count(r.settings.angle_deg, r.settings.per_ray) << ","
          << r.settings.accurate_maps << "," << r.settings.integrated_steps << "," << r.triangles << "," << r.main_ms << "," << r.fps() << ","
          << r.rebuild_ms << "," << r.similarity << "," << r.thesis_similarity << "," << r.rmse8 << "," << rank << "\n";
    }
    std::sort(ranked.begin(), ranked.end(), [&](const result* a, const result* b) {
      return lightwave_rank(a->fps() - base.fps(), a->similarity) > lightwave_rank(b->fps() - base.fps(), b->similarity);
    });
    md << "\n## Ranking (Table 5.10, Eq. 5.3: FPS gain over the default / (100 - % similar))\n\n| rank | configuration | FPS | % similar | rank value |\n|---:|---|---:|---:|---:|\n";
    for (std::size_t i = 0; i < ranked.size(); ++i)
      md << "| " << i + 1 << " | " << ranked[i]->table << ": " << ranked[i]->label << " | " << fixed(ranked[i]->fps(), 1) << " | "
         << fixed(ranked[i]->similarity, 3) << " | " << fixed(lightwave_rank(ranked[i]->fps() - base.fps(), ranked[i]->similarity), 2) << " |\n";
    md << seed_md.str();
    fs::create_directories(out);
    std::ofstream(fs::path(out) / "lightwave_sweep.csv") << csv.str();
    std::ofstream(fs::path(out) / "lightwave_sweep.md") << md.str();
    std::cout << md.str() << "\nwrote " << fs::absolute(fs::path(out) / "lightwave_sweep.csv").string() << " and lightwave_sweep.md\n";
  } catch (const std::exception& failure) {
    std::cerr << "vplkit_lightwave_sweep: error: " << failure.what() << "\n";
    return 1;
  }
  return 0;
}
