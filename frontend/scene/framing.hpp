// How frame_mesh (frontend/scene/scene.hpp) tells a closed room from an object or an open scene:
// rays cast on the CPU (a bounding-volume hierarchy over the mesh's triangles) from points inside
// the bounds. A point is enclosed when nearly every direction meets a surface whose normal faces
// the point: inside a room the walls, floor and ceiling face inwards; inside a closed object
// (a bunny's centre, a box modelled with outward normals) the rays meet back faces, so an object
// is not taken for a room; a hollow inside an object (a cylinder's bore) faces its inside too, but
// is small against the scene's bounds, and a room is not.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "frontend/scene/scene.hpp"

namespace vplkit {

/// Closest hits of rays against a mesh's triangles (the mesh must outlive it).
class mesh_ray_caster {
 public:
  explicit mesh_ray_caster(const mesh& geometry);
  ~mesh_ray_caster();
  mesh_ray_caster(const mesh_ray_caster&) = delete;
  mesh_ray_caster& operator=(const mesh_ray_caster&) = delete;

  struct hit {
    bool found = false;
    float distance = 0.0f;
    std::size_t triangle = 0;
    glm::vec3 normal{0.0f};  ///< the interpolated shading normal
  };
  /// The nearest triangle along origin + t direction, 0 < t < far (direction need not be unit;
  /// t is in its units).
  hit intersect(const glm::vec3& origin, const glm::vec3& direction, float far) const;

 private:
  struct tree;
  std::unique_ptr<tree> tree_;
  const mesh& geometry_;
};

/// What the rays from one point meet.
struct enclosure {
  float hit_fraction = 0.0f;    ///< of the directions, those that meet a surface
  float facing_fraction = 0.0f; ///< of the directions, those whose first surface faces the point
  float median_distance = 0.0f; ///< of the hits' distances (0 without hits)
};

/// `directions` rays (a Fibonacci sphere) from `point`, up to `far`.
enclosure measure_enclosure(const mesh_ray_caster& rays, const glm::vec3& point, int directions, float far);

/// A point counts as inside a closed room when at least this share of the directions meets a
/// surface facing it (a door or a window may let some rays out).
inline constexpr float closed_room_facing_fraction = 0.9f;
/// ... and when the space around it is a room, not a hollow in an object: the median distance to
/// those surfaces at least this share of the bounding sphere's radius (a cubic room seen from its
/// centre: 0.58 to 1; the bore of an engine's cylinder, whose inner walls face inwards too: < 0.1).
inline constexpr float closed_room_median_distance = 0.25f;

}  // namespace vplkit
