#include "frontend/reference/ray_scene.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "frontend/core/error.hpp"
#include "frontend/core/parallel.hpp"
#include "frontend/core/progress.hpp"

namespace vplkit {

struct ray_scene::state {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
};

namespace {

// The alpha test of cut-out (MASK) materials for every ray: a hit where the texture's alpha, at
// level 0, is below the cutoff is not a hit (material.hpp on where this differs from GL).
void skip_cut_outs(const RTCFilterFunctionNArguments* args) {
  const auto* geometry = static_cast<const mesh*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const glm::vec2 barycentric(RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i));
    if (surface_cut_out(*geometry, RTCHitN_primID(args->hit, args->N, i), barycentric)) args->valid[i] = 0;
  }
}

bool has_cut_outs(const mesh& geometry) {
  if (!geometry.materials) return false;
  for (const material_range& range : geometry.material_ranges)
    if (geometry.materials->materials[range.material].alpha_mask) return true;
  return false;
}

}  // namespace

ray_scene::ray_scene(const mesh& geometry) : state_(std::make_unique<state>()), geometry_(geometry) {
  check_mesh(geometry, "ray tracer scene");  // Embree asserts (aborts) on bounds it cannot represent
  // Embree's own threads build the BVH; as many as the frontend's (hardware_threads()).
  const std::string configuration = "threads=" + std::to_string(hardware_threads());
  state_->device = rtcNewDevice(configuration.c_str());
  if (!state_->device) throw error("Embree: could not create a device (error " + std::to_string(rtcGetDeviceError(nullptr)) + ")");
  state_->scene = rtcNewScene(state_->device);
  RTCGeometry triangles = rtcNewGeometry(state_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  // The mesh's own (indexed) arrays, shared rather than copied: positions at the start of each
  // vertex, whose normal follows, so Embree's 16-byte loads of the last position stay inside it.
  static_assert(offsetof(vertex, position) == 0 && sizeof(vertex) >= 16 && sizeof(vertex) % 4 == 0);
  rtcSetSharedGeometryBuffer(triangles, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, geometry.vertices.data(), 0, sizeof(vertex), geometry.vertices.size());
  rtcSetSharedGeometryBuffer(triangles, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, geometry.indices.data(), 0, 3 * sizeof(std::uint32_t),
                             geometry.indices.size() / 3);
  if (has_cut_outs(geometry)) {
    rtcSetGeometryUserData(triangles, const_cast<mesh*>(&geometry));
    rtcSetGeometryIntersectFilterFunction(triangles, skip_cut_outs);
    rtcSetGeometryOccludedFilterFunction(triangles, skip_cut_outs);
  }
  rtcCommitGeometry(triangles);
  rtcAttachGeometry(state_->scene, triangles);
  rtcReleaseGeometry(triangles);
  rtcCommitScene(state_->scene);
  if (rtcGetDeviceError(state_->device) != RTC_ERROR_NONE) throw error("Embree: building the scene failed");
}

ray_scene::~ray_scene() {
  rtcReleaseScene(state_->scene);
  rtcReleaseDevice(state_->device);
}

namespace {

bool within(const glm::vec3& v, float limit) {
  return std::fabs(v.x) <= limit && std::fabs(v.y) <= limit && std::fabs(v.z) <= limit;  // false for NaN
}

std::string text_of(const glm::vec3& v) {
  char text[96];
  std::snprintf(text, sizeof text, "(%g, %g, %g)", static_cast<double>(v.x), static_cast<double>(v.y), static_cast<double>(v.z));
  return text;
}

}  // namespace

ray_scene::hit ray_scene::intersect(const glm::vec3& origin, const glm::vec3& direction, float far) const {
  // What Embree's ray.valid() asserts, with margin: a ray it would abort on is an error here.
  if (!within(origin, max_ray_coordinate) || !within(direction, max_ray_coordinate) || !(glm::dot(direction, direction) > 0.0f) || !(far >= 1e-4f))
    throw error("ray tracer: refused a ray from " + text_of(origin) + " along " + text_of(direction) +
                " (not finite, or beyond " + count_text(static_cast<double>(max_ray_coordinate)) + ")");
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit query{};
  query.ray.org_x = origin.x;
  query.ray.org_y = origin.y;
  query.ray.org_z = origin.z;
  query.ray.dir_x = direction.x;
  query.ray.dir_y = direction.y;
  query.ray.dir_z = direction.z;
  query.ray.tnear = 1e-4f;
  query.ray.tfar = far;
  query.ray.mask = 0xffffffffu;
  query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(state_->scene, &context, &query);
  hit result;
  if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID) return result;
  const std::size_t triangle = query.hit.primID;
  const vertex& a = geometry_.vertices[geometry_.indices[3 * triangle]];
  const vertex& b = geometry_.vertices[geometry_.indices[3 * triangle + 1]];
  const vertex& c = geometry_.vertices[geometry_.indices[3 * triangle + 2]];
  const float u = query.hit.u, v = query.hit.v;
  result.found = true;
  result.distance = query.ray.tfar;
  result.position = origin + direction * query.ray.tfar;
  result.normal = glm::normalize((1.0f - u - v) * a.normal + u * b.normal + v * c.normal);
  result.triangle = triangle;
  result.barycentric = glm::vec2(u, v);
  result.albedo = glm::vec3(surface_albedo_alpha(geometry_, triangle, result.barycentric));
  return result;
}

bool ray_scene::occluded(const glm::vec3& from, const glm::vec3& to) const {
  if (!within(from, max_ray_coordinate) || !within(to, max_ray_coordinate))
    throw error("ray tracer: refused a shadow ray from " + text_of(from) + " to " + text_of(to) + " (not finite, or beyond " +
                count_text(static_cast<double>(max_ray_coordinate)) + ")");
  const glm::vec3 d = to - from;
  const float length = glm::length(d);
  if (!(length > 0.0f)) return false;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray{};
  ray.org_x = from.x;
  ray.org_y = from.y;
  ray.org_z = from.z;
  ray.dir_x = d.x / length;
  ray.dir_y = d.y / length;
  ray.dir_z = d.z / length;
  ray.tnear = 1e-4f * std::max(1.0f, length);
  ray.tfar = length * (1.0f - 1e-4f) - 1e-4f;
  ray.mask = 0xffffffffu;
  rtcOccluded1(state_->scene, &context, &ray);
  return ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

camera_rays::camera_rays(const camera& view, int width, int height) : width_(width), height_(height) {
  if (width < 1 || height < 1) throw error("camera rays: the image size " + std::to_string(width) + "x" + std::to_string(height) + " is empty");
  const glm::dmat4 projection = glm::perspective(glm::radians(static_cast<double>(view.vertical_fov_degrees)),
                                                 static_cast<double>(width) / static_cast<double>(height), static_cast<double>(view.near_plane),
                                                 static_cast<double>(view.far_plane));
  const glm::dmat4 view_matrix = glm::lookAt(glm::dvec3(view.position), glm::dvec3(view.target), glm::dvec3(view.up));
  inverse_ = glm::inverse(projection * view_matrix);
  // The rays in between interpolate the corners' near and far points: finite corners, finite rays.
  for (const glm::ivec2 corner : {glm::ivec2(0, 0), glm::ivec2(width - 1, 0), glm::ivec2(0, height - 1), glm::ivec2(width - 1, height - 1)}) {
    const ray r = at(corner.x, corner.y);
    if (!within(r.origin, max_ray_coordinate) || !within(r.direction, 1.5f) || !(glm::dot(r.direction, r.direction) > 0.5f))
      throw error("camera at " + text_of(view.position) + " (near " + std::to_string(view.near_plane) + ", far " + std::to_string(view.far_plane) +
                  "): its ray through pixel (" + std::to_string(corner.x) + ", " + std::to_string(corner.y) + ") is not finite");
  }
}

camera_rays::ray camera_rays::at(int x, int y_from_top) const {
  const glm::dvec2 ndc((static_cast<double>(x) + 0.5) / static_cast<double>(width_) * 2.0 - 1.0,
                       1.0 - (static_cast<double>(y_from_top) + 0.5) / static_cast<double>(height_) * 2.0);
  const glm::dvec4 near_point = inverse_ * glm::dvec4(ndc, -1.0, 1.0), far_point = inverse_ * glm::dvec4(ndc, 1.0, 1.0);
  const glm::dvec3 origin = glm::dvec3(near_point) / near_point.w;
  const glm::dvec3 direction = glm::normalize(glm::dvec3(far_point) / far_point.w - origin);
  return {glm::vec3(origin), glm::vec3(direction)};
}

}  // namespace vplkit
