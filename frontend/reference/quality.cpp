#include "frontend/reference/quality.hpp"

#include <cstdint>

#include "frontend/core/error.hpp"
#include "frontend/core/parallel.hpp"
#include "frontend/image/metrics.hpp"
#include "frontend/techniques/final_gather/final_gather_pipeline.hpp"
#include "frontend/techniques/registry.hpp"

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
        const float radius = rsm_radius_in_texels(frame.radius, glm::ivec2(frame.rsm_size));
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
        scene_light light;
        light.spot = source.light;
        const image& positions = buffers.gbuffer[0];
        image reference(positions.width, positions.height), mask(positions.width, positions.height);
        const irradiance_settings<float> irradiance = gathering->settings().irradiance;
        parallel_for(static_cast<int>(positions.texels.size()), options_.threads, [&](int i) {
          const auto k = static_cast<std::size_t>(i);
          if (positions.texels[k].w < 1.5f) return;  // not the object
          const glm::vec3 p(positions.texels[k]), n(buffers.gbuffer[1].texels[k]);
          const glm::vec3 e =
              one_bounce_irradiance(room, light, irradiance, p + n * 1e-3f, n, options_.samples, options_.seed, static_cast<std::uint32_t>(i));
          reference.texels[k] = glm::vec4(e, 1.0f);
          mask.texels[k] = glm::vec4(1.0f);
        });
        const relative_error errors = relative_error_of(indirect, reference, &mask);
        quality.metrics = {rmse_metric("rel_rmse", errors), bias_metric("rel_bias", errors)};
        quality.receivers = errors.pixels;
        break;
      }
      const image radiance = drawn.output().read_image();
      const image_metrics m = compare_images(radiance, monte_carlo(radiance.width, radiance.height));
      quality.metrics = {rmse_metric("rel_rmse", m.relative), bias_metric("rel_bias", m.relative), plain_metric("similarity", m.similarity),
                         plain_metric("ssim", m.ssim)};
      quality.receivers = m.relative.pixels;
      break;
    }
    case reference_kind::base: {
      auto base = bases_.find(settings.reads("seed") ? settings.get("seed") : std::string());
      if (base == bases_.end()) base = bases_.begin();  // a frame without a seed, or a base without one
      if (base == bases_.end()) throw error("the base configuration's image was not rendered");
      const image radiance = stretched(drawn.output().read_image(), base->second.width, base->second.height);
      const image_metrics m = compare_images(radiance, base->second);
      quality.metrics = {rmse_metric("rel_rmse", m.relative), bias_metric("rel_bias", m.relative), plain_metric("similarity", m.similarity),
                         plain_metric("ssim", m.ssim)};
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
             "room's direct light (the room alone blocks the rays, as the cube map leaves the object out), over the object's pixels.";
    case reference_kind::base:
      return "Reference: the base configuration's final image (the sweep's settings without --vary) drawn with the frame's seed where it reads "
             "one, a smaller image stretched to its size (nearest texel, as [LW] Table 5.7); similarity: Alg. 1 of [LW] on 8-bit sRGB (%), the "
             "measure of [LW] Tables 5.5-5.9; rel_rmse, rel_bias over every pixel.";
  }
  return {};
}

}  // namespace vplkit
