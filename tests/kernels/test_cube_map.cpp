// The faces of a point light's cube of RSMs (include/vplkit/cube_map.hpp): the face of a
// direction is the one whose 90-degree frustum contains it, the six frusta tile the sphere, and
// each face's axis and up vector make a proper view.
#include <doctest/doctest.h>

#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/cube_map.hpp>

using namespace vplkit;

namespace {

// The normalised device coordinates of direction d in face f's view (lookAt from the origin
// along the face's axis with its up vector, a 90-degree square perspective): inside the face's
// frustum when both lie in [-1, 1] and the depth is in front.
glm::dvec3 face_ndc(int f, const glm::dvec3& d) {
  const glm::dmat4 view = glm::lookAt(glm::dvec3(0), cube_face_axis<double>(f), cube_face_up<double>(f));
  const glm::dmat4 projection = glm::perspective(glm::radians(90.0), 1.0, 0.01, 100.0);
  const glm::dvec4 clip = projection * view * glm::dvec4(d, 1.0);
  return glm::dvec3(clip) / clip.w;
}

}  // namespace

TEST_CASE("cube map: the face of a direction is the one frustum that contains it, and it is in front of no other face") {
  std::mt19937 random(38);
  std::normal_distribution<double> normal;
  int per_face[6] = {};
  for (int i = 0; i < 20000; ++i) {
    const glm::dvec3 d(normal(random), normal(random), normal(random));
    if (glm::length(d) < 1e-6) continue;
    const int f = cube_face_of(d);
    REQUIRE(f >= 0);
    REQUIRE(f < 6);
    ++per_face[f];
    // In front of its face, inside its square frustum.
    CHECK(glm::dot(d, cube_face_axis<double>(f)) > 0.0);
    const glm::dvec3 ndc = face_ndc(f, 2.0 * glm::normalize(d));
    CHECK(std::abs(ndc.x) <= 1.0 + 1e-9);
    CHECK(std::abs(ndc.y) <= 1.0 + 1e-9);
    // Its face's axis is the nearest of the six (the major axis): the frusta do not overlap.
    for (int g = 0; g < 6; ++g) CHECK(glm::dot(d, cube_face_axis<double>(f)) >= glm::dot(d, cube_face_axis<double>(g)));
    // The length does not matter.
    CHECK(cube_face_of(d * 1e-3) == f);
    CHECK(cube_face_of(glm::vec3(d * 7.0)) == f);
  }
  // Uniform directions fall on each face a sixth of the time (20000 / 6 = 3333, sigma ~ 53).
  for (int f = 0; f < 6; ++f) {
    CAPTURE(f);
    CHECK(per_face[f] > 3333 - 300);
    CHECK(per_face[f] < 3333 + 300);
  }
}

TEST_CASE("cube map: each face's axis is its own face, its up vector is orthogonal, and borders have one face") {
  for (int f = 0; f < 6; ++f) {
    CAPTURE(f);
    const glm::vec3 axis = cube_face_axis<float>(f), up = cube_face_up<float>(f);
    CHECK(cube_face_of(axis) == f);
    CHECK(glm::length(axis) == doctest::Approx(1.0));
    CHECK(glm::length(up) == doctest::Approx(1.0));
    CHECK(glm::dot(axis, up) == 0.0f);
    // The face's own centre ray projects to the centre of its view.
    const glm::dvec3 centre = face_ndc(f, glm::dvec3(axis));
    CHECK(std::abs(centre.x) < 1e-12);
    CHECK(std::abs(centre.y) < 1e-12);
  }
  // OpenGL's order: +x, -x, +y, -y, +z, -z.
  CHECK(cube_face_axis<float>(3) == glm::vec3(0, -1, 0));
  CHECK(cube_face_axis<float>(4) == glm::vec3(0, 0, 1));
  // A corner direction and edge directions get exactly one face, by the documented tie order.
  CHECK(cube_face_of(glm::vec3(1, 1, 1)) == 0);
  CHECK(cube_face_of(glm::vec3(-1, 1, 1)) == 1);
  CHECK(cube_face_of(glm::vec3(0, -1, 1)) == 3);
  CHECK(cube_face_of(glm::vec3(0, 0, -1)) == 5);
  CHECK(cube_face_of(glm::vec3(0)) == 0);
}
