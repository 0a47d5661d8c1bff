// The one-bounce Monte Carlo reference, which does not depend on the RSM: direct light plus one
// diffuse bounce of direct light, path traced with the Embree scene of ray_scene.hpp.
// Deterministic for a seed (per-pixel hashes), multi-threaded, long work (estimate_one_bounce
// says what a run costs).
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include <vplkit/irradiance.hpp>

#include "frontend/core/progress.hpp"
#include "frontend/image/image.hpp"
#include "frontend/reference/ray_scene.hpp"
#include "frontend/reference/work.hpp"
#include "frontend/scene/scene.hpp"

namespace vplkit {

/// Direct irradiance at (x, n) from one light, with an occlusion ray (a spot, a point light: to
/// its position; a sun: 100 units against its direction).
glm::vec3 direct_irradiance(const ray_scene& rays, const scene_light& light, const irradiance_settings<float>& irradiance,
                            const glm::vec3& x, const glm::vec3& n);
/// The sum over the lights: light adds linearly, so several lights are the sum of each alone.
glm::vec3 direct_irradiance(const ray_scene& rays, const std::vector<scene_light>& lights, const irradiance_settings<float>& irradiance,
                            const glm::vec3& x, const glm::vec3& n);

/// One diffuse bounce of direct light at (x, n): the irradiance from every surface the lights
/// reach, estimated with `samples` cosine-weighted rays; deterministic for (seed, key).
glm::vec3 one_bounce_irradiance(const ray_scene& rays, const std::vector<scene_light>& lights, const irradiance_settings<float>& irradiance,
                                const glm::vec3& x, const glm::vec3& n, int samples, std::uint32_t seed, std::uint32_t key);

/// The same with separate scenes for the bounce rays (`bounce_rays`: what blocks the view of the
/// environment, e.g. the environment plus a dynamic object, for self-shadowing) and for the
/// direct light of the surfaces they reach (`light_rays`).
glm::vec3 one_bounce_irradiance(const ray_scene& bounce_rays, const ray_scene& light_rays, const std::vector<scene_light>& lights,
                                const irradiance_settings<float>& irradiance, const glm::vec3& x, const glm::vec3& n, int samples,
                                std::uint32_t seed, std::uint32_t key);

struct one_bounce_images {
  image radiance;  ///< albedo / pi * (E_direct + E_one_bounce) + the surface's emission (material.hpp), what the camera sees
  image indirect;  ///< E_one_bounce at each pixel's surface
  image direct;    ///< E_direct at each pixel's surface: every light's, each with an exact shadow ray
  /// Pixels whose surface faces away from the camera (the normal points away from the eye). Every
  /// surface is lit on the side its normal faces, by the reference as by the GL techniques, so
  /// these see only what reaches that side: usually the sign of reversed faces in the mesh.
  std::uint64_t back_facing_pixels = 0;
};

/// The revision of the Monte Carlo reference's results: tools that cache its images key them by it.
/// 2: the surface the camera sees is lit on its normal's side (1 turned the normal to the camera).
/// (Emission, added to the radiance since, did not change it: every image without an emissive
/// material is the same bit for bit, and the studies that cache images have none.)
inline constexpr int monte_carlo_revision = 2;

/// The one-bounce Monte Carlo reference of a scene seen by its camera (`rays` of its geometry).
/// Throws vplkit::error when the progress deadline stops it.
one_bounce_images reference_one_bounce(const ray_scene& rays, const scene& source, int width, int height, int samples, std::uint32_t seed, int threads,
                                       const progress_settings& progress = {});
/// The same with its own ray_scene of the scene's geometry.
one_bounce_images reference_one_bounce(const scene& source, int width, int height, int samples, std::uint32_t seed, int threads);

/// The cost of reference_one_bounce: at most width x height x (2 + 2 samples) rays (a camera and
/// a shadow ray per pixel, a bounce and a shadow ray per sample), the time from two calibration
/// runs on up to 2048 pixels (without and with min(samples, 32) samples), extrapolated linearly.
reference_cost estimate_one_bounce(const ray_scene& rays, const scene& source, int width, int height, int samples, std::uint32_t seed, int threads);

}  // namespace vplkit
