#include "frontend/reference/final_gather_reference.hpp"

#include <vplkit/direct_light.hpp>
#include <vplkit/form_factor.hpp>

namespace vplkit {

double final_gather_reference(const final_gather_scene& scene, const glm::dvec3& x, const glm::dvec3& n, int cuts) {
  spot_light<double> light;
  light.position = scene.light.position;
  light.direction = scene.light.direction;
  light.intensity = scene.light.intensity;
  light.cos_inner = scene.light.cos_inner;
  light.cos_outer = scene.light.cos_outer;
  double total = 0.0;
  for (std::size_t quad = 0; quad + 3 < scene.room.vertices.size(); quad += 4) {
    const glm::dvec3 a(scene.room.vertices[quad].position), b(scene.room.vertices[quad + 1].position), d(scene.room.vertices[quad + 3].position);
    const glm::dvec3 normal(scene.room.vertices[quad].normal), albedo(scene.room.vertices[quad].albedo);
    const glm::dvec3 u = (b - a) / double(cuts), v = (d - a) / double(cuts);
    for (int j = 0; j < cuts; ++j)
      for (int i = 0; i < cuts; ++i) {
        const glm::dvec3 corner = a + u * double(i) + v * double(j);
        const glm::dvec3 radiance = albedo / 3.14159265358979323846 * spot_light_irradiance(corner + 0.5 * (u + v), normal, light);
        total += glm::dot(radiance, glm::dvec3(1.0)) * 3.14159265358979323846 *
                 polygon_form_factor(x, n, corner, corner + u, corner + u + v, corner + v);
      }
  }
  return total;
}

}  // namespace vplkit
