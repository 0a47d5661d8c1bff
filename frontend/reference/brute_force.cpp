#include "frontend/reference/brute_force.hpp"

#include <algorithm>
#include <cstddef>
#include <optional>

#include <vplkit/irradiance.hpp>
#include <vplkit/rsm_gather.hpp>
#include <vplkit/transform.hpp>

#include "frontend/core/error.hpp"
#include "frontend/core/parallel.hpp"
#include "frontend/techniques/rsm/rsm_cpu_mirror.hpp"

namespace vplkit {

using reference_work::scrambled_order;
using reference_work::time_sample;

namespace {

image empty_indirect(const rsm_frame_constants& constants) {
  image out;
  out.width = constants.indirect_size.x;
  out.height = constants.indirect_size.y;
  out.texels.assign(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height), glm::vec4(0.0f));
  return out;
}

// The ray that decides whether pixel light (q, nq) lights receiver (p, n): both ends lifted off
// their surfaces by a small offset along their normals, so that neither surface blocks its own
// end.
bool light_occluded(const ray_scene& rays, const glm::vec3& p, const glm::vec3& n, const glm::vec3& q, const glm::vec3& nq) {
  return rays.occluded(p + n * 1e-3f, q + nq * 1e-3f);
}

// The brute-force gather's pixel lights and per-receiver work, shared by the run and its estimate.
class brute_force_gather {
 public:
  brute_force_gather(const ray_scene& rays, const rsm_pass_buffers& buffers, const rsm_frame_constants& constants, const rsm_brute_force_options& options)
      : rays_(rays), buffers_(buffers), constants_(constants), options_(options), to_world_(glm::inverse(constants.light.view)) {
    if (options.receiver_stride < 1) throw error("brute-force RSM gather: receiver_stride must be >= 1");
    if (!(options.max_radius >= 0.0f)) throw error("brute-force RSM gather: max_radius must be >= 0");
    // Every lit RSM texel is a pixel light. Eq. 3.2 in the light's eye space, like the gather's
    // receivers; the occlusion rays in the world, each light's world position and normal computed once.
    const std::vector<rsm_texel<float>> rsm = unpack_rsm(buffers, constants);
    for (int y = 0; y < buffers.rsm.height; ++y)
      for (int x = 0; x < buffers.rsm.width; ++x) {
        const rsm_texel<float>& texel = rsm[static_cast<std::size_t>(y) * static_cast<std::size_t>(buffers.rsm.width) + static_cast<std::size_t>(x)];
        if (texel.position.z < 0.0f && texel.flux != glm::vec3(0.0f))
          lights_.push_back({texel.position, texel.normal, texel.flux, glm::vec2(x, y) + 0.5f, transform_point(to_world_, texel.position),
                             transform_direction(to_world_, texel.normal)});
      }
    columns_ = (constants.indirect_size.x + options.receiver_stride - 1) / options.receiver_stride;
    rows_ = (constants.indirect_size.y + options.receiver_stride - 1) / options.receiver_stride;
  }

  std::size_t light_count() const { return lights_.size(); }
  /// Receivers computed (every stride-th per axis), numbered row by row.
  std::uint64_t receiver_count() const { return static_cast<std::uint64_t>(columns_) * static_cast<std::uint64_t>(rows_); }
  glm::ivec2 texel_of(std::uint64_t receiver) const {
    return glm::ivec2(static_cast<int>(receiver % static_cast<std::uint64_t>(columns_)), static_cast<int>(receiver / static_cast<std::uint64_t>(columns_))) *
           options_.receiver_stride;
  }

  /// [irradiance | visible fraction] at the receiver of `texel`, nothing where there is none.
  std::optional<glm::vec4> gather(glm::ivec2 texel) const {
    const std::optional<gather_receiver<float>> receiver = gather_receiver_at(texel, buffers_, constants_);
    if (!receiver) return std::nullopt;
    const glm::vec3 p = receiver->position, n = receiver->normal;
    const glm::vec3 world_p = transform_point(to_world_, p), world_n = transform_direction(to_world_, n);
    const float radius_squared = options_.max_radius * options_.max_radius;
    glm::vec3 all(0.0f), seen(0.0f);
    for (const light_texel& light : lights_) {
      if (radius_squared > 0.0f) {
        const glm::vec2 d = light.texel_centre - receiver->rsm_coordinate;
        if (glm::dot(d, d) > radius_squared) continue;
      }
      const glm::vec3 e = pixel_light_irradiance(p, n, light.position, light.normal, light.flux, constants_.gather.irradiance);
      if (e == glm::vec3(0.0f)) continue;
      all += e;
      if (!options_.exact_visibility || !light_occluded(rays_, world_p, world_n, light.world_position, light.world_normal)) seen += e;
    }
    const float total = all.x + all.y + all.z;
    return glm::vec4(seen * 0.318309886183790671538f, total > 0.0f ? (seen.x + seen.y + seen.z) / total : 1.0f);
  }

 private:
  struct light_texel {
    glm::vec3 position, normal, flux;
    glm::vec2 texel_centre;
    glm::vec3 world_position, world_normal;
  };
  const ray_scene& rays_;
  const rsm_pass_buffers& buffers_;
  const rsm_frame_constants& constants_;
  rsm_brute_force_options options_;
  glm::mat4 to_world_;
  std::vector<light_texel> lights_;
  int columns_ = 0, rows_ = 0;
};

}  // namespace

image reference_rsm_gather(const ray_scene& rays, const rsm_pass_buffers& buffers, const rsm_frame_constants& constants,
                                  const rsm_brute_force_options& options, const progress_settings& progress_to) {
  const brute_force_gather gather(rays, buffers, constants, options);
  image out = empty_indirect(constants);
  progress_monitor progress(options.exact_visibility ? "brute-force RSM gather with visibility" : "brute-force RSM gather", gather.receiver_count(),
                            "receivers", progress_to);
  const int columns = (out.width + options.receiver_stride - 1) / options.receiver_stride;
  const int rows = (out.height + options.receiver_stride - 1) / options.receiver_stride;
  const scrambled_order order(static_cast<std::uint64_t>(rows));
  parallel_for(rows, options.threads, [&](int k) {
    const auto row = static_cast<int>(order(static_cast<std::uint64_t>(k)));
    for (int column = 0; column < columns && !progress.stopped(); ++column) {
      const glm::ivec2 texel = gather.texel_of(static_cast<std::uint64_t>(row) * static_cast<std::uint64_t>(columns) + static_cast<std::uint64_t>(column));
      if (const std::optional<glm::vec4> value = gather.gather(texel)) out.at(texel) = *value;
      progress.advance();
    }
  });
  progress.finish();
  return out;
}

reference_cost estimate_rsm_gather(const ray_scene& rays, const rsm_pass_buffers& buffers, const rsm_frame_constants& constants,
                                   const rsm_brute_force_options& options) {
  const brute_force_gather gather(rays, buffers, constants, options);
  reference_cost cost;
  cost.units = gather.receiver_count();
  cost.unit = "receivers";
  const double pairs = static_cast<double>(cost.units) * static_cast<double>(gather.light_count());
  cost.rays = options.exact_visibility ? pairs : 0.0;
  cost.what = count_text(static_cast<double>(cost.units)) + " receivers x " + count_text(static_cast<double>(gather.light_count())) + " lit RSM texels" +
              (options.exact_visibility ? ", a shadow ray per pair with light" : " (no rays: no visibility)");
  // A receiver costs a shadow ray per lit texel (a 512^2 RSM: up to 262144): a few are enough.
  const std::uint64_t sample = std::min<std::uint64_t>(cost.units, static_cast<std::uint64_t>(std::max(options.threads, 8)));
  if (sample == 0) return cost;
  const double seconds = time_sample(cost.units, sample, options.threads, [&](std::uint64_t receiver) { (void)gather.gather(gather.texel_of(receiver)); });
  cost.seconds = seconds * static_cast<double>(cost.units) / static_cast<double>(sample);
  return cost;
}

namespace {

// The visibility object of gather_rsm_with: a ray per sample, in the world (the gather's points
// are in the light's eye space).
// One object per receiver: its world position and normal are computed once, not per sample.
struct ray_cast_visibility {
  const ray_scene& rays;
  const glm::mat4& to_world;
  glm::vec3 receiver_position, receiver_normal;  ///< world space
  ray_cast_visibility(const ray_scene& scene_rays, const glm::mat4& light_to_world, const gather_receiver<float>& receiver)
      : rays(scene_rays),
        to_world(light_to_world),
        receiver_position(transform_point(light_to_world, receiver.position)),
        receiver_normal(transform_direction(light_to_world, receiver.normal)) {}
  void begin_path() {}
  float operator()(const gather_receiver<float>&, const rsm_texel<float>& light) const {
    return light_occluded(rays, receiver_position, receiver_normal, transform_point(to_world, light.position), transform_direction(to_world, light.normal))
               ? 0.0f
               : 1.0f;
  }
};

}  // namespace

image gather_with_ray_cast_visibility(const ray_scene& rays, const rsm_pass_buffers& buffers, const rsm_frame_constants& constants,
                                             int receiver_stride, int threads) {
  if (receiver_stride < 1) throw error("gather with ray-cast visibility: receiver_stride must be >= 1");
  image out = empty_indirect(constants);
  const std::vector<rsm_texel<float>> rsm = unpack_rsm(buffers, constants);
  const auto fetch = [&](glm::ivec2 texel) {
    return rsm[static_cast<std::size_t>(texel.y) * static_cast<std::size_t>(buffers.rsm.width) + static_cast<std::size_t>(texel.x)];
  };
  const glm::mat4 to_world = glm::inverse(constants.light.view);
  // The coverage's coarse lights as the frame gathered them (none without coverage).
  const std::vector<coarse_light<float>> coarse = coarse_lights_of(buffers);
  const int blocks = buffers.coarse[0].width;
  const auto coarse_fetch = [&](glm::ivec2 block) {
    return coarse[static_cast<std::size_t>(block.y) * static_cast<std::size_t>(blocks) + static_cast<std::size_t>(block.x)];
  };
  const auto gather = [&](const gather_receiver<float>& receiver) {
    ray_cast_visibility visibility(rays, to_world, receiver);
    if (constants.technique.pattern == rsm_pattern::disk)
      return coarse.empty() ? gather_rsm_with<rsm_pattern::disk>(receiver, fetch, constants.gather, visibility)
                            : gather_rsm_with<rsm_pattern::disk>(receiver, fetch, coarse_fetch, constants.gather, visibility);
    return coarse.empty() ? gather_rsm_with<rsm_pattern::radial>(receiver, fetch, constants.gather, visibility)
                          : gather_rsm_with<rsm_pattern::radial>(receiver, fetch, coarse_fetch, constants.gather, visibility);
  };
  const int rows = (out.height + receiver_stride - 1) / receiver_stride;
  parallel_for(rows, threads, [&](int row) {
    const int y = row * receiver_stride;
    for (int x = 0; x < out.width; x += receiver_stride) {
      const glm::ivec2 texel(x, y);
      const std::optional<gather_receiver<float>> receiver = gather_receiver_at(texel, buffers, constants);
      if (!receiver) continue;
      const glm::vec3 e = gather(*receiver);
      out.at(texel) = glm::vec4(e, buffers.gbuffer[0].at(gbuffer_texel_of(texel, constants)).w);
    }
  });
  return out;
}

std::vector<std::uint8_t> rsm_covered_receivers(const rsm_pass_buffers& buffers, const rsm_frame_constants& constants, int receiver_stride) {
  if (receiver_stride < 1) throw error("covered receivers: receiver_stride must be >= 1");
  std::vector<std::uint8_t> covered(static_cast<std::size_t>(constants.indirect_size.x) * static_cast<std::size_t>(constants.indirect_size.y), 0);
  for (int y = 0; y < constants.indirect_size.y; y += receiver_stride)
    for (int x = 0; x < constants.indirect_size.x; x += receiver_stride) {
      const std::optional<gather_receiver<float>> receiver = gather_receiver_at(glm::ivec2(x, y), buffers, constants);
      if (!receiver) continue;
      const glm::vec2 projection = receiver->rsm_coordinate;
      const bool in_front = receiver->position.z < 0.0f;  // light eye space
      const bool inside = projection.x >= 0.0f && projection.y >= 0.0f && projection.x < static_cast<float>(constants.gather.rsm_size.x) &&
                          projection.y < static_cast<float>(constants.gather.rsm_size.y);
      covered[static_cast<std::size_t>(y) * static_cast<std::size_t>(constants.indirect_size.x) + static_cast<std::size_t>(x)] = in_front && inside ? 1 : 0;
    }
  return covered;
}

image reference_rsm_gather(const ray_scene& rays, const rsm_pipeline& drawn, const rsm_brute_force_options& options, const progress_settings& progress) {
  image sum = reference_rsm_gather(rays, drawn.read_buffers(0), drawn.constants(0), options, progress);
  if (drawn.view_count() == 1) return sum;
  // The visible fraction of the sum weighs each light's by its unoccluded light (the brightness of
  // its irradiance over its own fraction); a receiver no light reaches keeps the largest fraction
  // a light gave it (1 where computed, 0 where the stride skipped it).
  std::vector<double> seen(sum.texels.size(), 0.0), unoccluded(sum.texels.size(), 0.0);
  std::vector<float> fallback(sum.texels.size(), 0.0f);
  const auto add = [&](const image& light, bool first) {
    for (std::size_t i = 0; i < light.texels.size(); ++i) {
      const glm::vec4 value = light.texels[i];
      if (!first) sum.texels[i] += glm::vec4(glm::vec3(value), 0.0f);
      const double brightness = static_cast<double>(value.x) + value.y + value.z;
      seen[i] += brightness;
      if (value.w > 0.0f) unoccluded[i] += brightness / value.w;
      fallback[i] = std::max(fallback[i], value.w);
    }
  };
  add(sum, true);
  for (std::size_t k = 1; k < drawn.view_count(); ++k) add(reference_rsm_gather(rays, drawn.read_buffers(k), drawn.constants(k), options, progress), false);
  for (std::size_t i = 0; i < sum.texels.size(); ++i)
    sum.texels[i].w = unoccluded[i] > 0.0 ? static_cast<float>(std::min(1.0, seen[i] / unoccluded[i])) : fallback[i];
  return sum;
}

reference_cost estimate_rsm_gather(const ray_scene& rays, const rsm_pipeline& drawn, const rsm_brute_force_options& options) {
  reference_cost total = estimate_rsm_gather(rays, drawn.read_buffers(0), drawn.constants(0), options);
  for (std::size_t k = 1; k < drawn.view_count(); ++k) {
    const reference_cost light = estimate_rsm_gather(rays, drawn.read_buffers(k), drawn.constants(k), options);
    total.rays += light.rays;
    total.seconds += light.seconds;
    total.units += light.units;
    total.what += "; light view " + std::to_string(k) + ": " + light.what;
  }
  return total;
}

std::vector<std::uint8_t> rsm_covered_receivers(const rsm_pipeline& drawn, int receiver_stride) {
  std::vector<std::uint8_t> covered = rsm_covered_receivers(drawn.read_buffers(0), drawn.constants(0), receiver_stride);
  for (std::size_t k = 1; k < drawn.view_count(); ++k) {
    const std::vector<std::uint8_t> light = rsm_covered_receivers(drawn.read_buffers(k), drawn.constants(k), receiver_stride);
    for (std::size_t i = 0; i < covered.size(); ++i) covered[i] = covered[i] | light[i];
  }
  return covered;
}

}  // namespace vplkit
