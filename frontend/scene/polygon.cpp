#include "frontend/scene/polygon.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <string>

#include <GL/glu.h>

#include "frontend/core/error.hpp"

namespace vplkit {

// GLU's tessellator object and what its callbacks write to.
struct polygon_triangulator::tessellator {
  GLUtesselator* glu = nullptr;
  std::vector<std::array<double, 3>> coordinates;  ///< GLU reads them until gluTessEndPolygon
  std::vector<std::uint32_t>* out = nullptr;
  GLenum failure = 0;

  ~tessellator() {
    if (glu) gluDeleteTess(glu);
  }

  // Each corner's data pointer is its index + 1 (never null: GLU passes null for unused slots).
  static void* data_of(std::size_t corner) { return reinterpret_cast<void*>(static_cast<std::uintptr_t>(corner + 1)); }
  static std::uint32_t corner_of(void* data) { return static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(data) - 1); }

  static void GLAPIENTRY on_begin(GLenum, void*) {}
  // With an edge-flag callback GLU emits separate triangles only (no strips or fans).
  static void GLAPIENTRY on_edge_flag(GLboolean, void*) {}
  static void GLAPIENTRY on_vertex(void* vertex, void* self) { static_cast<tessellator*>(self)->out->push_back(corner_of(vertex)); }
  static void GLAPIENTRY on_error(GLenum code, void* self) {
    auto* t = static_cast<tessellator*>(self);
    if (t->failure == 0) t->failure = code;
  }
  // GLU asks for a vertex where corners coincide (a corner visited twice) and, in degenerate
  // cases (edges overlapping along a line), where edges meet. The polygon was checked to have no
  // crossing edges, so such a point is at or next to a corner it has: the corner of the largest
  // weight. No vertex is invented.
  static void GLAPIENTRY on_combine(GLdouble[3], void* data[4], GLfloat weight[4], void** out, void*) {
    int best = 0;
    for (int k = 1; k < 4; ++k)
      if (data[k] && weight[k] > weight[best]) best = k;
    *out = data[best];
  }
};

polygon_triangulator::polygon_triangulator(std::uint64_t max_edge_pair_tests) : pair_tests_left_(max_edge_pair_tests) {}
polygon_triangulator::~polygon_triangulator() = default;

namespace {

double cross(const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; }

// Whether the insides of segments ab and cd meet (a crossing, not a touch at an end or an
// overlap along one line, which GLU resolves with the corners there are).
bool cross_properly(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c, const glm::dvec2& d) {
  const double abc = cross(b - a, c - a), abd = cross(b - a, d - a);
  if (!((abc > 0.0 && abd < 0.0) || (abc < 0.0 && abd > 0.0))) return false;
  const double cda = cross(d - c, a - c), cdb = cross(d - c, b - c);
  return (cda > 0.0 && cdb < 0.0) || (cda < 0.0 && cdb > 0.0);
}

}  // namespace

void polygon_triangulator::triangulate(std::span<const glm::vec3> corners, std::vector<std::uint32_t>& triangles) {
  const std::size_t n = corners.size();
  if (n < 3) throw error("a face needs at least 3 corners");
  const auto fan = [&] {
    for (std::size_t i = 1; i + 1 < n; ++i)
      triangles.insert(triangles.end(), {0u, static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(i + 1)});
  };
  if (n == 3) {
    triangles.insert(triangles.end(), {0u, 1u, 2u});
    return;
  }
  // Newell's normal: twice the vector area, the best-fit plane's normal for a bent face.
  glm::dvec3 normal(0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec3 p(corners[i]), q(corners[(i + 1) % n]);
    normal += glm::dvec3((p.y - q.y) * (p.z + q.z), (p.z - q.z) * (p.x + q.x), (p.x - q.x) * (p.y + q.y));
  }
  const double length = glm::length(normal);
  if (!(length > 0.0) || !std::isfinite(length)) {
    // No net area. On a line, every triangle of the fan is degenerate (the loader skips them,
    // and says so if no face has area); otherwise lobes of opposite turn cancel: a bow tie.
    for (std::size_t i = 1; i + 1 < n; ++i)
      if (glm::length(glm::cross(glm::dvec3(corners[i]) - glm::dvec3(corners[0]), glm::dvec3(corners[i + 1]) - glm::dvec3(corners[0]))) > 0.0)
        throw error("the face crosses itself: its parts turn opposite ways and their areas cancel (a bow tie); vplkit triangulates faces whose "
                    "edges do not cross, convex or not");
    fan();
    return;
  }
  normal /= length;
  // (u, v, normal) right-handed: the polygon winds counter-clockwise in (u, v).
  const glm::dvec3 helper = std::fabs(normal.x) <= std::fabs(normal.y) && std::fabs(normal.x) <= std::fabs(normal.z) ? glm::dvec3(1, 0, 0)
                            : std::fabs(normal.y) <= std::fabs(normal.z)                                            ? glm::dvec3(0, 1, 0)
                                                                                                                    : glm::dvec3(0, 0, 1);
  const glm::dvec3 u = glm::normalize(glm::cross(helper, normal)), v = glm::cross(normal, u);
  std::vector<glm::dvec2>& flat = flat_;  // reused: most faces come here, most of them quads
  flat.resize(n);
  const glm::dvec3 origin(corners[0]);
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec3 p = glm::dvec3(corners[i]) - origin;
    flat[i] = glm::dvec2(glm::dot(p, u), glm::dot(p, v));
  }
  // Convex: every turn strictly to the left and once around in all (a star turns left at every
  // corner but goes around twice or more; that takes five corners or more, so a quad needs no
  // angles).
  bool convex = true;
  double turning = 0.0;
  for (std::size_t i = 0; i < n && convex; ++i) {
    const glm::dvec2 in = flat[i] - flat[(i + n - 1) % n], out = flat[(i + 1) % n] - flat[i];
    const double turn = cross(in, out);
    convex = turn > 0.0;
    if (n > 4) turning += std::atan2(turn, glm::dot(in, out));
  }
  if (convex && turning < 3.0 * 3.14159265358979323846) {
    fan();
    return;
  }

  // Not convex: no two edges may cross, checked pair by pair, within the budget.
  const std::uint64_t pairs = static_cast<std::uint64_t>(n) * static_cast<std::uint64_t>(n - 1) / 2;
  if (pairs > pair_tests_left_)
    throw error("a non-convex face of " + std::to_string(n) + " corners is more than vplkit checks for crossing edges (the non-convex faces of one file "
                "may compare at most 2^28 pairs of edges in all)");
  pair_tests_left_ -= pairs;
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec2 a = flat[i], b = flat[(i + 1) % n];
    const glm::dvec2 low = glm::min(a, b), high = glm::max(a, b);
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // adjacent through the closing edge
      const glm::dvec2 c = flat[j], d = flat[(j + 1) % n];
      if (glm::max(c.x, d.x) < low.x || glm::min(c.x, d.x) > high.x || glm::max(c.y, d.y) < low.y || glm::min(c.y, d.y) > high.y) continue;
      if (cross_properly(a, b, c, d))
        throw error("the face crosses itself (its edges from corner " + std::to_string(i + 1) + " and from corner " + std::to_string(j + 1) +
                    " cross); vplkit triangulates faces whose edges do not cross, convex or not");
    }
  }

  if (!tessellator_) {
    tessellator_ = std::make_unique<tessellator>();
    tessellator_->glu = gluNewTess();
    if (!tessellator_->glu) throw error("GLU could not make a tessellator (out of memory)");
    GLUtesselator* glu = tessellator_->glu;
    gluTessCallback(glu, GLU_TESS_BEGIN_DATA, reinterpret_cast<_GLUfuncptr>(&tessellator::on_begin));
    gluTessCallback(glu, GLU_TESS_EDGE_FLAG_DATA, reinterpret_cast<_GLUfuncptr>(&tessellator::on_edge_flag));
    gluTessCallback(glu, GLU_TESS_VERTEX_DATA, reinterpret_cast<_GLUfuncptr>(&tessellator::on_vertex));
    gluTessCallback(glu, GLU_TESS_ERROR_DATA, reinterpret_cast<_GLUfuncptr>(&tessellator::on_error));
    gluTessCallback(glu, GLU_TESS_COMBINE_DATA, reinterpret_cast<_GLUfuncptr>(&tessellator::on_combine));
    gluTessProperty(glu, GLU_TESS_WINDING_RULE, GLU_TESS_WINDING_ODD);
    gluTessNormal(glu, 0.0, 0.0, 1.0);
  }
  tessellator& t = *tessellator_;
  t.coordinates.resize(n);
  for (std::size_t i = 0; i < n; ++i) t.coordinates[i] = {flat[i].x, flat[i].y, 0.0};
  const std::size_t first = triangles.size();
  t.out = &triangles;
  t.failure = 0;
  gluTessBeginPolygon(t.glu, &t);
  gluTessBeginContour(t.glu);
  for (std::size_t i = 0; i < n; ++i) gluTessVertex(t.glu, t.coordinates[i].data(), tessellator::data_of(i));
  gluTessEndContour(t.glu);
  gluTessEndPolygon(t.glu);
  if (t.failure != 0 || (triangles.size() - first) % 3 != 0) {
    triangles.resize(first);
    throw error(std::string("GLU's tessellator could not triangulate the face: ") +
                (t.failure != 0 ? reinterpret_cast<const char*>(gluErrorString(t.failure)) : "it returned a partial triangle"));
  }
  // Wound as the face: counter-clockwise in (u, v). GLU may join three corners on a line into a
  // triangle without area (the L with its inner corner on the diagonal): it covers nothing, so it
  // is left out.
  std::size_t kept = first;
  for (std::size_t k = first; k < triangles.size(); k += 3) {
    std::uint32_t a = triangles[k], b = triangles[k + 1], c = triangles[k + 2];
    const double area = cross(flat[b] - flat[a], flat[c] - flat[a]);
    if (area == 0.0) continue;
    if (area < 0.0) std::swap(b, c);
    triangles[kept++] = a;
    triangles[kept++] = b;
    triangles[kept++] = c;
  }
  triangles.resize(kept);
}

}  // namespace vplkit
