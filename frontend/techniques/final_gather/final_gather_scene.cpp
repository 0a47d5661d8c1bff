#include "frontend/techniques/final_gather/final_gather_scene.hpp"

#include <algorithm>
#include <filesystem>

#include "frontend/core/error.hpp"
#include "frontend/scene/obj_loader.hpp"

namespace vplkit {

final_gather_scene make_final_gather_scene(const std::string& object, glm::vec3 position, float size) {
  if (!(size > 0.0f)) throw error("the object's size must be > 0");
  final_gather_scene s;
  s.object_source = object;
  s.object_size = size;
  const scene box = make_cornell_box();  // its camera and light
  add_cornell_room(s.room);
  // Closed at the front (the paper's box room): the cube map must see a surface everywhere. The
  // camera looks in through it: the G-buffer pass culls the room's back faces.
  add_quad(s.room, {1, 0, 1}, {-1, 0, 1}, {-1, 2, 1}, {1, 2, 1}, {0, 0, -1}, glm::vec3(0.73f));
  s.view = box.view;
  s.light = box.light.spot;
  mesh shape;
  if (object == "sphere") {
    add_sphere(shape, glm::vec3(0.0f), 1.0f, 24, 48, glm::vec3(0.8f));  // 2304 triangles, the paper's ~2300
    s.name = "sphere";
  } else {
    shape = load_obj(object);
    for (vertex& v : shape.vertices) v.albedo = glm::vec3(0.8f);
    s.name = std::filesystem::path(object).stem().string();
  }
  const bounding_box box_of_shape = bounds(shape);
  const float scale = size / std::max({box_of_shape.maximum.x - box_of_shape.minimum.x, box_of_shape.maximum.y - box_of_shape.minimum.y,
                                        box_of_shape.maximum.z - box_of_shape.minimum.z, 1e-9f});
  for (vertex& v : shape.vertices) v.position = (v.position - box_of_shape.centre()) * scale;
  for (const vertex& v : shape.vertices) s.object_radius = std::max(s.object_radius, glm::length(v.position));
  s.local_object = std::move(shape);
  s.object = s.local_object;
  for (std::size_t i = 0; i < s.object.vertices.size(); ++i) s.object.vertices[i].position = s.local_object.vertices[i].position + position;
  s.reference_point = position;
  return s;
}

}  // namespace vplkit
