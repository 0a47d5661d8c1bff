// Ground truth on the CPU, ray cast with Intel Embree: the brute-force RSM gather of [RSMV]'s
// Fig. 5.1d (every pixel light of the RSM at every G-buffer point, with exact visibility or
// without), and a one-bounce Monte Carlo reference that does not depend on the RSM (direct light
// plus one diffuse bounce of direct light, path traced). Deterministic for a seed (per-pixel
// hashes), multi-threaded, with a progress bar and ETA on a terminal and silence otherwise.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "frontend/image/image.hpp"
#include "frontend/techniques/rsm/rsm_pipeline.hpp"
#include "frontend/scene/scene.hpp"

namespace vplkit {

/// An Embree scene of a mesh: closest hits and occlusion tests. The mesh must outlive it.
/// Cut-outs of alpha-tested materials are not hit (a filter function tests each candidate hit's
/// alpha at texture level 0).
class ray_scene {
 public:
  explicit ray_scene(const mesh& geometry);
  ~ray_scene();
  ray_scene(const ray_scene&) = delete;
  ray_scene& operator=(const ray_scene&) = delete;

  struct hit {
    bool found = false;
    float distance = 0.0f;
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f};  ///< the triangle's interpolated shading normal, unit
    glm::vec3 albedo{0.0f};  ///< surface_albedo_alpha at texture level 0
    std::size_t triangle = 0;
    glm::vec2 barycentric{0.0f};  ///< (u, v): the point is (1 - u - v) a + u b + v c
  };
  hit intersect(const glm::vec3& origin, const glm::vec3& direction, float far = 1e30f) const;
  /// Whether anything lies on the segment from `from` to `to` (both ends excluded by a small
  /// epsilon relative to the segment's length).
  bool occluded(const glm::vec3& from, const glm::vec3& to) const;

 private:
  struct state;
  std::unique_ptr<state> state_;
  const mesh& geometry_;
};

/// Direct irradiance at (x, n) from the scene's light, with an occlusion ray.
glm::vec3 direct_irradiance(const ray_scene& rays, const scene_light& light, const irradiance_settings<float>& irradiance,
                            const glm::vec3& x, const glm::vec3& n);

/// One diffuse bounce of direct light at (x, n): the irradiance from every surface the light
/// reaches, estimated with `samples` cosine-weighted rays; deterministic for (seed, key).
glm::vec3 one_bounce_irradiance(const ray_scene& rays, const scene_light& light, const irradiance_settings<float>& irradiance,
                                const glm::vec3& x, const glm::vec3& n, int samples, std::uint32_t seed, std::uint32_t key);

/// The same with separate scenes for the bounce rays (`bounce_rays`: what blocks the view of the
/// environment, e.g. the environment plus a dynamic object, for self-shadowing) and for the
/// direct light of the surfaces they reach (`light_rays`).
glm::vec3 one_bounce_irradiance(const ray_scene& bounce_rays, const ray_scene& light_rays, const scene_light& light,
                                const irradiance_settings<float>& irradiance, const glm::vec3& x, const glm::vec3& n, int samples,
                                std::uint32_t seed, std::uint32_t key);

/// Prints a progress bar with an ETA to stderr when it is a terminal; silent otherwise.
class progress_bar {
 public:
  progress_bar(std::string label, std::size_t total);
  void advance(std::size_t done = 1);
  void finish();

 private:
  std::string label_;
  std::size_t total_;
  std::atomic<std::size_t> done_{0};
  bool terminal_;
  double start_;
  std::atomic<int> last_percent_{-1};
};

/// Options of the brute-force RSM gather (the thesis's Fig. 5.1d).
struct rsm_brute_force_options {
  bool exact_visibility = false;  ///< ray-cast every pixel light against the scene (else none)
  /// Only the pixel lights within this many RSM texels of the receiver's projection (for the
  /// radius part of the error split); 0: every lit texel of the RSM.
  float max_radius = 0.0f;
  /// Compute every stride-th receiver of the indirect buffer per axis (the others stay 0), to
  /// bound the cost of exact visibility at full resolution.
  int receiver_stride = 1;
  int threads = 1;
};

/// The brute-force RSM gather at the receivers of the indirect buffer of `buffers` (the G-buffer
/// points the GL gather uses): every lit RSM texel (flux > 0) is a pixel light, Eq. 3.2 with the
/// same distance clamp and the same 1/pi as gather_rsm. Receivers behind the light (light eye
/// z >= 0) are computed too: the RSM does light them, although the gather cannot (see
/// rsm_covered_receivers). Returns [irradiance | the fraction of the unoccluded irradiance that is
/// visible (1 without visibility)].
image reference_rsm_gather(const ray_scene& rays, const rsm_pass_buffers& buffers, const rsm_frame_constants& constants,
                                  const rsm_brute_force_options& options);

/// The radial pattern's own samples (the same pattern, seed and weights as the frame's gather)
/// with exact visibility: each sample's pixel light is ray cast instead of tested against the
/// micro linear buffer. The difference to the brute force with exact visibility is the
/// sampling error alone; to the gather with Alg. 6, the visibility approximation's error alone.
image gather_with_ray_cast_visibility(const ray_scene& rays, const rsm_pass_buffers& buffers, const rsm_frame_constants& constants,
                                             int receiver_stride, int threads);

/// The receivers of the indirect buffer the RSM gather covers (1) or not (0): a surface in front
/// of the light (light eye z < 0) whose projection falls inside the RSM. gather_rsm returns 0
/// behind the light (no projection), and outside the light's frustum its pattern reaches only
/// the part of the RSM within its radius of a projection that lies off the map. Every RSM metric
/// counts covered receivers only, and says how much light the others hold. With a stride, only
/// every stride-th receiver per axis can count (the ones a strided reference computes).
std::vector<std::uint8_t> rsm_covered_receivers(const rsm_pass_buffers& buffers, const rsm_frame_constants& constants, int receiver_stride = 1);

struct one_bounce_images {
  image radiance;  ///< albedo / pi * (E_direct + E_one_bounce), what the camera sees
  image indirect;  ///< E_one_bounce at each pixel's surface
};

/// The one-bounce Monte Carlo reference of a scene seen by its camera.
one_bounce_images reference_one_bounce(const scene& source, int width, int height, int samples, std::uint32_t seed, int threads);

}  // namespace vplkit
