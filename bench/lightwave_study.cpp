// Light Wave against the one-bounce Monte Carlo reference, per scene and per seed: the
// measurements behind docs/lightwave-shadows.md ("Against the one-bounce reference").
//   build/bench/vplkit_lightwave_study [--size 640x360] [--samples 1024] [--seeds 4] [--maps 20,10,5,1]
//       [--scenes boxes,teapot,bench/scenes/room-a.gltf,...] [--energy flux] [--out output/lightwave-study]
// A scene is a built-in name or a .gltf/.glb/.obj path, optionally posed: NAME@camera=x,y,z,tx,ty,tz
// and/or @light=x,y,z,tx,ty,tz (as render --camera/--light).
// For each scene: the reference (Embree, --samples bounce rays per pixel, reference seed 1) and its
// direct light alone (0 bounce rays), cached in --out/references (keyed by the scene's bytes, its
// posed camera and light and the size: bench/study_cache.hpp); a second reference with a
// quarter of the samples and another seed gives the reference's noise (sigma, per pixel and
// channel: their RMSE / sqrt(5)). Then lightwave-direct, -unshadowed, and -accurate with each
// --maps count for seeds 0 .. --seeds - 1, at the same size, with the defaults otherwise.
// What each number covers:
// - RMSE: linear radiance, every pixel of the image, the three channels (background pixels are 0
//   in both images and count as equal);
// - RMSE 8-bit: the same on 8-bit sRGB images (values / 255);
// - level: the indirect light an image adds (its -indirect output: final minus direct, linear,
//   after the indirect shadow factor), summed as Rec. 709 luminance over every pixel, divided by
//   the reference's (its final image minus its direct-only image, the same sum);
// - mean and spread over the seeds (spread = largest - smallest), and the worst seed.
// Writes study.md and study.csv into --out.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

#include "bench/study_cache.hpp"
#include "frontend/core/error.hpp"
#include "frontend/core/files.hpp"
#include "frontend/core/parallel.hpp"
#include "frontend/core/text.hpp"
#include "frontend/gl/context.hpp"
#include "frontend/image/image_files.hpp"
#include "frontend/reference/reference.hpp"
#include "frontend/reference/rsm_measure.hpp"
#include "frontend/scene/gltf_scene.hpp"
#include "frontend/scene/obj_loader.hpp"
#include "frontend/scene/pose.hpp"
#include "frontend/techniques/lightwave/lightwave_pipeline.hpp"

namespace fs = std::filesystem;
using namespace vplkit;

namespace {

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> items;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, separator);)
    if (!item.empty()) items.push_back(item);
  return items;
}

// --scenes split at its commas, except those inside a pose: a pose's six numbers stay together.
std::vector<std::string> split_scenes(const std::string& text) {
  std::vector<std::string> scenes;
  int pose_numbers_left = 0;
  for (const std::string& item : split(text, ',')) {
    if (pose_numbers_left > 0) {
      scenes.back() += "," + item;
      --pose_numbers_left;
    } else {
      scenes.push_back(item);
    }
    if (item.find('=') != std::string::npos) pose_numbers_left = 5;  // x,y,z,tx,ty,tz: five more after the '='
  }
  return scenes;
}

// The scene part of "NAME[@camera=...][@light=...]".
std::string scene_file_of(const std::string& spec) { return spec.substr(0, spec.find('@')); }

// "NAME[@camera=...][@light=...]" -> the scene, posed, and a label for files and tables.
scene load_study_scene(const std::string& spec, std::string& label) {
  const std::vector<std::string> parts = split(spec, '@');
  if (parts.empty()) throw error("empty scene in --scenes");
  const std::string& name = parts[0];
  const std::string extension = fs::path(name).extension().string();
  scene loaded = extension == ".obj"                          ? frame_mesh(fs::path(name).stem().string(), load_obj(name))
                 : extension == ".gltf" || extension == ".glb" ? load_gltf(name)
                                                               : built_in_scene(name);
  label = fs::path(name).stem().string();
  for (std::size_t i = 1; i < parts.size(); ++i) {
    const std::size_t equals = parts[i].find('=');
    const std::string key = parts[i].substr(0, equals);
    pose where;
    if (equals == std::string::npos || (key != "camera" && key != "light")) throw error("scene " + spec + ": expected @camera=... or @light=...");
    if (const std::string problem = parse_pose(parts[i].substr(equals + 1), where); !problem.empty()) throw error("scene " + spec + ": " + problem);
    if (key == "camera") apply_pose(where, loaded.view, "scene " + spec + " camera");
    if (key == "light") apply_pose(where, loaded.lights[0], "scene " + spec + " light");
    label += "-" + key + std::to_string(i);
  }
  check_scene(loaded);
  return loaded;
}

double rmse(const image& a, const image& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.texels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double d = static_cast<double>(a.texels[i][c]) - static_cast<double>(b.texels[i][c]);
      sum += d * d;
    }
  return std::sqrt(sum / (3.0 * static_cast<double>(a.texels.size())));
}

double rmse8(const image& a, const image& b) {
  const std::vector<std::uint8_t> a8 = to_srgb8(a), b8 = to_srgb8(b);
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < a8.size(); ++i) {
    if (i % 4 == 3) continue;
    const double d = (static_cast<double>(a8[i]) - static_cast<double>(b8[i])) / 255.0;
    sum += d * d;
    ++count;
  }
  return std::sqrt(sum / static_cast<double>(count));
}

double luminance_sum(const image& a) {
  double sum = 0.0;
  for (const glm::vec4& texel : a.texels) sum += luminance(glm::dvec3(texel));
  return sum;
}

image difference(const image& a, const image& b) {
  image out = a;
  for (std::size_t i = 0; i < out.texels.size(); ++i) out.texels[i] = glm::vec4(glm::vec3(a.texels[i]) - glm::vec3(b.texels[i]), 1.0f);
  return out;
}

// A cached reference image (PFM), computed when missing.
image cached_reference(const fs::path& path, const scene& source, int width, int height, int samples, std::uint32_t seed) {
  if (fs::exists(path)) {
    image cached = read_image_file(path.string());
    if (cached.width == width && cached.height == height) return cached;
  }
  std::cerr << "  reference " << path.filename().string() << " (" << samples << " samples)\n";
  const one_bounce_images images = reference_one_bounce(source, width, height, samples, seed, hardware_threads());
  write_bytes_atomically(path, encode_pfm(images.radiance));
  return images.radiance;
}

struct measurement {
  double rmse = 0.0, rmse8 = 0.0, level = 0.0;
  double difference = 0.0;  ///< RMS of (this image - lightwave-unshadowed), linear, every pixel and channel
};

struct row {
  std::string technique;
  std::vector<measurement> seeds;  ///< one per seed (the seed-free techniques: the same for every seed)
};

double mean_of(const std::vector<double>& values) {
  double sum = 0.0;
  for (double v : values) sum += v;
  return values.empty() ? 0.0 : sum / static_cast<double>(values.size());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Light Wave against the one-bounce Monte Carlo reference, per scene and seed"};
  std::string size_text = "640x360", scenes_text = "boxes,teapot", maps_text = "20,10,5,1", energy = "flux", out = "output/lightwave-study";
  int samples = 1024, seeds = 4;
  float receiver_spacing = lightwave_settings{}.receiver_spacing;
  app.add_option("--size", size_text, "image size WxH")->capture_default_str();
  app.add_option("--samples", samples, "bounce rays per pixel of the reference")->check(CLI::Range(4, 1 << 16))->capture_default_str();
  app.add_option("--seeds", seeds, "seeds 0 .. N-1 of the accurate shadows")->check(CLI::Range(1, 64))->capture_default_str();
  app.add_option("--maps", maps_text, "accurate shadow map counts, comma-separated")->capture_default_str();
  app.add_option("--scenes", scenes_text, "comma-separated scenes: built-in names or files, each optionally @camera=...@light=...")->capture_default_str();
  app.add_option("--energy", energy, "--vpl-energy of every Light Wave image")->check(CLI::IsMember({"flux", "thesis"}))->capture_default_str();
  app.add_option("--receiver-spacing", receiver_spacing, "flux energy: receiver edge bound, a fraction of the scene's bounding radius")
      ->check(CLI::Range(0.001, 4.0))->capture_default_str();
  app.add_option("--out", out, "folder for study.md, study.csv and references/")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    int width = 0, height = 0;
    if (std::sscanf(size_text.c_str(), "%dx%d", &width, &height) != 2 || !validate_image_size(width, height).empty())
      throw error("--size must be WxH, got " + size_text);
    std::vector<int> map_counts;
    for (const std::string& item : split(maps_text, ',')) map_counts.push_back(std::stoi(item));
    fs::create_directories(fs::path(out) / "references");
    auto context = create_headless_context();
    const shader_library shaders(default_shader_dir());
    std::ostringstream md, csv;
    md << "# Light Wave against the one-bounce reference\n\n" << width << "x" << height << ", reference " << samples
       << " bounce rays per pixel, seeds 0-" << seeds - 1 << ", --vpl-energy " << energy << ", receiver spacing " << receiver_spacing
       << ", defaults otherwise, on:\n\n```\n"
       << describe_current_context() << "\n```\n\nRMSE: linear radiance over every pixel and channel. Level: the indirect light added (final minus "
       << "direct, linear, Rec. 709 luminance summed over the image) over the reference's. Spread: largest minus smallest over the seeds.\n";
    csv << "scene,technique,seed,rmse,rmse8,level\n";
    std::ostringstream summary;
    summary << "\n## Targets\n\n| scene | reference noise (sigma) | direct RMSE | unshadowed RMSE | accurate RMSE: mean / worst seed | accurate < "
               "unshadowed, seeds (unshadowed - worst accurate RMSE +- its standard error from the reference's noise) | accurate < direct | level of accurate: mean (worst) | maps never worse than none (mean over seeds; mean - unshadowed RMSE +- standard error) |\n"
               "|---|---:|---:|---:|---:|---:|---:|---:|---|\n";
    std::map<std::string, int> labels_seen;
    for (const std::string& spec : split_scenes(scenes_text)) {
      std::string label;
      const scene source = load_study_scene(spec, label);
      // Two poses of one file give one label ("room-a-camera1"): the second is "room-a-camera1-2",
      // so that its images and rows are its own.
      if (const int seen = ++labels_seen[label]; seen > 1) label += "-" + std::to_string(seen);
      std::cerr << label << "\n";
      // The references' names: readable, then the key of everything they depend on (the scene's
      // bytes, its posed camera and light, the size), so that two poses of one file differ.
      const std::string stem = label + "-" + std::to_string(width) + "x" + std::to_string(height) + "-" +
                               cache_key(study::scene_identity(scene_file_of(spec), source) + "\nsize " + std::to_string(width) + "x" +
                                         std::to_string(height));
      const fs::path references = fs::path(out) / "references";
      const std::string revision = "-r" + std::to_string(monte_carlo_revision);
      const image reference = cached_reference(references / (stem + "-" + std::to_string(samples) + revision + ".pfm"), source, width, height, samples, 1u);
      const image quarter =
          cached_reference(references / (stem + "-" + std::to_string(samples / 4) + "-seed2" + revision + ".pfm"), source, width, height, samples / 4, 2u);
      const image direct_only = cached_reference(references / (stem + "-direct" + revision + ".pfm"), source, width, height, 0, 1u);
      const double noise = rmse(reference, quarter) / std::sqrt(5.0);
      const double reference_indirect = luminance_sum(difference(reference, direct_only));
      std::vector<row> rows;
      double direct_floor = 0.0;  // lightwave-direct against the reference's direct light: shadow maps against rays
      image unshadowed_image;
      const auto measure = [&](const std::string& technique, int maps, std::uint32_t seed) {
        lightwave_settings settings;
        settings.technique = technique;
        settings.width = width;
        settings.height = height;
        settings.accurate_maps = maps;
        settings.seed = seed;
        settings.energy = energy == "thesis" ? lightwave_energy::thesis : lightwave_energy::flux;
        settings.receiver_spacing = receiver_spacing;
        lightwave_pipeline pipeline(shaders, source, settings);
        const lightwave_frame frame = pipeline.render();
        if (seed == 0 && maps == map_counts.front())
          write_png(fs::path(out) / (label + "-" + technique + ".png"), frame.radiance.width, frame.radiance.height, to_srgb8(frame.radiance));
        if (technique == "lightwave-direct") direct_floor = rmse(frame.radiance, direct_only);
        if (technique == "lightwave-unshadowed") unshadowed_image = frame.radiance;
        return measurement{rmse(frame.radiance, reference), rmse8(frame.radiance, reference),
                           reference_indirect > 0.0 ? luminance_sum(frame.indirect) / reference_indirect : 0.0,
                           unshadowed_image.texels.empty() ? 0.0 : rmse(frame.radiance, unshadowed_image)};
      };
      for (const char* technique : {"lightwave-direct", "lightwave-unshadowed"}) {
        const measurement m = measure(technique, 20, 0);
        rows.push_back({technique, std::vector<measurement>(static_cast<std::size_t>(seeds), m)});
      }
      for (int maps : map_counts) {
        row r{"lightwave-accurate, " + std::to_string(maps) + " maps", {}};
        for (int seed = 0; seed < seeds; ++seed) r.seeds.push_back(measure("lightwave-accurate", maps, static_cast<std::uint32_t>(seed)));
        rows.push_back(r);
      }
      write_png(fs::path(out) / (label + "-reference.png"), reference.width, reference.height, to_srgb8(reference));
      md << "\n## " << label << "\n\n`" << spec << "`: " << source.geometry.triangle_count() << " triangles; reference noise sigma " << fixed(noise, 5)
         << " (per pixel and channel); reference indirect level " << fixed(reference_indirect / static_cast<double>(width * height), 5)
         << " (mean luminance); lightwave-direct against the reference's direct light alone: RMSE " << fixed(direct_floor, 5)
         << " (what the direct light's shadow map and pixel sampling leave)\n\n| technique |";
      for (int seed = 0; seed < seeds; ++seed) md << " seed " << seed << " |";
      md << " mean | spread | worst | RMSE 8-bit (mean) | level (mean) | level (worst) |\n|---|";
      for (int seed = 0; seed < seeds + 6; ++seed) md << "---:|";
      md << "\n";
      std::map<std::string, std::vector<double>> rmse_of;
      std::map<std::string, std::vector<double>> level_of;
      for (const row& r : rows) {
        std::vector<double> values, levels, values8;
        md << "| " << r.technique << " |";
        for (std::size_t seed = 0; seed < r.seeds.size(); ++seed) {
          values.push_back(r.seeds[seed].rmse);
          values8.push_back(r.seeds[seed].rmse8);
          levels.push_back(r.seeds[seed].level);
          md << " " << fixed(r.seeds[seed].rmse, 5) << " |";
          csv << label << "," << r.technique << "," << seed << "," << r.seeds[seed].rmse << "," << r.seeds[seed].rmse8 << "," << r.seeds[seed].level << "\n";
        }
        const auto [low, high] = std::minmax_element(values.begin(), values.end());
        const double worst_level = *std::max_element(levels.begin(), levels.end(), [](double a, double b) { return std::fabs(a - 1.0) < std::fabs(b - 1.0); });
        md << " " << fixed(mean_of(values), 5) << " | " << fixed(*high - *low, 5) << " | " << fixed(*high, 5) << " | " << fixed(mean_of(values8), 5) << " | "
           << fixed(mean_of(levels), 3) << " | " << fixed(worst_level, 3) << " |\n";
        rmse_of[r.technique] = values;
        level_of[r.technique] = levels;
      }
      const std::string accurate = "lightwave-accurate, " + std::to_string(map_counts.front()) + " maps";
      const std::vector<double>& a = rmse_of[accurate];
      const double unshadowed = rmse_of["lightwave-unshadowed"].front(), direct = rmse_of["lightwave-direct"].front();
      int nearer = 0;
      for (double v : a) nearer += v < unshadowed;
      // The reference's noise n enters MSE(image, reference) as MSE(image, truth) + sigma^2 +
      // 2 <image - truth, n>: the same sigma^2 for every image, and a cross term whose difference
      // between two images a, b has the standard deviation 2 sigma rms(a - b) / sqrt(3 pixels).
      // In RMSE: that over (RMSE(a) + RMSE(b)).
      const auto standard_error_of = [&](const row& r) {
        double difference = 0.0;
        for (const measurement& m : r.seeds) difference = std::max(difference, m.difference);
        return 2.0 * noise * difference / std::sqrt(3.0 * static_cast<double>(width * height)) / (2.0 * unshadowed);
      };
      const double standard_error = standard_error_of(rows[2]);
      const double worst_level = *std::max_element(level_of[accurate].begin(), level_of[accurate].end(),
                                                   [](double x, double y) { return std::fabs(x - 1.0) < std::fabs(y - 1.0); });
      // "equal within noise": further than none by less than twice the standard error of the
      // difference that the reference's noise leaves (its sign is not measured).
      std::string fewer;
      for (std::size_t k = 0; k < map_counts.size(); ++k) {
        // The mean over the seeds against the unshadowed image's mean over the same seeds: an image
        // equal to the unshadowed one compares equal, not one rounding above it.
        const double m = mean_of(rmse_of["lightwave-accurate, " + std::to_string(map_counts[k]) + " maps"]);
        const double none = mean_of(rmse_of["lightwave-unshadowed"]);
        const double error = standard_error_of(rows[2 + k]);
        const char* verdict = m <= none ? "yes" : m <= none + 2.0 * error ? "equal within noise" : "NO";
        fewer += std::to_string(map_counts[k]) + ": " + verdict + " (" + fixed(m - none, 7) + " +- " + fixed(error, 7) + ") ";
      }
      summary << "| " << label << " | " << fixed(noise, 5) << " | " << fixed(direct, 5) << " | " << fixed(unshadowed, 5) << " | " << fixed(mean_of(a), 5)
              << " / " << fixed(*std::max_element(a.begin(), a.end()), 5) << " | " << nearer << " of " << a.size() << " (difference "
              << fixed(unshadowed - *std::max_element(a.begin(), a.end()), 6) << " +- " << fixed(standard_error, 6) << ") | "
              << (*std::max_element(a.begin(), a.end()) < direct ? "yes" : "NO") << " | " << fixed(mean_of(level_of[accurate]), 3) << " ("
              << fixed(worst_level, 3) << ") | " << fewer << "|\n";
    }
    md << summary.str();
    std::ofstream(fs::path(out) / "study.md") << md.str();
    std::ofstream(fs::path(out) / "study.csv") << csv.str();
    std::cout << md.str() << "\nwrote " << fs::absolute(fs::path(out) / "study.md").string() << "\n";
  } catch (const std::exception& failure) {
    std::cerr << "vplkit_lightwave_study: error: " << failure.what() << "\n";
    return 1;
  }
  return 0;
}
