#include "bench/rsm_measure.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "frontend/core/error.hpp"
#include "frontend/core/files.hpp"
#include "frontend/image/image_files.hpp"
#include "frontend/techniques/rsm/rsm_cpu_mirror.hpp"

namespace vplkit {

namespace {

image blank(const frame_reference& reference) { return image(reference.constants.indirect_size.x, reference.constants.indirect_size.y); }

// The post pass's full-resolution filtered indirect light at the G-buffer texels of the indirect
// buffer's receivers.
image filtered_at_receivers(const rsm_frame& frame, const frame_reference& reference) {
  image out = blank(reference);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      const glm::ivec2 pixel = gbuffer_texel_of(glm::ivec2(x, y), reference.constants);
      out.at(x, y) = frame.indirect.at(pixel);
    }
  return out;
}

void accumulate(relative_error& sum, const relative_error& value, int seeds) {
  sum.rmse += value.rmse / seeds;
  sum.bias += value.bias / seeds;
  sum.pixels = value.pixels;
}

}  // namespace

std::string cache_key(const std::string& text) {
  std::uint64_t hash = 14695981039346656037ull;
  for (const char c : text) hash = (hash ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  std::ostringstream out;
  out << std::hex << std::setw(16) << std::setfill('0') << hash;
  return out.str();
}

frame_reference make_frame_reference(const shader_library& shaders, const scene& source, const rsm_pipeline_settings& settings, int stride,
                                     int threads, const std::string& cache) {
  frame_reference reference;
  reference.source = std::make_unique<scene>(source);
  reference.rays = std::make_unique<ray_scene>(reference.source->geometry);
  rsm_pipeline_settings frame_settings = settings;
  frame_settings.technique = "rsm-radial";
  rsm_pipeline pipeline(shaders, source, frame_settings);
  pipeline.render();
  reference.buffers = pipeline.read_buffers();
  reference.constants = pipeline.constants();
  reference.stride = stride;
  const std::string unoccluded_file = cache + "-unoccluded.pfm", exact_file = cache + "-exact.pfm";
  if (!cache.empty() && std::filesystem::exists(unoccluded_file) && std::filesystem::exists(exact_file)) {
    reference.unoccluded = read_image_file(unoccluded_file);
    reference.exact = read_image_file(exact_file);
    if (reference.unoccluded.width != reference.constants.indirect_size.x || reference.unoccluded.height != reference.constants.indirect_size.y ||
        reference.exact.width != reference.unoccluded.width || reference.exact.height != reference.unoccluded.height)
      throw error(cache + ": the cached brute force does not match the frame's indirect buffer; remove it");
  } else {
    rsm_brute_force_options options;
    options.receiver_stride = stride;
    options.threads = threads;
    reference.unoccluded = reference_rsm_gather(*reference.rays, reference.buffers, reference.constants, options);
    options.exact_visibility = true;
    reference.exact = reference_rsm_gather(*reference.rays, reference.buffers, reference.constants, options);
    if (!cache.empty())
      write_all_or_nothing({{unoccluded_file, [&] { return encode_pfm(reference.unoccluded); }}, {exact_file, [&] { return encode_pfm(reference.exact); }}});
  }
  reference.receivers = blank(reference);
  reference.covered = blank(reference);
  reference.uncovered = blank(reference);
  reference.leak = blank(reference);
  const std::vector<std::uint8_t> covered = rsm_covered_receivers(reference.buffers, reference.constants, stride);
  double all = 0.0, behind = 0.0, seen = 0.0, leak_all = 0.0, leak_seen = 0.0;
  for (int y = 0; y < reference.unoccluded.height; y += stride)
    for (int x = 0; x < reference.unoccluded.width; x += stride) {
      if (!gather_receiver_at(glm::ivec2(x, y), reference.buffers, reference.constants)) continue;  // no surface
      const std::size_t i = reference.unoccluded.index(x, y);
      const glm::vec3 u(reference.unoccluded.texels[i]), e(reference.exact.texels[i]);
      const double u_sum = u.x + u.y + u.z, e_sum = e.x + e.y + e.z;
      reference.receivers.texels[i] = glm::vec4(1.0f);
      ++reference.receiver_count;
      all += u_sum;
      seen += e_sum;
      if (covered[static_cast<std::size_t>(y) * static_cast<std::size_t>(reference.unoccluded.width) + static_cast<std::size_t>(x)]) {
        reference.covered.texels[i] = glm::vec4(1.0f);
        ++reference.covered_count;
      } else {
        reference.uncovered.texels[i] = glm::vec4(1.0f);
        behind += u_sum;
      }
      if (u_sum > 0.0 && e_sum <= 0.8 * u_sum) {
        reference.leak.texels[i] = glm::vec4(1.0f);
        ++reference.leak_count;
        leak_all += u_sum;
        leak_seen += e_sum;
      }
    }
  reference.uncovered_share = all > 0.0 ? behind / all : 0.0;
  reference.occluded_share = all > 0.0 ? 1.0 - seen / all : 0.0;
  reference.leak_occluded_share = leak_all > 0.0 ? 1.0 - leak_seen / leak_all : 0.0;
  return reference;
}

image brute_force_within(const frame_reference& reference, float radius, int threads) {
  rsm_brute_force_options options;
  options.receiver_stride = reference.stride;
  options.max_radius = radius;
  options.threads = threads;
  return reference_rsm_gather(*reference.rays, reference.buffers, reference.constants, options);
}

technique_errors measure_technique(const shader_library& shaders, const scene& source, const rsm_pipeline_settings& settings,
                                   const frame_reference& reference, int seeds) {
  if (seeds < 1) throw error("measure_technique: seeds must be >= 1");
  technique_errors errors;
  errors.mean_raw = blank(reference);
  errors.filtered_mean = blank(reference);
  errors.filtered_image = image(reference.constants.image_size.x, reference.constants.image_size.y);
  std::vector<image> raws;
  for (int seed = 1; seed <= seeds; ++seed) {
    rsm_pipeline_settings seeded = settings;
    seeded.radial.seed = static_cast<std::uint32_t>(seed);
    seeded.disk.seed = static_cast<std::uint32_t>(seed);
    rsm_pipeline pipeline(shaders, source, seeded);
    const rsm_frame frame = pipeline.render();
    // Direct light only has no indirect buffer: its indirect light is 0 everywhere.
    const image indirect = pipeline.read_buffers().indirect;
    const image raw = indirect.texels.empty() ? blank(reference) : indirect;
    const image filtered = filtered_at_receivers(frame, reference);
    accumulate(errors.raw_vs_unoccluded, relative_error_of(raw, reference.unoccluded, &reference.receivers), seeds);
    const relative_error vs_exact = relative_error_of(raw, reference.exact, &reference.receivers);
    accumulate(errors.raw_vs_exact, vs_exact, seeds);
    errors.raw_bias_min = seed == 1 ? vs_exact.bias : std::min(errors.raw_bias_min, vs_exact.bias);
    errors.raw_bias_max = seed == 1 ? vs_exact.bias : std::max(errors.raw_bias_max, vs_exact.bias);
    accumulate(errors.raw_covered_vs_unoccluded, relative_error_of(raw, reference.unoccluded, &reference.covered), seeds);
    accumulate(errors.raw_covered_vs_exact, relative_error_of(raw, reference.exact, &reference.covered), seeds);
    accumulate(errors.raw_uncovered_vs_unoccluded, relative_error_of(raw, reference.unoccluded, &reference.uncovered), seeds);
    accumulate(errors.raw_uncovered_vs_exact, relative_error_of(raw, reference.exact, &reference.uncovered), seeds);
    accumulate(errors.raw_leak, relative_error_of(raw, reference.exact, &reference.leak), seeds);
    accumulate(errors.filtered_vs_exact, relative_error_of(filtered, reference.exact, &reference.receivers), seeds);
    accumulate(errors.filtered_leak, relative_error_of(filtered, reference.exact, &reference.leak), seeds);
    for (std::size_t i = 0; i < raw.texels.size(); ++i) {
      errors.mean_raw.texels[i] += raw.texels[i] / static_cast<float>(seeds);
      errors.filtered_mean.texels[i] += filtered.texels[i] / static_cast<float>(seeds);
    }
    for (std::size_t i = 0; i < frame.indirect.texels.size(); ++i) errors.filtered_image.texels[i] += frame.indirect.texels[i] / static_cast<float>(seeds);
    raws.push_back(raw);
  }
  if (seeds > 1) {
    // E|x_i - mean|^2 = (n - 1) / n sigma^2: scale back to one seed's spread.
    double noise = 0.0;
    for (const image& raw : raws) noise += relative_error_of(raw, errors.mean_raw, &reference.receivers).rmse / seeds;
    errors.raw_noise = noise * std::sqrt(static_cast<double>(seeds) / (seeds - 1));
  }
  return errors;
}

image ray_cast_gather(const frame_reference& reference, const rsm_pipeline_settings& settings, int seeds, int threads) {
  image mean = blank(reference);
  for (int seed = 1; seed <= seeds; ++seed) {
    rsm_pipeline_settings seeded = settings;
    seeded.radial.seed = static_cast<std::uint32_t>(seed);
    seeded.disk.seed = static_cast<std::uint32_t>(seed);
    const rsm_frame_constants constants = make_frame_constants(*reference.source, seeded);
    const image gathered = gather_with_ray_cast_visibility(*reference.rays, reference.buffers, constants, reference.stride, threads);
    for (std::size_t i = 0; i < gathered.texels.size(); ++i) mean.texels[i] += gathered.texels[i] / static_cast<float>(seeds);
  }
  return mean;
}

std::vector<double> interleaved_frame_ms(const shader_library& shaders, const scene& source, const std::vector<rsm_pipeline_settings>& configurations,
                                         int repeat) {
  std::vector<std::unique_ptr<rsm_pipeline>> pipelines;
  for (const rsm_pipeline_settings& settings : configurations) {
    pipelines.push_back(std::make_unique<rsm_pipeline>(shaders, source, settings));
    pipelines.back()->draw_wall_clock_ms();  // warm-up: shader JIT
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

std::string fixed(double value, int digits) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(digits) << value;
  return out.str();
}

std::string percent(double fraction) { return fixed(100.0 * fraction, 1); }

std::string describe(const frame_reference& reference) {
  return std::to_string(reference.receiver_count) + " receivers counted, " + std::to_string(reference.receiver_count - reference.covered_count) +
         " of them behind the light or outside its frustum, where the pattern cannot reach (they hold " + percent(reference.uncovered_share) +
         " % of the unoccluded light), " + std::to_string(reference.leak_count) + " in the leak region. Exact visibility removes " +
         percent(reference.occluded_share) + " % of the light over the receivers, " + percent(reference.leak_occluded_share) +
         " % in the leak region.";
}

}  // namespace vplkit
