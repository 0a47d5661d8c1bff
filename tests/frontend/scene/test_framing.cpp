// frame_mesh (frontend/scene/scene.hpp, framing.hpp): a closed room gets its camera and light
// inside, below the ceiling; an object, an open scene and a hollow inside an object get the
// three-quarter view and a floor; the note gives the pose as --camera/--light.
#include <doctest/doctest.h>

#include <cmath>

#include "frontend/scene/framing.hpp"
#include "frontend/scene/scene.hpp"

using namespace vplkit;

namespace {

// A box whose faces look inwards (a room's walls, floor and ceiling).
void add_inward_box(mesh& target, glm::vec3 centre, glm::vec3 size) {
  mesh box;
  add_box(box, centre, size, 0.0f, glm::vec3(0.7f));
  const auto base = static_cast<std::uint32_t>(target.vertices.size());
  for (vertex v : box.vertices) {
    v.normal = -v.normal;
    target.vertices.push_back(v);
  }
  for (std::size_t i = 0; i < box.indices.size(); i += 3)
    for (const std::size_t k : {0, 2, 1}) target.indices.push_back(base + box.indices[i + k]);
}

bool inside_box(const bounding_box& box, glm::vec3 p) { return glm::all(glm::greaterThan(p, box.minimum)) && glm::all(glm::lessThan(p, box.maximum)); }

}  // namespace

TEST_CASE("framing: a closed room is seen and lit from inside, below the ceiling, with no floor added") {
  mesh room;
  add_inward_box(room, {0.0f, 1.5f, 0.0f}, {6.0f, 3.0f, 5.0f});
  add_box(room, {0.0f, 0.4f, 0.0f}, {2.0f, 0.8f, 1.2f}, 0.0f, glm::vec3(0.7f));  // a table in the middle
  const std::size_t triangles = room.triangle_count();
  const bounding_box box = bounds(room);
  const scene framed = frame_mesh("room", room);
  CHECK(framed.geometry.triangle_count() == triangles);
  CHECK(inside_box(box, framed.view.position));
  CHECK(framed.view.position.y < 3.0f);
  REQUIRE(framed.lights[0].kind == light_kind::spot);
  CHECK(inside_box(box, framed.lights[0].spot.position));
  CHECK(framed.lights[0].spot.position.y < 3.0f);
  CHECK(framed.lights[0].spot.position.y > framed.view.position.y);
  REQUIRE(framed.notes.size() == 1);
  CHECK(framed.notes[0].find("closed room") != std::string::npos);
  CHECK(framed.notes[0].find("--camera ") != std::string::npos);
  CHECK(framed.notes[0].find("--light ") != std::string::npos);
}

TEST_CASE("framing: an object gets a raised three-quarter view (not of one face) and a floor") {
  mesh object;
  add_box(object, {0.0f, 0.5f, 0.0f}, {1.0f, 1.0f, 1.0f}, 0.0f, glm::vec3(0.7f));
  const std::size_t triangles = object.triangle_count();
  const scene framed = frame_mesh("box", object);
  CHECK(framed.geometry.triangle_count() == triangles + 2);  // the floor
  const glm::vec3 from = glm::normalize(framed.view.position - framed.view.target);
  CHECK(from.y > 0.2f);                    // raised
  CHECK(std::fabs(from.x) > 0.2f);         // three-quarter: neither axis dominates alone
  CHECK(std::fabs(from.z) > 0.2f);
  CHECK(framed.notes.at(0).find("an object or an open scene") != std::string::npos);
}

TEST_CASE("framing: a hollow inside an object (inward faces, small against the bounds) is not a room") {
  mesh engine;
  add_box(engine, {0.0f, 0.0f, 0.0f}, {10.0f, 10.0f, 10.0f}, 0.0f, glm::vec3(0.7f));
  add_inward_box(engine, {0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f});  // a bore at the centre
  const mesh_ray_caster rays(engine);
  const enclosure bore = measure_enclosure(rays, {0.0f, 0.0f, 0.0f}, 128, 100.0f);
  CHECK(bore.facing_fraction == 1.0f);  // facing, as a room's walls would be ...
  CHECK(bore.median_distance < closed_room_median_distance * bounds(engine).radius());  // ... but close
  CHECK(frame_mesh("engine", engine).notes.at(0).find("an object or an open scene") != std::string::npos);
}

TEST_CASE("framing: a file's own camera or light is kept, the floor comes only with a placed light") {
  mesh object;
  add_box(object, {0.0f, 0.5f, 0.0f}, {1.0f, 1.0f, 1.0f}, 0.0f, glm::vec3(0.7f));
  framing_needs camera_only;
  camera_only.light = false;
  const scene framed = frame_mesh("box", object, camera_only);
  CHECK(framed.geometry.triangle_count() == object.triangle_count());
  CHECK(framed.notes.at(0).find("--light") == std::string::npos);
}

TEST_CASE("framing: an open scene with its own floor gets no second floor in the same plane") {
  mesh ground;
  add_quad(ground, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, {-2, 0, -2}, {0, 1, 0}, glm::vec3(0.7f));
  add_box(ground, {0.0f, 0.5f, 0.0f}, {1.0f, 1.0f, 1.0f}, 0.0f, glm::vec3(0.7f));  // standing on it
  const scene framed = frame_mesh("ground", ground);
  CHECK(framed.geometry.triangle_count() == ground.triangle_count());
  CHECK(framed.notes.at(0).find("its own floor") != std::string::npos);
}
