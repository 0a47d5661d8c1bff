#include "frontend/reference/rsm_measure.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include <filesystem>

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
  reference.views = pipeline.view_count();
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
    reference.unoccluded = reference_rsm_gather(*reference.rays, pipeline, options);  // every light's, summed
    options.exact_visibility = true;
    reference.exact = reference_rsm_gather(*reference.rays, pipeline, options);
    if (!cache.empty())
      write_all_or_nothing({{unoccluded_file, [&] { return encode_pfm(reference.unoccluded); }}, {exact_file, [&] { return encode_pfm(reference.exact); }}});
  }
  reference.receivers = blank(reference);
  reference.covered = blank(reference);
  reference.uncovered = blank(reference);
  reference.leak = blank(reference);
  const std::vector<std::uint8_t> covered = rsm_covered_receivers(pipeline, stride);
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
      } else {
        reference.uncovered.texels[i] = glm::vec4(1.0f);
        ++reference.uncovered_count;
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

namespace {

// The radius and visibility splits run one view's RSM: with several they would compare the sum of
// every light's gather with one light's.
void require_one_view(const frame_reference& reference, const char* what) {
  if (reference.views > 1)
    throw error(std::string(what) + " measures one light view; scene " + reference.source->name + " has " + std::to_string(reference.views) +
                " (choose one spot or sun with --lights k)");
}

}  // namespace

image brute_force_within(const frame_reference& reference, float radius, int threads) {
  require_one_view(reference, "the radius split (brute force within the radius)");
  rsm_brute_force_options options;
  options.receiver_stride = reference.stride;
  options.max_radius = radius;
  options.threads = threads;
  return reference_rsm_gather(*reference.rays, reference.buffers, reference.constants, options);
}

frame_errors measure_frame(const rsm_pipeline& drawn, const frame_reference& reference) {
  frame_errors errors;
  // Direct light only has no indirect buffer: its indirect light is 0 everywhere.
  const std::optional<image> indirect = drawn.raw_indirect();
  errors.raw = indirect ? *indirect : blank(reference);
  rsm_frame frame;
  frame.indirect = drawn.indirect_output().read_image();
  errors.filtered = filtered_at_receivers(frame, reference);
  require_same_size(errors.raw, reference.exact, "the drawn frame's indirect buffer and the reference's");
  errors.raw_vs_unoccluded = relative_error_of(errors.raw, reference.unoccluded, &reference.receivers);
  errors.raw_vs_exact = relative_error_of(errors.raw, reference.exact, &reference.receivers);
  errors.raw_leak = relative_error_of(errors.raw, reference.exact, &reference.leak);
  errors.raw_covered_vs_exact = relative_error_of(errors.raw, reference.exact, &reference.covered);
  errors.raw_uncovered_vs_unoccluded = relative_error_of(errors.raw, reference.unoccluded, &reference.uncovered);
  errors.filtered_vs_exact = relative_error_of(errors.filtered, reference.exact, &reference.receivers);
  errors.filtered_leak = relative_error_of(errors.filtered, reference.exact, &reference.leak);
  return errors;
}

relative_error seed_noise(const std::vector<image>& raws, const frame_reference& reference) {
  relative_error noise;
  noise.defined = true;
  if (raws.size() < 2) return noise;
  const auto seeds = static_cast<double>(raws.size());
  image mean = blank(reference);
  for (const image& raw : raws)
    for (std::size_t i = 0; i < raw.texels.size(); ++i) mean.texels[i] += raw.texels[i] / static_cast<float>(seeds);
  // E|x_i - mean|^2 = (n - 1) / n sigma^2: scale back to one seed's spread.
  for (const image& raw : raws) {
    const relative_error one = relative_error_of(raw, mean, &reference.receivers);
    if (!one.defined) return one;  // the same mean for every seed: undefined for all
    noise.rmse += one.rmse / seeds;
    noise.pixels = one.pixels;
  }
  noise.rmse *= std::sqrt(seeds / (seeds - 1.0));
  return noise;
}

image ray_cast_gather(const frame_reference& reference, const rsm_pipeline_settings& settings, int threads) {
  require_one_view(reference, "the visibility split (the pattern with ray-cast visibility)");
  const rsm_frame_constants constants = make_frame_constants(*reference.source, settings);
  return gather_with_ray_cast_visibility(*reference.rays, reference.buffers, constants, reference.stride, threads);
}

namespace {

std::string percent(double fraction) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(1) << 100.0 * fraction;
  return out.str();
}

}  // namespace

std::string describe(const frame_reference& reference) {
  return std::to_string(reference.receiver_count) + " receivers counted, every one with a surface (" + std::to_string(reference.uncovered_count) +
         " of them behind the light or off the map, where the pattern cannot reach and the coverage lights them: they hold " +
         percent(reference.uncovered_share) + " % of the unoccluded light), " + std::to_string(reference.leak_count) + " in the leak region. Exact visibility removes " +
         percent(reference.occluded_share) + " % of the light over the receivers, " + percent(reference.leak_occluded_share) +
         " % in the leak region.";
}

}  // namespace vplkit
