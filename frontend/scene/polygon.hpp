// Triangulation of one polygon (an OBJ face): convex ones as a fan, others by GLU's tessellator
// (libGLU from Mesa, Debian's libglu1-mesa-dev: the sweep-line tessellator OpenGL programs have
// used since 1994, packaged and maintained with Mesa, so vplkit carries no triangulator of its
// own). A face is triangulated in its best-fit plane, the plane through its Newell normal, so a
// slightly bent face is handled as its projection.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace vplkit {

/// Triangulates polygons one after another, sharing one GLU tessellator. Not thread-safe.
class polygon_triangulator {
 public:
  /// `max_edge_pair_tests`: how many pairs of edges the self-crossing check of the non-convex
  /// polygons may compare in all (it is quadratic in a polygon's corners; GLU's own time grows
  /// faster than quadratically with the crossings, which is why they are refused first).
  explicit polygon_triangulator(std::uint64_t max_edge_pair_tests = std::uint64_t{1} << 28);
  ~polygon_triangulator();
  polygon_triangulator(const polygon_triangulator&) = delete;
  polygon_triangulator& operator=(const polygon_triangulator&) = delete;

  /// Appends the triangles of the polygon with these corners (3 or more, in order) to
  /// `triangles`, three indices into `corners` each, wound as the polygon is wound about its
  /// Newell normal. A convex polygon (every turn the same way, once around) is a fan from
  /// corner 0; any other is GLU's triangulation of the region inside it, by the odd winding
  /// rule (a corner visited twice, as where a face traces a ring and comes back along a slit, is
  /// one vertex), less any triangle GLU makes of three corners on a line. A polygon with its
  /// corners on a line is a fan, each triangle degenerate.
  /// Throws vplkit::error, with no file or line (the caller adds them), when the
  /// polygon crosses itself (edges whose insides meet, or lobes whose areas cancel: a
  /// triangulation would need corners the file does not have) or the edge-pair budget is spent.
  void triangulate(std::span<const glm::vec3> corners, std::vector<std::uint32_t>& triangles);

 private:
  struct tessellator;
  std::unique_ptr<tessellator> tessellator_;
  std::uint64_t pair_tests_left_;
  std::vector<glm::dvec2> flat_;  ///< the polygon in its plane
};

}  // namespace vplkit
