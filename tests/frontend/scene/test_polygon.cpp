// Polygon triangulation (frontend/scene/polygon.hpp): a non-convex polygon's triangles cover
// exactly its inside (their areas add up to its shoelace area, each lies inside it, none
// overlaps), wound as the polygon; convex ones are fans; crossing edges are refused.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "frontend/core/error.hpp"
#include "frontend/scene/polygon.hpp"

using namespace vplkit;

namespace {

constexpr double pi = 3.14159265358979323846;

double cross(const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; }

// The shoelace formula: the signed area of a polygon in the plane (positive counter-clockwise).
double shoelace(const std::vector<glm::dvec2>& p) {
  double twice = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) twice += cross(p[i], p[(i + 1) % p.size()]);
  return 0.5 * twice;
}

// Whether point q is inside the polygon by the crossing number (even-odd, as GLU's odd rule).
bool inside_polygon(const std::vector<glm::dvec2>& p, const glm::dvec2& q) {
  bool in = false;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++)
    if ((p[i].y > q.y) != (p[j].y > q.y) && q.x < (p[j].x - p[i].x) * (q.y - p[i].y) / (p[j].y - p[i].y) + p[i].x) in = !in;
  return in;
}

// A planar polygon given in 2D, placed in 3D on the plane spanned by `u` and `v` through `origin`.
std::vector<glm::vec3> place(const std::vector<glm::dvec2>& p, const glm::dvec3& origin, const glm::dvec3& u, const glm::dvec3& v) {
  std::vector<glm::vec3> out;
  for (const glm::dvec2& q : p) out.emplace_back(origin + q.x * u + q.y * v);
  return out;
}

// Triangulates the polygon placed in 3D and checks, in its own 2D coordinates: every triangle is
// wound counter-clockwise (as the polygon, whose normal is u x v) with an area, lies inside the
// polygon (its centroid and points just inside the midpoints of its edges), and the areas add up
// to the shoelace area (with the triangles inside and none inverted, a sum equal to the area
// means no overlap and no gap).
void check_triangulation(const std::vector<glm::dvec2>& polygon, const glm::dvec3& origin, const glm::dvec3& u, const glm::dvec3& v,
                         std::size_t most_triangles) {
  polygon_triangulator triangulator;
  std::vector<std::uint32_t> triangles;
  triangulator.triangulate(place(polygon, origin, u, v), triangles);
  REQUIRE(triangles.size() % 3 == 0);
  CHECK(triangles.size() / 3 <= most_triangles);  // n - 2, less triangles of three corners on a line
  double total = 0.0;
  int outside = 0, inverted = 0;
  for (std::size_t k = 0; k < triangles.size(); k += 3) {
    const glm::dvec2 a = polygon[triangles[k]], b = polygon[triangles[k + 1]], c = polygon[triangles[k + 2]];
    const double area = 0.5 * cross(b - a, c - a);
    if (area <= 0.0) ++inverted;
    total += area;
    for (const glm::dvec2& q : {(a + b + c) / 3.0, (a + b) * 0.5 + (c - (a + b) * 0.5) * 1e-6, (b + c) * 0.5 + (a - (b + c) * 0.5) * 1e-6,
                                (c + a) * 0.5 + (b - (c + a) * 0.5) * 1e-6})
      if (!inside_polygon(polygon, q)) ++outside;
  }
  CHECK(inverted == 0);
  CHECK(outside == 0);
  CHECK(total == doctest::Approx(shoelace(polygon)).epsilon(1e-9));
}

// A ring traced as one polygon, as LightWave writes it (assimp's OBJ/concave_polygon.obj): the
// outer circle counter-clockwise, along a slit to the inner circle, the inner circle clockwise,
// and back along the slit. Both circles have `sides` corners; the slit's two corners appear twice.
std::vector<glm::dvec2> keyhole_ring(int sides, double outer, double inner) {
  std::vector<glm::dvec2> p;
  // i % sides: the slit's corners are the same points both times (in an OBJ, the same vertex).
  for (int i = 0; i <= sides; ++i) p.emplace_back(outer * std::cos(2 * pi * (i % sides) / sides), outer * std::sin(2 * pi * (i % sides) / sides));
  for (int i = 0; i <= sides; ++i) p.emplace_back(inner * std::cos(-2 * pi * (i % sides) / sides), inner * std::sin(-2 * pi * (i % sides) / sides));
  return p;
}

}  // namespace

TEST_CASE("a concave polygon's triangles cover exactly its inside, in any plane, wound as the polygon") {
  const glm::dvec3 origin(1.5, -2.0, 0.25);
  // Planes: the xy plane, a tilted one, and the yz plane facing -x (as assimp's ring is).
  const std::vector<std::pair<glm::dvec3, glm::dvec3>> planes = {
      {{1, 0, 0}, {0, 1, 0}}, {glm::normalize(glm::dvec3(1, 1, 0)), glm::normalize(glm::dvec3(-1, 1, 2))}, {{0, 0, 1}, {0, 1, 0}}};
  for (const auto& plane : planes) {
    const glm::dvec3 u = plane.first, v = plane.second;
    CAPTURE(u.x);
    CAPTURE(v.z);
    // An L: one reflex corner.
    check_triangulation({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, origin, u, v, 4);
    // A comb with five teeth: many reflex corners, where a fan from corner 0 leaves the polygon.
    std::vector<glm::dvec2> comb = {{0, 0}, {10, 0}};
    for (int t = 4; t >= 0; --t) comb.insert(comb.end(), {{2.0 * t + 2, 5}, {2.0 * t + 1.5, 5}, {2.0 * t + 1.5, 1}, {2.0 * t + 0.5, 1}, {2.0 * t + 0.5, 5}});
    comb.back() = {0, 5};
    check_triangulation(comb, origin, u, v, comb.size() - 2);
    // The ring: 2 x 32 sides, 66 corners as in the assimp file; its area is the annulus' polygon area.
    const std::vector<glm::dvec2> ring = keyhole_ring(32, 1.0, 0.9);
    check_triangulation(ring, origin, u, v, 64);
    CHECK(shoelace(ring) == doctest::Approx(0.5 * 32 * std::sin(2 * pi / 32) * (1.0 - 0.81)).epsilon(1e-12));
  }
}

TEST_CASE("random star-shaped polygons (simple, mostly concave) are triangulated into n - 2 triangles inside them") {
  std::mt19937 random(36);
  std::uniform_real_distribution<double> radius(0.2, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 4 + trial % 60;
    std::vector<glm::dvec2> p;
    for (int i = 0; i < n; ++i) {
      const double r = radius(random), angle = 2 * pi * i / n;
      p.emplace_back(r * std::cos(angle), r * std::sin(angle));
    }
    CAPTURE(trial);
    check_triangulation(p, {0, 0, 0}, {0, 1, 0}, {0, 0, 1}, static_cast<std::size_t>(n - 2));
  }
}

TEST_CASE("convex polygons are fans from corner 0, as before; a clockwise polygon's triangles are clockwise too") {
  polygon_triangulator triangulator;
  std::vector<std::uint32_t> triangles;
  const std::vector<glm::vec3> pentagon = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, 0.5f, 0}};
  triangulator.triangulate(pentagon, triangles);
  CHECK(triangles == std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3, 0, 3, 4});
  // The L backwards (clockwise seen from +z): its triangles face -z, as the face does.
  const std::vector<glm::vec3> l_backwards = {{0, 2, 0}, {1, 2, 0}, {1, 1, 0}, {2, 1, 0}, {2, 0, 0}, {0, 0, 0}};
  triangles.clear();
  triangulator.triangulate(l_backwards, triangles);
  REQUIRE(triangles.size() >= 9);  // its inner corner lies on the diagonal: GLU's triangle along it has no area and is left out
  for (std::size_t k = 0; k < triangles.size(); k += 3) {
    const glm::vec3 a = l_backwards[triangles[k]], b = l_backwards[triangles[k + 1]], c = l_backwards[triangles[k + 2]];
    CHECK(glm::cross(b - a, c - a).z < 0.0f);
  }
}

TEST_CASE("a polygon whose edges cross is refused, naming the edges; the pair budget is named when spent") {
  polygon_triangulator triangulator;
  std::vector<std::uint32_t> triangles;
  // A lopsided bow tie: edges 1-2 and 3-4 cross.
  const std::vector<glm::vec3> bow_tie = {{0, 0, 0}, {3, 1, 0}, {3, 0, 0}, {0, 2, 0}};
  CHECK_THROWS_WITH_AS(triangulator.triangulate(bow_tie, triangles), doctest::Contains("the face crosses itself (its edges from corner 1 and from corner 3 cross)"),
                       vplkit::error);
  // A symmetric one: its lobes' areas cancel, so it has no plane to be triangulated in.
  const std::vector<glm::vec3> symmetric = {{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}};
  CHECK_THROWS_WITH_AS(triangulator.triangulate(symmetric, triangles), doctest::Contains("their areas cancel (a bow tie)"), vplkit::error);
  CHECK(triangles.empty());
  // Corners on a line: a fan of degenerate triangles (the OBJ loader skips them).
  const std::vector<glm::vec3> line = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  triangulator.triangulate(line, triangles);
  CHECK(triangles == std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3});
  triangles.clear();
  // A pentagram: convex at every corner, but twice around.
  std::vector<glm::vec3> star;
  for (int i = 0; i < 5; ++i) star.emplace_back(std::cos(2 * pi * 2 * i / 5), std::sin(2 * pi * 2 * i / 5), 0.0);
  CHECK_THROWS_WITH_AS(triangulator.triangulate(star, triangles), doctest::Contains("crosses itself"), vplkit::error);
  polygon_triangulator small(10);  // 5 corners: 10 pairs; 6 corners: 15
  const std::vector<glm::vec3> l_shape = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  CHECK_THROWS_WITH_AS(small.triangulate(l_shape, triangles), doctest::Contains("a non-convex face of 6 corners is more than vplkit checks"), vplkit::error);
}
