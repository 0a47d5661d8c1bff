#include "frontend/reference/final_gather_reference.hpp"

#include <vplkit/direct_light.hpp>
#include <vplkit/form_factor.hpp>

namespace vplkit {

namespace {

// Light `light`'s irradiance at (x, n) in double precision, without visibility.
glm::dvec3 light_irradiance(const scene_light& light, const glm::dvec3& x, const glm::dvec3& n) {
  if (light.kind == light_kind::spot) {
    spot_light<double> spot;
    spot.position = light.spot.position;
    spot.direction = light.spot.direction;
    spot.intensity = light.spot.intensity;
    spot.cos_inner = light.spot.cos_inner;
    spot.cos_outer = light.spot.cos_outer;
    return spot_light_irradiance(x, n, spot);
  }
  if (light.kind == light_kind::point) {
    point_light<double> point;
    point.position = light.point.position;
    point.intensity = light.point.intensity;
    return point_light_irradiance(x, n, point);
  }
  directional_light<double> sun;
  sun.direction = light.directional.direction;
  sun.irradiance = light.directional.irradiance;
  return directional_light_irradiance(n, sun);
}

}  // namespace

double final_gather_reference(const final_gather_scene& scene, const glm::dvec3& x, const glm::dvec3& n, int cuts) {
  double total = 0.0;
  for (std::size_t quad = 0; quad + 3 < scene.room.vertices.size(); quad += 4) {
    const glm::dvec3 a(scene.room.vertices[quad].position), b(scene.room.vertices[quad + 1].position), d(scene.room.vertices[quad + 3].position);
    const glm::dvec3 normal(scene.room.vertices[quad].normal), albedo(scene.room.vertices[quad].albedo);
    const glm::dvec3 u = (b - a) / double(cuts), v = (d - a) / double(cuts);
    for (int j = 0; j < cuts; ++j)
      for (int i = 0; i < cuts; ++i) {
        const glm::dvec3 corner = a + u * double(i) + v * double(j);
        glm::dvec3 irradiance(0.0);
        for (const scene_light& light : scene.lights) irradiance += light_irradiance(light, corner + 0.5 * (u + v), normal);
        const glm::dvec3 radiance = albedo / 3.14159265358979323846 * irradiance;
        total += glm::dot(radiance, glm::dvec3(1.0)) * 3.14159265358979323846 *
                 polygon_form_factor(x, n, corner, corner + u, corner + u + v, corner + v);
      }
  }
  return total;
}

}  // namespace vplkit
