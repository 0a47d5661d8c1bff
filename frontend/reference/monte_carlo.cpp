#include "frontend/reference/monte_carlo.hpp"

#include <vplkit/shading.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <optional>

#include <vplkit/direct_light.hpp>
#include <vplkit/hash.hpp>
#include <vplkit/irradiance.hpp>

#include "frontend/core/error.hpp"
#include "frontend/core/parallel.hpp"

namespace vplkit {

using reference_work::scrambled_order;
using reference_work::time_sample;

glm::vec3 direct_irradiance(const ray_scene& rays, const scene_light& light, const irradiance_settings<float>& irradiance, const glm::vec3& x,
                            const glm::vec3& n) {
  if (light.kind == light_kind::spot) {
    const glm::vec3 e = spot_light_irradiance(x, n, light.spot, irradiance);
    if (e == glm::vec3(0.0f)) return e;
    return rays.occluded(x + n * 1e-4f, light.spot.position) ? glm::vec3(0.0f) : e;
  }
  if (light.kind == light_kind::point) {
    const glm::vec3 e = point_light_irradiance(x, n, light.point, irradiance);
    if (e == glm::vec3(0.0f)) return e;
    return rays.occluded(x + n * 1e-4f, light.point.position) ? glm::vec3(0.0f) : e;
  }
  const glm::vec3 e = directional_light_irradiance(n, light.directional);
  if (e == glm::vec3(0.0f)) return e;
  return rays.occluded(x + n * 1e-4f, x - light.directional.direction * 100.0f) ? glm::vec3(0.0f) : e;
}

glm::vec3 direct_irradiance(const ray_scene& rays, const std::vector<scene_light>& lights, const irradiance_settings<float>& irradiance,
                            const glm::vec3& x, const glm::vec3& n) {
  glm::vec3 sum(0.0f);
  for (const scene_light& light : lights) sum += direct_irradiance(rays, light, irradiance, x, n);
  return sum;
}

glm::vec3 one_bounce_irradiance(const ray_scene& rays, const std::vector<scene_light>& lights, const irradiance_settings<float>& irradiance, const glm::vec3& x,
                                const glm::vec3& n, int samples, std::uint32_t seed, std::uint32_t key) {
  return one_bounce_irradiance(rays, rays, lights, irradiance, x, n, samples, seed, key);
}

glm::vec3 one_bounce_irradiance(const ray_scene& bounce_rays, const ray_scene& light_rays, const std::vector<scene_light>& lights,
                                const irradiance_settings<float>& irradiance, const glm::vec3& x, const glm::vec3& n, int samples,
                                std::uint32_t seed, std::uint32_t key) {
  // Cosine-weighted directions about n: the estimator of the irradiance integral is pi times the
  // mean of the radiances found.
  const glm::vec3 helper = std::abs(n.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  const glm::vec3 u = glm::normalize(glm::cross(helper, n)), v = glm::cross(n, u);
  glm::vec3 sum(0.0f);
  const std::uint32_t base = hash_combine(seed, key);
  for (int s = 0; s < samples; ++s) {
    const std::uint32_t h = hash_combine(base, static_cast<std::uint32_t>(s));
    const float r1 = uniform_float_from_bits(h), r2 = uniform_float_from_bits(hash_uint32(h));
    const float radius = std::sqrt(r1), angle = 6.28318530717958647692f * r2;
    const glm::vec3 direction = glm::normalize(u * (radius * std::cos(angle)) + v * (radius * std::sin(angle)) + n * std::sqrt(std::max(0.0f, 1.0f - r1)));
    const ray_scene::hit y = bounce_rays.intersect(x + n * 1e-4f, direction);
    if (!y.found || glm::dot(y.normal, direction) >= 0.0f) continue;  // nothing, or the back of a surface
    sum += diffuse_radiance(y.albedo, direct_irradiance(light_rays, lights, irradiance, y.position, y.normal), 1.0f, glm::vec3(0.0f));
  }
  return sum * (3.14159265358979323846f / static_cast<float>(std::max(samples, 1)));
}

namespace {

// GL's texture level of detail at a camera ray's hit: where the rays through the next pixel to the
// right and the next one down meet the hit triangle's plane, in texels of texture `index` of the
// mesh's materials, reached through `transform` (a material's texture coordinate for a vertex's:
// the base colour's or the emission's); the larger step (GL's isotropic rho) as log2. On a plane
// this is the difference GL takes across a pixel quad. 0 (level 0) where there is no texture
// (index -1) or no usable step.
template <typename Transform>
float camera_ray_lod(const mesh& geometry, const ray_scene::hit& hit, const glm::vec3 origins[2], const glm::vec3 directions[2], int index,
                     Transform transform) {
  if (index < 0) return 0.0f;
  const texture_level& level = geometry.materials->textures[static_cast<std::size_t>(index)].levels.front();
  const vertex& a = geometry.vertices[geometry.indices[3 * hit.triangle]];
  const vertex& b = geometry.vertices[geometry.indices[3 * hit.triangle + 1]];
  const vertex& c = geometry.vertices[geometry.indices[3 * hit.triangle + 2]];
  const glm::vec3 e1 = b.position - a.position, e2 = c.position - a.position, plane = glm::cross(e1, e2);
  const float area = glm::dot(plane, plane);
  if (!(area > 0.0f)) return 0.0f;
  const auto texel_coordinate = [&](const glm::vec3& p) {
    // Barycentrics of p in the triangle's plane.
    const glm::vec3 w = p - a.position;
    const float u = glm::dot(glm::cross(w, e2), plane) / area, v = glm::dot(glm::cross(e1, w), plane) / area;
    const glm::vec2 uv = transform((1.0f - u - v) * a.texcoord + u * b.texcoord + v * c.texcoord);
    return uv * glm::vec2(static_cast<float>(level.width), static_cast<float>(level.height));
  };
  const glm::vec2 centre = texel_coordinate(hit.position);
  float rho = 0.0f;
  for (int k = 0; k < 2; ++k) {
    const float along = glm::dot(directions[k], plane);
    if (!(std::fabs(along) > 0.0f)) return 0.0f;
    const float t = glm::dot(a.position - origins[k], plane) / along;
    if (!(t > 0.0f) || !std::isfinite(t)) return 0.0f;
    rho = std::max(rho, glm::length(texel_coordinate(origins[k] + t * directions[k]) - centre));
  }
  return rho > 0.0f && std::isfinite(rho) ? std::log2(rho) : 0.0f;
}

// One pixel of the Monte Carlo reference: [radiance, indirect irradiance, direct irradiance],
// whether the camera sees the back of the surface (its normal faces away), nothing for a miss.
struct one_bounce_pixel {
  glm::vec3 radiance, indirect, direct;
  bool back_facing = false;
};

std::optional<one_bounce_pixel> trace_one_bounce_pixel(const ray_scene& rays, const scene& source, const camera_rays& primary, int x, int y, int width,
                                                       int samples, std::uint32_t seed) {
  const irradiance_settings<float> irradiance;
  const camera_rays::ray ray = primary.at(x, y);
  ray_scene::hit hit = rays.intersect(ray.origin, ray.direction);
  if (!hit.found) return std::nullopt;
  // The emission the camera sees: leaving the side the normal faces (as emission.frag draws it);
  // it is added to the radiance and lights nothing.
  glm::vec3 emission(0.0f);
  if (const surface_material* material = material_of_triangle(source.geometry, hit.triangle)) {
    // A textured surface at GL's level of detail: the rays through the next pixel to the right
    // and the next one down (camera_ray_lod).
    const camera_rays::ray right = primary.at(x + 1, y), down = primary.at(x, y + 1);
    const glm::vec3 origins[2] = {right.origin, down.origin}, directions[2] = {right.direction, down.direction};
    const float lod = camera_ray_lod(source.geometry, hit, origins, directions, material->texture,
                                     [&](glm::vec2 uv) { return material_texture_coordinate(*material, uv); });
    hit.albedo = glm::vec3(surface_albedo_alpha(source.geometry, hit.triangle, hit.barycentric, lod));
    if (emits(*material) && glm::dot(hit.normal, ray.direction) < 0.0f) {
      const float emission_lod = camera_ray_lod(source.geometry, hit, origins, directions, material->emission_texture,
                                                [&](glm::vec2 uv) { return material_emission_coordinate(*material, uv); });
      emission = surface_emission(source.geometry, hit.triangle, hit.barycentric, emission_lod);
    }
  }
  // The surface is lit on the side its normal faces, wherever the camera is: as the GL techniques
  // light it (their G-buffers, RSMs and Light Wave's receivers keep the mesh's normals), and as the
  // bounce below treats the surfaces it meets. A reference that turned the normal towards the
  // camera would light the back of a one-sided surface that no technique lights, and a scene
  // with reversed faces would read as a technique's missing light.
  const glm::vec3& n = hit.normal;
  const std::uint32_t key = static_cast<std::uint32_t>(y * width + x);
  const glm::vec3 direct = direct_irradiance(rays, source.lights, irradiance, hit.position, n);
  const glm::vec3 bounce = samples > 0 ? one_bounce_irradiance(rays, source.lights, irradiance, hit.position, n, samples, seed, key) : glm::vec3(0.0f);
  return one_bounce_pixel{diffuse_radiance(hit.albedo, direct, 1.0f, bounce) + emission, bounce, direct, glm::dot(hit.normal, ray.direction) > 0.0f};
}

}  // namespace

one_bounce_images reference_one_bounce(const ray_scene& rays, const scene& source, int width, int height, int samples, std::uint32_t seed, int threads,
                                       const progress_settings& progress_to) {
  const camera_rays primary(source.view, width, height);
  one_bounce_images out;
  out.radiance = image(width, height, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  out.indirect = out.radiance;
  out.direct = out.radiance;
  progress_monitor progress("one-bounce Monte Carlo reference", static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height), "pixels",
                            progress_to);
  std::atomic<std::uint64_t> back_facing{0};
  // Rows counted from the top (the estimate's seed key is y * width + x), stored bottom-up.
  const scrambled_order order(static_cast<std::uint64_t>(height));
  parallel_for(height, threads, [&](int k) {
    const auto y = static_cast<int>(order(static_cast<std::uint64_t>(k)));
    for (int x = 0; x < width && !progress.stopped(); ++x) {
      if (const std::optional<one_bounce_pixel> pixel = trace_one_bounce_pixel(rays, source, primary, x, y, width, samples, seed)) {
        out.radiance.at(x, height - 1 - y) = glm::vec4(pixel->radiance, 1.0f);
        out.indirect.at(x, height - 1 - y) = glm::vec4(pixel->indirect, 1.0f);
        out.direct.at(x, height - 1 - y) = glm::vec4(pixel->direct, 1.0f);
        if (pixel->back_facing) back_facing.fetch_add(1, std::memory_order_relaxed);
      }
      progress.advance();
    }
  });
  progress.finish();
  out.back_facing_pixels = back_facing.load();
  return out;
}

one_bounce_images reference_one_bounce(const scene& source, int width, int height, int samples, std::uint32_t seed, int threads) {
  const ray_scene rays(source.geometry);
  return reference_one_bounce(rays, source, width, height, samples, seed, threads);
}

reference_cost estimate_one_bounce(const ray_scene& rays, const scene& source, int width, int height, int samples, std::uint32_t seed, int threads) {
  const camera_rays primary(source.view, width, height);
  reference_cost cost;
  cost.units = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
  cost.unit = "pixels";
  cost.rays = static_cast<double>(cost.units) * (2.0 + 2.0 * static_cast<double>(samples));
  cost.what = count_text(static_cast<double>(cost.units)) + " pixels x (a camera and a shadow ray + " + std::to_string(samples) +
              " x (a bounce and a shadow ray))";
  // Two timed runs over the same pixels, without and with some samples: a pixel's cost is
  // linear in its samples, and the difference isolates the part that is.
  const std::uint64_t sample = std::min<std::uint64_t>(cost.units, 2048);
  const int calibration_samples = std::min(samples, 32);
  const auto run = [&](int with_samples) {
    return time_sample(cost.units, sample, threads, [&](std::uint64_t pixel) {
      (void)trace_one_bounce_pixel(rays, source, primary, static_cast<int>(pixel % static_cast<std::uint64_t>(width)),
                                   static_cast<int>(pixel / static_cast<std::uint64_t>(width)), width, with_samples, seed);
    });
  };
  const double base = run(0), with = run(calibration_samples);
  const double per_sample = std::max(with - base, 0.0) / static_cast<double>(calibration_samples);
  cost.seconds = (base + per_sample * static_cast<double>(samples)) * static_cast<double>(cost.units) / static_cast<double>(sample);
  return cost;
}

}  // namespace vplkit
