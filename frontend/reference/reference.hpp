// Ground truth on the CPU, ray cast with Intel Embree: the brute-force RSM gather of [RSMV]'s
// Fig. 5.1d (every pixel light of the RSM at every G-buffer point, with exact visibility or
// without), and a one-bounce Monte Carlo reference that does not depend on the RSM (direct light
// plus one diffuse bounce of direct light, path traced). Deterministic for a seed (per-pixel
// hashes), multi-threaded. Both are long work: estimate_* say what a run costs (rays, and seconds
// from a calibration on this machine) before it starts, and a progress_monitor reports it and
// stops it at its deadline (frontend/core/progress.hpp). Every ray is checked before it reaches
// Embree (an Embree assertion aborts the process).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "frontend/core/progress.hpp"
#include "frontend/image/image.hpp"
#include "frontend/techniques/rsm/rsm_pipeline.hpp"
#include "frontend/scene/scene.hpp"

namespace vplkit {

/// An Embree scene of a mesh: closest hits and occlusion tests. It shares the mesh's vertex and
/// index arrays (no copy): the mesh must outlive it, unchanged. Cut-outs of alpha-tested
/// materials are not hit (a filter function tests each candidate hit's alpha at texture level 0).
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
  /// The closest hit along the ray. Throws vplkit::error when the ray is not one Embree takes
  /// (a non-finite or huge origin, a non-finite or zero direction): Embree would abort.
  hit intersect(const glm::vec3& origin, const glm::vec3& direction, float far = 1e30f) const;
  /// Whether anything lies on the segment from `from` to `to` (both ends excluded by a small
  /// epsilon relative to the segment's length). Throws like intersect for a non-finite end.
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

/// The largest ray origin coordinate, direction component or distance the tracer takes: far
/// below Embree's own limit (1.8e18, beyond which it asserts), far above max_scene_coordinate.
inline constexpr float max_ray_coordinate = 1.0e12f;

/// The camera's primary rays, computed in double: the inverse projection of a camera with znear
/// 1e-6 and zfar 50 (or 0.05 and 1e7) loses every digit in float. Origins on the near plane,
/// unit directions, the same pixels as the GL pipelines (camera_view_matrix and
/// camera_projection_matrix in double).
class camera_rays {
 public:
  /// Throws vplkit::error naming the camera when a corner ray of the image is not finite.
  camera_rays(const camera& view, int width, int height);
  struct ray {
    glm::vec3 origin;
    glm::vec3 direction;
  };
  /// The ray through the centre of pixel (x, y), y counted from the top row.
  ray at(int x, int y_from_top) const;

 private:
  glm::dmat4 inverse_;
  int width_, height_;
};

/// What a reference run costs before it starts: an upper bound of its rays and an estimate of
/// its wall time on this machine (a calibration run of a sample of its work, same threads).
struct reference_cost {
  double rays = 0.0;          ///< at most this many rays
  double seconds = 0.0;       ///< estimated wall time
  std::uint64_t units = 0;    ///< the work items progress counts (pixels, receivers)
  std::string unit;           ///< their name
  std::string what;           ///< how the rays are counted, for the announcement
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
                                  const rsm_brute_force_options& options, const progress_settings& progress = {});

/// The cost of reference_rsm_gather with these options: receivers x lit RSM texels pairs (a ray
/// each with exact visibility), timed on up to 64 receivers spread over the buffer.
reference_cost estimate_rsm_gather(const ray_scene& rays, const rsm_pass_buffers& buffers, const rsm_frame_constants& constants,
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
  /// Pixels whose surface faces away from the camera (the normal points away from the eye). Every
  /// surface is lit on the side its normal faces, by the reference as by the GL techniques, so
  /// these see only what reaches that side: usually the sign of reversed faces in the mesh.
  std::uint64_t back_facing_pixels = 0;
};

/// The revision of the Monte Carlo reference's results: tools that cache its images key them by it.
/// 2: the surface the camera sees is lit on its normal's side (1 turned the normal to the camera).
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
