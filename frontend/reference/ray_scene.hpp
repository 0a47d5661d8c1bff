// The rays of the CPU references: an Intel Embree scene of a mesh (closest hits, occlusion tests)
// and a camera's primary rays. Every ray is checked before it reaches Embree (an Embree assertion
// aborts the process).
#pragma once

#include <cstddef>
#include <memory>

#include <glm/glm.hpp>

#include "frontend/scene/camera.hpp"
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

}  // namespace vplkit
