// Final gathering ([FG]) on the current GL implementation: ms per frame for M = 2 and 4,
// each variant (polygon-to-point, point-to-point, environment map), sphere against bunny. The
// paper's figure to compare with: 150 FPS point-to-point against 32 FPS polygon-to-point (a
// sphere of ~2300 faces, 700 x 700, GeForce 7950 GX2): polygon 4.7x the cost of point.
// Times: the wall clock of a whole frame (every pass, read-back included) and the shading pass
// from the pass timer (frontend/gl/pass_timer.hpp: timer queries on a GPU, wall clock around
// glFinish on a software renderer), medians of --repeat frames.
//   build/bench/vplkit_finalgather_sweep [--size 256] [--repeat 5] [--out output/bench]
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "frontend/gl/pass_timer.hpp"
#include "frontend/gl/context.hpp"
#include "frontend/core/error.hpp"
#include "frontend/techniques/final_gather/final_gather_pipeline.hpp"

namespace fs = std::filesystem;
using namespace vplkit;

int main(int argc, char** argv) {
  CLI::App app{"final gathering sweep ([FG])"};
  int size = 256, repeat = 5;
  std::string out = "output/bench", bunny = "meshes/bunny.obj";
  app.add_option("--size", size, "image side (the paper: 700)")->check(CLI::Range(16, 2048))->capture_default_str();
  app.add_option("--repeat", repeat, "timed frames per configuration")->check(CLI::Range(1, 50))->capture_default_str();
  app.add_option("--bunny", bunny, "the bunny OBJ (scripts/setup.sh makes it)")->capture_default_str();
  app.add_option("--out", out, "folder for finalgather_sweep.csv and .md")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    auto context = create_headless_context();
    const shader_library shaders(default_shader_dir());
    std::ostringstream md, csv;
    md << "# Final gathering sweep\n\n" << size << "x" << size << ", cube faces 256^2, medians of " << repeat << " frames; frame ms by wall clock, shading ms by "
       << describe(timing_method_for_current_context()) << ", on:\n\n```\n"
       << describe_current_context() << "\n```\n\n| object | triangles | M | technique | frame ms | shading ms | shading vs point |\n|---|---:|---:|---|---:|---:|---:|\n";
    csv << "object,triangles,resolution,technique,frame_ms,shading_ms\n";
    std::vector<std::string> objects = {"sphere"};
    if (fs::exists(bunny)) objects.push_back(bunny);
    else std::cerr << "skipping the bunny: " << bunny << " is missing (scripts/setup.sh makes it)\n";
    for (const std::string& object : objects) {
      const final_gather_scene scene = make_final_gather_scene(object, glm::vec3(0.0f, 0.7f, 0.0f), 0.6f);
      for (int resolution : {4, 2}) {
        double point_shading = 0.0;
        for (const char* technique : {"finalgather-point", "finalgather-polygon", "envmap"}) {
          final_gather_settings settings;
          settings.technique = technique;
          settings.width = settings.height = size;
          settings.resolution = resolution;
          final_gather_pipeline pipeline(shaders, scene, settings);
          pipeline.render();  // warm-up: shader JIT
          std::vector<double> frames, shading;
          for (int i = 0; i < repeat; ++i) {
            const auto start = std::chrono::steady_clock::now();
            const final_gather_frame frame = pipeline.render();
            frames.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
            for (const pass_time& time : frame.pass_times)
              if (time.pass == "shading") shading.push_back(time.milliseconds);
          }
          std::sort(frames.begin(), frames.end());
          std::sort(shading.begin(), shading.end());
          const double frame_ms = frames[frames.size() / 2], shading_ms = shading[shading.size() / 2];
          if (std::string(technique) == "finalgather-point") point_shading = shading_ms;
          md << "| " << scene.name << " | " << scene.object.triangle_count() << " | " << resolution << " | " << technique << " | " << std::fixed
             << std::setprecision(2) << frame_ms << " | " << shading_ms << " | " << std::setprecision(2) << shading_ms / point_shading << "x |\n";
          csv << scene.name << "," << scene.object.triangle_count() << "," << resolution << "," << technique << "," << frame_ms << "," << shading_ms << "\n";
          std::cerr << "  " << scene.name << " M=" << resolution << " " << technique << ": " << frame_ms << " ms\n";
        }
      }
    }
    md << "\nThe paper: point-to-point 150 FPS, polygon-to-point 32 FPS (polygon 4.7x the cost of point).\n";
    fs::create_directories(out);
    std::ofstream(fs::path(out) / "finalgather_sweep.csv") << csv.str();
    std::ofstream(fs::path(out) / "finalgather_sweep.md") << md.str();
    std::cout << md.str() << "\nwrote " << fs::absolute(fs::path(out) / "finalgather_sweep.csv").string() << " and finalgather_sweep.md\n";
  } catch (const std::exception& failure) {
    std::cerr << "vplkit_finalgather_sweep: error: " << failure.what() << "\n";
    return 1;
  }
  return 0;
}
