// Frame-level sweep of the RSM pipeline on the current GL implementation (OSMesa/llvmpipe),
// in the structure of [RSMV]'s Tables 5.1-5.3, plus a parameter sweep, the full against the
// separable post filter, and the CPU gather (the C++ mirror, all cores) against the GL gather.
// Pass times come from the pass timer (frontend/gl/pass_timer.hpp: GL timer queries on a GPU,
// wall clock around glFinish per pass on a software renderer), median of --repeat frames after a
// warm-up frame.
//   build/bench/vplkit_rsm_sweep [--scene atrium] [--size 512] [--rsm-size 512] [--repeat 3]
//                                [--quick] [--out output/bench]
// Writes rsm_sweep.csv and rsm_sweep.md into --out and prints the markdown.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "frontend/gl/pass_timer.hpp"
#include "frontend/gl/context.hpp"
#include "frontend/core/error.hpp"
#include "frontend/scene/obj_loader.hpp"
#include "frontend/techniques/rsm/rsm_cpu_mirror.hpp"
#include "frontend/techniques/rsm/rsm_pipeline.hpp"

namespace fs = std::filesystem;
using namespace vplkit;

namespace {

struct measurement {
  std::string technique;
  int width = 0, height = 0, rsm = 0, indirect_divisor = 2, paths = 0, samples = 0, slots = 0;
  std::string filter;
  std::map<std::string, double> pass_ms;  // median per pass
  double total_ms = 0.0;
};

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values.empty() ? 0.0 : values[values.size() / 2];
}

struct sweep {
  const shader_library& shaders;
  const scene& source;
  int repeat;

  measurement run(const rsm_pipeline_settings& settings) const { return run_interleaved({settings}).front(); }

  // Renders the configurations in turn, frame by frame (A B C A B C ...), so that they share
  // whatever else the machine is doing: their ratios are the numbers to quote.
  std::vector<measurement> run_interleaved(const std::vector<rsm_pipeline_settings>& configurations) const {
    std::vector<std::unique_ptr<rsm_pipeline>> pipelines;
    for (const rsm_pipeline_settings& settings : configurations) {
      pipelines.push_back(std::make_unique<rsm_pipeline>(shaders, source, settings));
      pipelines.back()->render();  // warm-up: shader JIT
    }
    std::vector<std::map<std::string, std::vector<double>>> samples(configurations.size());
    std::vector<std::vector<double>> totals(configurations.size());
    for (int i = 0; i < repeat; ++i) {
      for (std::size_t c = 0; c < pipelines.size(); ++c) {
        const rsm_frame frame = pipelines[c]->render();
        double total = 0.0;
        for (const pass_time& time : frame.pass_times) {
          samples[c][time.pass].push_back(time.milliseconds);
          total += time.milliseconds;
        }
        totals[c].push_back(total);
      }
    }
    std::vector<measurement> results;
    for (std::size_t c = 0; c < configurations.size(); ++c) results.push_back(summarise(configurations[c], samples[c], totals[c]));
    return results;
  }

  measurement summarise(const rsm_pipeline_settings& settings, const std::map<std::string, std::vector<double>>& samples,
                        const std::vector<double>& totals) const {
    measurement m;
    m.technique = settings.technique;
    m.width = settings.width;
    m.height = settings.height;
    m.rsm = settings.rsm_size;
    m.indirect_divisor = settings.indirect_divisor;
    m.paths = settings.radial.paths;
    m.samples = settings.radial.samples_per_path;
    m.slots = settings.slots;
    m.filter = settings.filter == post_filter::full ? "full" : "separable";
    for (const auto& [pass, values] : samples) m.pass_ms[pass] = median(values);
    m.total_ms = median(totals);
    std::cerr << "  " << m.technique << " " << m.width << "x" << m.height << "/" << m.indirect_divisor << " " << m.paths << "x"
              << m.samples << " slots " << m.slots << " " << m.filter << ": " << std::fixed << std::setprecision(1) << m.total_ms
              << " ms\n";
    return m;
  }
};

std::string fixed(double value, int digits = 2) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(digits) << value;
  return out.str();
}

double pass(const measurement& m, const std::string& name) {
  const auto found = m.pass_ms.find(name);
  return found == m.pass_ms.end() ? 0.0 : found->second;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"RSM pipeline sweep ([RSMV], Tables 5.1-5.3)"};
  std::string scene_name = "atrium", out = "output/bench";
  int size = 512, rsm_size = 512, repeat = 3;
  bool quick = false;
  app.add_option("--scene", scene_name, "built-in scene or .obj file")->capture_default_str();
  app.add_option("--size", size, "final image side (the thesis: 512)")->check(CLI::Range(16, 4096))->capture_default_str();
  app.add_option("--rsm-size", rsm_size, "RSM side (the thesis: 512)")->check(CLI::Range(16, 4096))->capture_default_str();
  app.add_option("--repeat", repeat, "timed frames per configuration (median)")->check(CLI::Range(1, 100))->capture_default_str();
  app.add_flag("--quick", quick, "a smaller parameter sweep");
  app.add_option("--out", out, "folder for rsm_sweep.csv and rsm_sweep.md")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  try {
    auto context = create_headless_context();
    const shader_library shaders(default_shader_dir());
    const scene source = fs::path(scene_name).extension() == ".obj" ? frame_mesh(fs::path(scene_name).stem().string(), load_obj(scene_name))
                                                                    : built_in_scene(scene_name);
    const sweep runner{shaders, source, repeat};
    rsm_pipeline_settings base;
    base.width = base.height = size;
    base.rsm_size = rsm_size;
    base.filter = post_filter::separable;
    std::vector<measurement> rows;
    std::ostringstream md;
    md << "# RSM pipeline sweep\n\nScene " << source.name << " (" << source.geometry.triangle_count() << " triangles), "
       << size << "x" << size << " image, " << rsm_size << "x" << rsm_size << " RSM, median of " << repeat
       << " frames (configurations compared in one table are rendered interleaved), " << describe(timing_method_for_current_context()) << ", on:\n\n```\n" << describe_current_context() << "\n```\n\n";

    // Table 5.1: with and without visibility (and the original RSM), thesis configuration.
    std::cerr << "Table 5.1 / 5.3\n";
    md << "## With and without visibility (Table 5.1), indirect " << size / 2 << "^2\n\n| technique | total ms | RSM sampling ms | vs rsm-radial |\n|---|---:|---:|---:|\n";
    std::map<std::string, measurement> by_technique;
    const std::vector<const char*> table_techniques = {"rsm-radial", "rsm-alg3", "rsm-alg6", "rsm-original", "direct"};
    std::vector<rsm_pipeline_settings> table_settings;
    for (const char* technique : table_techniques) {
      table_settings.push_back(base);
      table_settings.back().technique = technique;
    }
    const std::vector<measurement> table = runner.run_interleaved(table_settings);
    for (std::size_t i = 0; i < table.size(); ++i) {
      by_technique[table_techniques[i]] = table[i];
      rows.push_back(table[i]);
    }
    for (const char* technique : {"rsm-radial", "rsm-alg3", "rsm-alg6", "rsm-original", "direct"}) {
      const measurement& m = by_technique[technique];
      md << "| " << technique << " | " << fixed(m.total_ms) << " | " << fixed(pass(m, "RSM sampling")) << " | "
         << fixed(m.total_ms / by_technique["rsm-radial"].total_ms, 3) << "x |\n";
    }
    const double overhead = by_technique["rsm-alg6"].total_ms / by_technique["rsm-radial"].total_ms;
    const double sampling_overhead = pass(by_technique["rsm-alg6"], "RSM sampling") / pass(by_technique["rsm-radial"], "RSM sampling");
    md << "\nVisibility overhead (Alg. 6 / no visibility, same 150 samples): frame " << fixed(overhead, 3) << "x, RSM sampling pass "
       << fixed(sampling_overhead, 3) << "x (the thesis: 1.13-1.14x per frame).\n\n";

    // Table 5.3: the per-pass split of the Alg. 6 frame.
    const measurement& alg6 = by_technique["rsm-alg6"];
    md << "## Per-pass split (Table 5.3), rsm-alg6, separable post filter\n\n| pass | ms | % | the thesis's % |\n|---|---:|---:|---:|\n";
    const std::map<std::string, std::string> thesis = {
        {"RSM generation", "5.7"}, {"G-buffer generation", "6.9"}, {"RSM sampling", "60.7"}, {"post processing", "26.7"}};
    for (const char* name : {"RSM generation", "G-buffer generation", "RSM sampling", "post processing"})
      md << "| " << name << " | " << fixed(pass(alg6, name)) << " | " << fixed(100.0 * pass(alg6, name) / alg6.total_ms, 1) << " | "
         << thesis.at(name) << " |\n";
    md << "| total | " << fixed(alg6.total_ms) << " | 100.0 | 100.0 |\n\n";

    // Full against separable post filter: time and the difference of the images.
    std::cerr << "post filter\n";
    {
      rsm_pipeline_settings full = base;
      full.filter = post_filter::full;
      const measurement full_time = runner.run(full);
      rows.push_back(full_time);
      rsm_pipeline full_pipeline(shaders, source, full);
      const rsm_frame full_frame = full_pipeline.render();
      rsm_pipeline separable_pipeline(shaders, source, base);
      const rsm_frame separable_frame = separable_pipeline.render();
      double difference = 0.0, level = 0.0, worst = 0.0;
      for (std::size_t i = 0; i < full_frame.indirect.texels.size(); ++i) {
        const glm::vec3 full_indirect(full_frame.indirect.texels[i]), separable_indirect(separable_frame.indirect.texels[i]);
        const glm::vec3 absolute = glm::abs(full_indirect - separable_indirect);
        const double d = static_cast<double>(absolute.r) + absolute.g + absolute.b;
        difference += d;
        worst = std::max(worst, d);
        level += static_cast<double>(full_indirect.r) + full_indirect.g + full_indirect.b;
      }
      md << "## Post filter: full 17x17 against separable 2 x 17 (indirect " << size / 2 << "^2)\n\n| filter | post ms | % of frame |\n|---|---:|---:|\n"
         << "| full | " << fixed(pass(full_time, "post processing")) << " | " << fixed(100.0 * pass(full_time, "post processing") / full_time.total_ms, 1) << " |\n"
         << "| separable | " << fixed(pass(alg6, "post processing")) << " | " << fixed(100.0 * pass(alg6, "post processing") / alg6.total_ms, 1) << " |\n\n"
         << "Filtered indirect irradiance, separable against full: mean absolute difference " << fixed(100.0 * difference / std::max(level, 1e-30), 2)
         << "% of the mean level, worst pixel " << fixed(worst, 4) << " (sum over RGB).\n\n";
    }

    // Table 5.2: indirect resolution, with and without visibility.
    std::cerr << "Table 5.2\n";
    md << "## Indirect resolution (Table 5.2)\n\n| visibility | indirect | total ms | RSM sampling ms |\n|---|---|---:|---:|\n";
    for (int divisor : {2, 1})
      for (const char* technique : {"rsm-radial", "rsm-alg6"}) {
        rsm_pipeline_settings settings = base;
        settings.technique = technique;
        settings.indirect_divisor = divisor;
        const measurement m = divisor == 2 ? by_technique[technique] : runner.run(settings);
        if (divisor == 1) rows.push_back(m);
        md << "| " << (std::string(technique) == "rsm-alg6" ? "yes" : "no") << " | " << size / divisor << "^2 | " << fixed(m.total_ms) << " | "
           << fixed(pass(m, "RSM sampling")) << " |\n";
      }
    md << "\n";

    // The parameter sweep: paths x samples per path x slots (rsm-alg6).
    std::cerr << "paths x samples x slots\n";
    md << "## Paths x samples per path x slots (rsm-alg6)\n\n| paths | samples | slots | total ms | RSM sampling ms | sampling ns / sample / pixel |\n|---:|---:|---:|---:|---:|---:|\n";
    const std::vector<int> paths = quick ? std::vector<int>{5, 15} : std::vector<int>{5, 10, 15, 20};
    const std::vector<int> samples = quick ? std::vector<int>{5, 10} : std::vector<int>{5, 10, 20};
    const std::vector<int> slots = quick ? std::vector<int>{5} : std::vector<int>{3, 5, 8};
    const double receivers = static_cast<double>(size / 2) * (size / 2);
    for (int p : paths)
      for (int s : samples)
        for (int b : slots) {
          rsm_pipeline_settings settings = base;
          settings.radial.paths = p;
          settings.radial.samples_per_path = s;
          settings.slots = b;
          const measurement m = runner.run(settings);
          rows.push_back(m);
          md << "| " << p << " | " << s << " | " << b << " | " << fixed(m.total_ms) << " | " << fixed(pass(m, "RSM sampling")) << " | "
             << fixed(1e6 * pass(m, "RSM sampling") / (receivers * p * s), 2) << " |\n";
        }
    md << "\n";

    // The CPU gather (C++ mirror, all cores) against the GL gather on the same frame.
    std::cerr << "CPU gather\n";
    md << "## CPU gather (C++ mirror, " << hardware_threads() << " threads) against the GL gather, same frame\n\n"
       << "| technique | GL ms | CPU ms | GL Msamples/s | CPU Msamples/s | CPU / GL |\n|---|---:|---:|---:|---:|---:|\n";
    // GL gather and CPU gather of the same frame, alternating, for each technique in turn.
    std::map<std::string, double> cpu_ms;
    for (const char* technique : {"rsm-radial", "rsm-alg6"}) {
      rsm_pipeline_settings settings = base;
      settings.technique = technique;
      rsm_pipeline pipeline(shaders, source, settings);
      pipeline.render();
      const rsm_pass_buffers buffers = pipeline.read_buffers();
      std::size_t occupied = 0;
      for (const glm::vec4& texel : buffers.indirect.texels) occupied += texel.w < 0.0f;
      std::vector<double> cpu_times, gl_times;
      for (int i = 0; i < repeat; ++i) {
        for (const pass_time& time : pipeline.render().pass_times)
          if (time.pass == "RSM sampling") gl_times.push_back(time.milliseconds);
        const auto start = std::chrono::steady_clock::now();
        const image gathered = cpu_gather_pass(buffers, pipeline.constants(), hardware_threads());
        cpu_times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        if (gathered.texels.size() != buffers.indirect.texels.size()) throw error("CPU gather: wrong size");
      }
      cpu_ms[technique] = median(cpu_times);
      const double gl_ms = median(gl_times);
      const double sample_count = static_cast<double>(occupied) * settings.radial.paths * settings.radial.samples_per_path;
      md << "| " << technique << " | " << fixed(gl_ms) << " | " << fixed(cpu_ms[technique]) << " | " << fixed(sample_count / gl_ms / 1e3, 1)
         << " | " << fixed(sample_count / cpu_ms[technique] / 1e3, 1) << " | " << fixed(gl_ms / cpu_ms[technique], 2) << "x |\n";
    }
    md << "\nVisibility overhead of the CPU gather (Alg. 6 / no visibility): " << fixed(cpu_ms["rsm-alg6"] / cpu_ms["rsm-radial"], 3) << "x.\n";

    fs::create_directories(out);
    std::ofstream csv(fs::path(out) / "rsm_sweep.csv");
    csv << "scene,technique,width,height,rsm,indirect_divisor,paths,samples_per_path,slots,filter,rsm_ms,gbuffer_ms,sampling_ms,post_ms,total_ms\n";
    for (const measurement& m : rows)
      csv << source.name << "," << m.technique << "," << m.width << "," << m.height << "," << m.rsm << "," << m.indirect_divisor << "," << m.paths
          << "," << m.samples << "," << m.slots << "," << m.filter << "," << pass(m, "RSM generation") << "," << pass(m, "G-buffer generation")
          << "," << pass(m, "RSM sampling") << "," << pass(m, "post processing") << "," << m.total_ms << "\n";
    std::ofstream(fs::path(out) / "rsm_sweep.md") << md.str();
    if (!csv) throw error("cannot write " + (fs::path(out) / "rsm_sweep.csv").string());
    std::cout << md.str() << "\nwrote " << fs::absolute(fs::path(out) / "rsm_sweep.csv").string() << " and rsm_sweep.md\n";
  } catch (const std::exception& failure) {
    std::cerr << "vplkit_rsm_sweep: error: " << failure.what() << "\n";
    return 1;
  }
  return 0;
}
