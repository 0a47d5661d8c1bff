#include "frontend/reference/quality.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "frontend/core/error.hpp"
#include "frontend/core/parallel.hpp"
#include "frontend/image/metrics.hpp"
#include "frontend/image/reference_noise.hpp"
#include "frontend/techniques/final_gather/final_gather_pipeline.hpp"
#include "frontend/techniques/registry.hpp"
#include "frontend/techniques/rsm/rsm_settings.hpp"

namespace vplkit {

const char* reference_name(reference_kind kind) {
  switch (kind) {
    case reference_kind::none: return "none";
    case reference_kind::rsm_brute_force: return "rsm-brute-force";
    case reference_kind::monte_carlo: return "monte-carlo";
    case reference_kind::base: return "base";
  }
  return "";
}

reference_kind reference_from_name(const std::string& name) {
  for (reference_kind kind : {reference_kind::none, reference_kind::rsm_brute_force, reference_kind::monte_carlo, reference_kind::base})
    if (name == reference_name(kind)) return kind;
  throw error("unknown reference '" + name + "' (known: none, rsm-brute-force, monte-carlo, base)");
}

std::string reference_refusal(reference_kind kind, const std::string& technique) {
  if (kind == reference_kind::rsm_brute_force && family_of(technique).name != "rsm")
    return "the brute-force RSM gather is the reference of the RSM techniques (direct, rsm-*), not of " + technique;
  return {};
}

namespace {

// Nearest texel of `source` for every texel of a width x height image ([LW] Table 5.7 stretches
// the smaller renders to the default size).
image stretched(const image& source, int width, int height) {
  if (source.width == width && source.height == height) return source;
  image out(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) out.at(x, y) = source.at(std::min(source.width - 1, x * source.width / width), std::min(source.height - 1, y * source.height / height));
  return out;
}

const rsm_technique& rsm_technique_of(const technique_settings& settings) { return find_rsm_technique(settings.technique()); }

// A relative error's RMSE or bias as a named metric: undefined, with the reason, where the error is.
quality_metric rmse_metric(const std::string& name, const relative_error& error) { return {name, error.rmse, error.defined, error.why_undefined}; }
quality_metric bias_metric(const std::string& name, const relative_error& error) { return {name, error.bias, error.defined, error.why_undefined}; }
quality_metric plain_metric(const std::string& name, double value) { return {name, value, true, {}}; }
quality_metric higher_better_metric(const std::string& name, double value) {
  quality_metric metric = plain_metric(name, value);
  metric.higher_is_better = true;
  return metric;
}

// The reference's noise in the metrics measured against it (rel_rmse, rel_bias, and
// similarity and ssim when `second` is given), and the noise-corrected rel_rmse beside them: the
// image against the first reference is what the rows report; `variance` is the first's.
void add_reference_noise(frame_quality& quality, const reference_noise& noise, const image* candidate, const image* second) {
  if (!noise.defined) return;
  quality.reference_noise = noise.noise;
  for (quality_metric& metric : quality.metrics) {
    if (metric.name == "rel_rmse") metric.reference_se = noise.rmse_se;
    if (metric.name == "rel_bias") metric.reference_se = noise.bias_se;
  }
  if (candidate && second) {
    // Similarity and SSIM have no closed form in the variance: the spread of the two references'
    // values, |q1 - q2| / sqrt(2), estimates their standard error (one degree of freedom).
    const image_metrics other = compare_images(*candidate, *second);
    for (quality_metric& metric : quality.metrics) {
      if (metric.name == "similarity") metric.reference_se = std::fabs(metric.value - other.similarity) / std::sqrt(2.0);
      if (metric.name == "ssim") metric.reference_se = std::fabs(metric.value - other.ssim) / std::sqrt(2.0);
    }
  }
  const auto rmse = std::find_if(quality.metrics.begin(), quality.metrics.end(), [](const quality_metric& m) { return m.name == "rel_rmse"; });
  if (rmse == quality.metrics.end() || !rmse->defined) return;
  quality_metric corrected = plain_metric("rel_rmse_corrected", noise.rmse_corrected);
  corrected.reference_se = noise.rmse_se;
  quality.metrics.insert(rmse + 1, corrected);
}

}  // namespace

scene_references::scene_references(const shader_library& shaders, reference_options options, const scene* source)
    : shaders_(shaders), options_(options), source_(source) {}

scene_references::~scene_references() = default;

const frame_reference& scene_references::brute_force(const technique_settings& settings) {
  std::string key;
  // coverage-blocks too: the reference keeps the frame's coarse lights, C x C of them.
  for (const char* name : {"size", "rsm-size", "indirect-divisor", "format", "min-distance", "coverage-blocks"}) key += settings.get(name) + "|";
  std::unique_ptr<frame_reference>& cached = brute_forces_[key];
  if (!cached) {
    if (!source_) throw error("the brute-force RSM reference needs a scene");
    cached = std::make_unique<frame_reference>(
        make_frame_reference(shaders_, *source_, settings_struct<rsm_pipeline_settings, rsm_technique>(settings), options_.receiver_stride, options_.threads));
  }
  return *cached;
}

const image& scene_references::monte_carlo(int width, int height) {
  const std::string key = std::to_string(width) + "x" + std::to_string(height);
  const auto found = monte_carlo_.find(key);
  if (found != monte_carlo_.end()) return found->second;
  if (!source_) throw error("the Monte Carlo reference needs a scene");
  return monte_carlo_[key] = reference_one_bounce(*source_, width, height, options_.samples, options_.seed, options_.threads).radiance;
}

const image& scene_references::monte_carlo_second(int width, int height) {
  const std::string key = std::to_string(width) + "x" + std::to_string(height);
  const auto found = monte_carlo_second_.find(key);
  if (found != monte_carlo_second_.end()) return found->second;
  if (!source_) throw error("the Monte Carlo reference needs a scene");
  // Seed + 1: the per-pixel hashes of another seed, an estimate independent of the first. Twice
  // the reference's cost, once per frame size, for the noise in every row measured against it.
  return monte_carlo_second_[key] = reference_one_bounce(*source_, width, height, options_.samples, options_.seed + 1u, options_.threads).radiance;
}

frame_quality scene_references::measure(pipeline& drawn, const technique_settings& settings) {
  frame_quality quality;
  switch (options_.kind) {
    case reference_kind::none: break;
    case reference_kind::rsm_brute_force: {
      const frame_reference& reference = brute_force(settings);
      const rsm_pipeline& rsm = dynamic_cast<const rsm_pipeline&>(drawn);
      frame_errors errors = measure_frame(rsm, reference);
      quality.metrics = {rmse_metric("rel_rmse", errors.raw_vs_exact),          bias_metric("rel_bias", errors.raw_vs_exact),
                         bias_metric("rel_bias_unoccluded", errors.raw_vs_unoccluded), rmse_metric("leak_rmse", errors.raw_leak),
                         bias_metric("leak_bias", errors.raw_leak),             rmse_metric("filtered_rel_rmse", errors.filtered_vs_exact),
                         bias_metric("filtered_leak_bias", errors.filtered_leak)};
      const rsm_technique& technique = rsm_technique_of(settings);
      const rsm_pipeline_settings& frame = rsm.settings();
      if (technique.indirect) {
        const float radius = derive(frame).radial.max_radius;  // the frame's own radius in texels (rsm_settings)
        std::string key;
        for (const char* name : {"size", "rsm-size", "indirect-divisor", "format", "min-distance", "radius"}) key += settings.get(name) + "|";
        auto cut = radius_cuts_.find(key);
        if (cut == radius_cuts_.end()) cut = radius_cuts_.emplace(key, brute_force_within(reference, radius, options_.threads)).first;
        quality.metrics.push_back(bias_metric("radius_bias", relative_error_of(cut->second, reference.unoccluded, &reference.receivers)));
      }
      if (technique.visibility != rsm_visibility::none) {
        const image ray_cast = ray_cast_gather(reference, frame, options_.threads);
        quality.metrics.push_back(bias_metric("visibility_bias", relative_error_of(errors.raw, ray_cast, &reference.receivers)));
        quality.metrics.push_back(bias_metric("visibility_leak_bias", relative_error_of(errors.raw, ray_cast, &reference.leak)));
      }
      quality.receivers = reference.receiver_count;
      quality.raw = std::move(errors.raw);
      break;
    }
    case reference_kind::monte_carlo: {
      if (const auto* gathering = dynamic_cast<const final_gather_pipeline*>(&drawn)) {
        // The object's indirect irradiance against one bounce of the room's direct light: the
        // room alone blocks the bounce rays, as the cube map leaves the object out.
        const final_gather_buffers buffers = gathering->read_buffers();
        const image indirect = gathering->indirect_output().read_image();
        const final_gather_scene& source = gathering->source();
        const ray_scene room(source.room);
        const std::vector<scene_light>& lights = source.lights;  // every light the pipeline drew
        const image& positions = buffers.gbuffer[0];
        image reference(positions.width, positions.height), second(positions.width, positions.height), mask(positions.width, positions.height);
        const irradiance_settings<float> irradiance = gathering->settings().irradiance;
        parallel_for(static_cast<int>(positions.texels.size()), options_.threads, [&](int i) {
          const auto k = static_cast<std::size_t>(i);
          if (positions.texels[k].w < 1.5f) return;  // not the object
          const glm::vec3 p(positions.texels[k]), n(buffers.gbuffer[1].texels[k]);
          const glm::vec3 e =
              one_bounce_irradiance(room, lights, irradiance, p + n * 1e-3f, n, options_.samples, options_.seed, static_cast<std::uint32_t>(i));
          // A second, independent estimate (seed + 1) for the reference's noise.
          const glm::vec3 f =
              one_bounce_irradiance(room, lights, irradiance, p + n * 1e-3f, n, options_.samples, options_.seed + 1u, static_cast<std::uint32_t>(i));
          reference.texels[k] = glm::vec4(e, 1.0f);
          second.texels[k] = glm::vec4(f, 1.0f);
          mask.texels[k] = glm::vec4(1.0f);
        });
        const relative_error errors = relative_error_of(indirect, reference, &mask);
        quality.metrics = {rmse_metric("rel_rmse", errors), bias_metric("rel_bias", errors)};
        quality.receivers = errors.pixels;
        add_reference_noise(quality, reference_noise_of(indirect, reference, variance_of_two(reference, second), &mask), nullptr, nullptr);
        break;
      }
      const image radiance = drawn.output().read_image();
      const image& reference = monte_carlo(radiance.width, radiance.height);
      const image_metrics m = compare_images(radiance, reference);
      quality.metrics = {rmse_metric("rel_rmse", m.relative), bias_metric("rel_bias", m.relative), higher_better_metric("similarity", m.similarity),
                         higher_better_metric("ssim", m.ssim)};
      quality.receivers = m.relative.pixels;
      const image& second = monte_carlo_second(radiance.width, radiance.height);
      add_reference_noise(quality, reference_noise_of(radiance, reference, variance_of_two(reference, second)), &radiance, &second);
      break;
    }
    case reference_kind::base: {
      auto base = bases_.find(settings.reads("seed") ? settings.get("seed") : std::string());
      if (base == bases_.end()) base = bases_.begin();  // a frame without a seed, or a base without one
      if (base == bases_.end()) throw error("the base configuration's image was not rendered");
      const image radiance = stretched(drawn.output().read_image(), base->second.width, base->second.height);
      const image_metrics m = compare_images(radiance, base->second);
      quality.metrics = {rmse_metric("rel_rmse", m.relative), bias_metric("rel_bias", m.relative), higher_better_metric("similarity", m.similarity),
                         higher_better_metric("ssim", m.ssim)};
      quality.receivers = m.relative.pixels;
      break;
    }
  }
  last_receivers_ = quality.receivers;
  return quality;
}

quality_metric scene_references::seed_noise(const std::vector<image>& raws, const technique_settings& settings) {
  if (options_.kind != reference_kind::rsm_brute_force || raws.size() < 2) return plain_metric("seed_noise", 0.0);
  return rmse_metric("seed_noise", vplkit::seed_noise(raws, brute_force(settings)));
}

std::string scene_references::coverage() const {
  switch (options_.kind) {
    case reference_kind::none: return "No reference: no quality numbers.";
    case reference_kind::rsm_brute_force: {
      std::string text =
          "Reference: the brute-force gather of every lit RSM texel of the same RSM and G-buffer with exact (ray-cast) visibility ([RSMV] "
          "Fig. 5.1d), at every " + std::to_string(options_.receiver_stride) +
          "th receiver of the indirect buffer per axis that the gather covers (in front of the light, inside its frustum). rel_rmse = RMSE / "
          "reference mean and rel_bias = (mean - reference mean) / reference mean, over the three channels of those receivers, of the raw gather "
          "(before the post filter); rel_bias_unoccluded: against the brute force without visibility; leak_rmse, leak_bias: over the leak "
          "region (receivers where exact visibility removes >= 20 %); filtered_*: after the bilateral post filter at the same receivers; "
          "radius_bias: the brute force within the sampling radius against all texels (the light the radius misses); visibility_bias: the "
          "gather against its own samples ray cast (what Alg. 2/3/6 get wrong), visibility_leak_bias the same over the leak region; noise: one "
          "seed's raw gather against the mean of the seeds.";
      for (const auto& [key, reference] : brute_forces_) text += " Frame " + key.substr(0, key.find('|')) + ": " + describe(*reference);
      return text;
    }
    case reference_kind::monte_carlo:
      return "Reference: the one-bounce Monte Carlo image (Embree path tracing of direct light plus one diffuse bounce, " + std::to_string(options_.samples) +
             " bounce rays per pixel, seed " + std::to_string(options_.seed) +
             ") of the same scene, camera and size; rel_rmse, rel_bias of the final image over every pixel and its three channels; similarity: "
             "Alg. 1 of [LW] on 8-bit sRGB (%); ssim on luminance. Final gathering: the object's indirect irradiance against one bounce of the "
             "room's direct light (the room alone blocks the rays, as the cube map leaves the object out), over the object's pixels. The "
             "reference is an estimate: a second one of seed " + std::to_string(options_.seed + 1u) +
             " gives its per-pixel variance, from which come each number's _ref_se (the standard error the reference's noise causes), "
             "ref_noise (the reference's own noise as a rel_rmse: what a perfect image scores), rel_rmse_corrected (sqrt(rel_rmse^2 - "
             "ref_noise^2)) and ref_noise_share (ref_noise / rel_rmse).";
    case reference_kind::base:
      return "Reference: the base configuration's final image (the sweep's settings without --vary) drawn with the frame's seed where it reads "
             "one, a smaller image stretched to its size (nearest texel, as [LW] Table 5.7); similarity: Alg. 1 of [LW] on 8-bit sRGB (%), the "
             "measure of [LW] Tables 5.5-5.9; rel_rmse, rel_bias over every pixel.";
  }
  return {};
}

}  // namespace vplkit
