#include "frontend/reference/reference.hpp"

#include <vplkit/shading.hpp>

#include <embree3/rtcore.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>

#include <vplkit/direct_light.hpp>
#include <vplkit/hash.hpp>
#include <vplkit/irradiance.hpp>
#include <vplkit/rsm_gather.hpp>
#include <vplkit/transform.hpp>

#include "frontend/core/error.hpp"
#include "frontend/core/parallel.hpp"
#include "frontend/techniques/rsm/rsm_cpu_mirror.hpp"

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
  auto* vertices = static_cast<float*>(
      rtcSetNewGeometryBuffer(triangles, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), geometry.vertices.size()));
  for (std::size_t i = 0; i < geometry.vertices.size(); ++i)
    for (int k = 0; k < 3; ++k) vertices[3 * i + static_cast<std::size_t>(k)] = geometry.vertices[i].position[k];
  auto* indices = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(triangles, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), geometry.indices.size() / 3));
  for (std::size_t i = 0; i < geometry.indices.size(); ++i) indices[i] = geometry.indices[i];
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

ray_scene::hit ray_scene::intersect(const glm::vec3& origin, const glm::vec3& direction, float far) const {
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

glm::vec3 direct_irradiance(const ray_scene& rays, const scene_light& light, const irradiance_settings<float>& irradiance, const glm::vec3& x,
                            const glm::vec3& n) {
  if (light.kind == light_kind::spot) {
    const glm::vec3 e = spot_light_irradiance(x, n, light.spot, irradiance);
    if (e == glm::vec3(0.0f)) return e;
    return rays.occluded(x + n * 1e-4f, light.spot.position) ? glm::vec3(0.0f) : e;
  }
  const glm::vec3 e = directional_light_irradiance(n, light.directional);
  if (e == glm::vec3(0.0f)) return e;
  return rays.occluded(x + n * 1e-4f, x - light.directional.direction * 100.0f) ? glm::vec3(0.0f) : e;
}

glm::vec3 one_bounce_irradiance(const ray_scene& rays, const scene_light& light, const irradiance_settings<float>& irradiance, const glm::vec3& x,
                                const glm::vec3& n, int samples, std::uint32_t seed, std::uint32_t key) {
  return one_bounce_irradiance(rays, rays, light, irradiance, x, n, samples, seed, key);
}

glm::vec3 one_bounce_irradiance(const ray_scene& bounce_rays, const ray_scene& light_rays, const scene_light& light,
                                const irradiance_settings<float>& irradiance, const glm::vec3& x, const glm::vec3& n, int samples,
                                std::uint32_t seed, std::uint32_t key) {
  // Cosine-weighted directions about n: the estimator of the irradiance integral is pi times the
  // mean of the radiances found.
  const glm::vec3 helper = std::abs(n.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  const glm::vec3 u = glm::normalize(glm::cross(helper, n)), v = glm::cross(n, u);
  glm::vec3 sum(0.0f);
  const std::uint32_t base = hash_combine(seed, key);
  for (int s = 0; s < samples; ++s) {
    const std::uint32_t h = hash_combine(base, static_cast<std::uint32_t>(s));
    const float r1 = uniform_float_from_bits(h), r2 = uniform_float_from_bits(hash_uint32(h));
    const float radius = std::sqrt(r1), angle = 6.28318530717958647692f * r2;
    const glm::vec3 direction = glm::normalize(u * (radius * std::cos(angle)) + v * (radius * std::sin(angle)) + n * std::sqrt(std::max(0.0f, 1.0f - r1)));
    const ray_scene::hit y = bounce_rays.intersect(x + n * 1e-4f, direction);
    if (!y.found || glm::dot(y.normal, direction) >= 0.0f) continue;  // nothing, or the back of a surface
    sum += diffuse_radiance(y.albedo, direct_irradiance(light_rays, light, irradiance, y.position, y.normal), 1.0f, glm::vec3(0.0f));
  }
  return sum * (3.14159265358979323846f / static_cast<float>(std::max(samples, 1)));
}

namespace {
double now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
}  // namespace

progress_bar::progress_bar(std::string label, std::size_t total)
    : label_(std::move(label)), total_(std::max<std::size_t>(total, 1)), terminal_(isatty(2) != 0), start_(now_seconds()) {}

void progress_bar::advance(std::size_t done) {
  const std::size_t now = done_ += done;
  if (!terminal_) return;
  const int percent = static_cast<int>(100 * now / total_);
  int last = last_percent_.load();
  if (percent == last || !last_percent_.compare_exchange_strong(last, percent)) return;
  const double elapsed = now_seconds() - start_;
  const double eta = now > 0 ? elapsed * static_cast<double>(total_ - now) / static_cast<double>(now) : 0.0;
  const int filled = percent / 4;
  std::fprintf(stderr, "\r%s [%-25s] %3d%% ETA %4.0fs", label_.c_str(), std::string(static_cast<std::size_t>(filled), '=').c_str(), percent, eta);
  std::fflush(stderr);
}

void progress_bar::finish() {
  if (terminal_) std::fprintf(stderr, "\r%s done in %.1fs%40s\n", label_.c_str(), now_seconds() - start_, "");
}

namespace {

image empty_indirect(const rsm_frame_constants& constants) {
  image out;
  out.width = constants.indirect_size.x;
  out.height = constants.indirect_size.y;
  out.texels.assign(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height), glm::vec4(0.0f));
  return out;
}

// The ray that decides whether pixel light (q, nq) lights receiver (p, n): both ends lifted off
// their surfaces by a small offset along their normals, so that neither surface blocks its own
// end.
bool light_occluded(const ray_scene& rays, const glm::vec3& p, const glm::vec3& n, const glm::vec3& q, const glm::vec3& nq) {
  return rays.occluded(p + n * 1e-3f, q + nq * 1e-3f);
}

}  // namespace

image reference_rsm_gather(const ray_scene& rays, const rsm_pass_buffers& buffers, const rsm_frame_constants& constants,
                                  const rsm_brute_force_options& options) {
  if (options.receiver_stride < 1) throw error("brute-force RSM gather: receiver_stride must be >= 1");
  if (!(options.max_radius >= 0.0f)) throw error("brute-force RSM gather: max_radius must be >= 0");
  image out = empty_indirect(constants);
  // Every lit RSM texel is a pixel light.
  // Eq. 3.2 in the light's eye space, like the gather's receivers; the occlusion rays in the world,
  // each light's world position and normal computed once.
  struct light_texel {
    glm::vec3 position, normal, flux;
    glm::vec2 texel_centre;
    glm::vec3 world_position, world_normal;
  };
  const glm::mat4 to_world = glm::inverse(constants.light.view);
  std::vector<light_texel> lights;
  const std::vector<rsm_texel<float>> rsm = unpack_rsm(buffers, constants);
  for (int y = 0; y < buffers.rsm.height; ++y)
    for (int x = 0; x < buffers.rsm.width; ++x) {
      const rsm_texel<float>& texel = rsm[static_cast<std::size_t>(y) * static_cast<std::size_t>(buffers.rsm.width) + static_cast<std::size_t>(x)];
      if (texel.position.z < 0.0f && texel.flux != glm::vec3(0.0f))
        lights.push_back({texel.position, texel.normal, texel.flux, glm::vec2(x, y) + 0.5f, transform_point(to_world, texel.position),
                          transform_direction(to_world, texel.normal)});
    }
  const int stride = options.receiver_stride;
  const int rows = (out.height + stride - 1) / stride;
  progress_bar progress(options.exact_visibility ? "brute-force RSM gather with visibility" : "brute-force RSM gather", static_cast<std::size_t>(rows));
  const float radius_squared = options.max_radius * options.max_radius;
  parallel_for(rows, options.threads, [&](int row) {
    const int y = row * stride;
    for (int x = 0; x < out.width; x += stride) {
      const std::optional<gather_receiver<float>> receiver = gather_receiver_at(glm::ivec2(x, y), buffers, constants);
      if (!receiver) continue;
      const glm::vec3 p = receiver->position, n = receiver->normal;
      const glm::vec3 world_p = transform_point(to_world, p), world_n = transform_direction(to_world, n);
      glm::vec3 all(0.0f), seen(0.0f);
      for (const light_texel& light : lights) {
        if (radius_squared > 0.0f) {
          const glm::vec2 d = light.texel_centre - receiver->rsm_coordinate;
          if (glm::dot(d, d) > radius_squared) continue;
        }
        const glm::vec3 e = pixel_light_irradiance(p, n, light.position, light.normal, light.flux, constants.gather.irradiance);
        if (e == glm::vec3(0.0f)) continue;
        all += e;
        if (!options.exact_visibility || !light_occluded(rays, world_p, world_n, light.world_position, light.world_normal)) seen += e;
      }
      const float total = all.x + all.y + all.z;
      out.at(glm::ivec2(x, y)) = glm::vec4(seen * 0.318309886183790671538f, total > 0.0f ? (seen.x + seen.y + seen.z) / total : 1.0f);
    }
    progress.advance();
  });
  progress.finish();
  return out;
}

namespace {

// The visibility object of gather_rsm_with: a ray per sample, in the world (the gather's points
// are in the light's eye space).
// One object per receiver: its world position and normal are computed once, not per sample.
struct ray_cast_visibility {
  const ray_scene& rays;
  const glm::mat4& to_world;
  glm::vec3 receiver_position, receiver_normal;  ///< world space
  ray_cast_visibility(const ray_scene& scene_rays, const glm::mat4& light_to_world, const gather_receiver<float>& receiver)
      : rays(scene_rays),
        to_world(light_to_world),
        receiver_position(transform_point(light_to_world, receiver.position)),
        receiver_normal(transform_direction(light_to_world, receiver.normal)) {}
  void begin_path() {}
  float operator()(const gather_receiver<float>&, const rsm_texel<float>& light) const {
    return light_occluded(rays, receiver_position, receiver_normal, transform_point(to_world, light.position), transform_direction(to_world, light.normal))
               ? 0.0f
               : 1.0f;
  }
};

}  // namespace

image gather_with_ray_cast_visibility(const ray_scene& rays, const rsm_pass_buffers& buffers, const rsm_frame_constants& constants,
                                             int receiver_stride, int threads) {
  if (receiver_stride < 1) throw error("gather with ray-cast visibility: receiver_stride must be >= 1");
  image out = empty_indirect(constants);
  const std::vector<rsm_texel<float>> rsm = unpack_rsm(buffers, constants);
  const auto fetch = [&](glm::ivec2 texel) {
    return rsm[static_cast<std::size_t>(texel.y) * static_cast<std::size_t>(buffers.rsm.width) + static_cast<std::size_t>(texel.x)];
  };
  const glm::mat4 to_world = glm::inverse(constants.light.view);
  const int rows = (out.height + receiver_stride - 1) / receiver_stride;
  parallel_for(rows, threads, [&](int row) {
    const int y = row * receiver_stride;
    for (int x = 0; x < out.width; x += receiver_stride) {
      const glm::ivec2 texel(x, y);
      const std::optional<gather_receiver<float>> receiver = gather_receiver_at(texel, buffers, constants);
      if (!receiver) continue;
      const glm::vec3 e = constants.technique.pattern == rsm_pattern::disk
                              ? gather_rsm_with<rsm_pattern::disk>(*receiver, fetch, constants.gather, ray_cast_visibility(rays, to_world, *receiver))
                              : gather_rsm_with<rsm_pattern::radial>(*receiver, fetch, constants.gather, ray_cast_visibility(rays, to_world, *receiver));
      out.at(texel) = glm::vec4(e, buffers.gbuffer[0].at(gbuffer_texel_of(texel, constants)).w);
    }
  });
  return out;
}

std::vector<std::uint8_t> rsm_covered_receivers(const rsm_pass_buffers& buffers, const rsm_frame_constants& constants, int receiver_stride) {
  if (receiver_stride < 1) throw error("covered receivers: receiver_stride must be >= 1");
  std::vector<std::uint8_t> covered(static_cast<std::size_t>(constants.indirect_size.x) * static_cast<std::size_t>(constants.indirect_size.y), 0);
  for (int y = 0; y < constants.indirect_size.y; y += receiver_stride)
    for (int x = 0; x < constants.indirect_size.x; x += receiver_stride) {
      const std::optional<gather_receiver<float>> receiver = gather_receiver_at(glm::ivec2(x, y), buffers, constants);
      if (!receiver) continue;
      const glm::vec2 projection = receiver->rsm_coordinate;
      const bool in_front = receiver->position.z < 0.0f;  // light eye space
      const bool inside = projection.x >= 0.0f && projection.y >= 0.0f && projection.x < static_cast<float>(constants.gather.rsm_size.x) &&
                          projection.y < static_cast<float>(constants.gather.rsm_size.y);
      covered[static_cast<std::size_t>(y) * static_cast<std::size_t>(constants.indirect_size.x) + static_cast<std::size_t>(x)] = in_front && inside ? 1 : 0;
    }
  return covered;
}

namespace {

// GL's texture level of detail at a camera ray's hit: where the rays through the next pixel to the
// right and the next one down meet the hit triangle's plane, in texels of the material's
// texture; the larger step (GL's isotropic rho) as log2. On a plane this is the difference GL
// takes across a pixel quad. 0 (level 0) where there is no texture or no usable step.
float camera_ray_lod(const mesh& geometry, const ray_scene::hit& hit, const glm::vec3 origins[2], const glm::vec3 directions[2]) {
  const surface_material* material = material_of_triangle(geometry, hit.triangle);
  if (!material || material->texture < 0) return 0.0f;
  const texture_level& level = geometry.materials->textures[static_cast<std::size_t>(material->texture)].levels.front();
  const vertex& a = geometry.vertices[geometry.indices[3 * hit.triangle]];
  const vertex& b = geometry.vertices[geometry.indices[3 * hit.triangle + 1]];
  const vertex& c = geometry.vertices[geometry.indices[3 * hit.triangle + 2]];
  const glm::vec3 e1 = b.position - a.position, e2 = c.position - a.position, plane = glm::cross(e1, e2);
  const float area = glm::dot(plane, plane);
  if (!(area > 0.0f)) return 0.0f;
  const auto texel_coordinate = [&](const glm::vec3& p) {
    // Barycentrics of p in the triangle's plane.
    const glm::vec3 w = p - a.position;
    const float u = glm::dot(glm::cross(w, e2), plane) / area, v = glm::dot(glm::cross(e1, w), plane) / area;
    const glm::vec2 uv = material_texture_coordinate(*material, (1.0f - u - v) * a.texcoord + u * b.texcoord + v * c.texcoord);
    return uv * glm::vec2(static_cast<float>(level.width), static_cast<float>(level.height));
  };
  const glm::vec2 centre = texel_coordinate(hit.position);
  float rho = 0.0f;
  for (int k = 0; k < 2; ++k) {
    const float along = glm::dot(directions[k], plane);
    if (!(std::fabs(along) > 0.0f)) return 0.0f;
    const float t = glm::dot(a.position - origins[k], plane) / along;
    if (!(t > 0.0f) || !std::isfinite(t)) return 0.0f;
    rho = std::max(rho, glm::length(texel_coordinate(origins[k] + t * directions[k]) - centre));
  }
  return rho > 0.0f && std::isfinite(rho) ? std::log2(rho) : 0.0f;
}

}  // namespace

one_bounce_images reference_one_bounce(const scene& source, int width, int height, int samples, std::uint32_t seed, int threads) {
  const ray_scene rays(source.geometry);
  const glm::mat4 inverse = glm::inverse(camera_projection_matrix(source.view, static_cast<float>(width) / static_cast<float>(height)) *
                                         camera_view_matrix(source.view));
  const irradiance_settings<float> irradiance;
  one_bounce_images out;
  out.radiance = image(width, height, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  out.indirect = out.radiance;
  progress_bar progress("one-bounce Monte Carlo reference", static_cast<std::size_t>(height));
  // Rows counted from the top (the estimate's seed key is y * width + x), stored bottom-up.
  // The ray through the centre of pixel (x, y), y counted from the top.
  const auto pixel_ray = [&](int x, int y, glm::vec3& origin, glm::vec3& direction) {
    const glm::vec2 ndc((static_cast<float>(x) + 0.5f) / static_cast<float>(width) * 2.0f - 1.0f,
                        1.0f - (static_cast<float>(y) + 0.5f) / static_cast<float>(height) * 2.0f);
    const glm::vec4 near_point = inverse * glm::vec4(ndc, -1.0f, 1.0f), far_point = inverse * glm::vec4(ndc, 1.0f, 1.0f);
    origin = glm::vec3(near_point) / near_point.w;
    direction = glm::normalize(glm::vec3(far_point) / far_point.w - origin);
  };
  parallel_for(height, threads, [&](int y) {
    for (int x = 0; x < width; ++x) {
      glm::vec3 origin, direction;
      pixel_ray(x, y, origin, direction);
      ray_scene::hit hit = rays.intersect(origin, direction);
      if (!hit.found) continue;
      if (material_of_triangle(source.geometry, hit.triangle)) {
        glm::vec3 origins[2], directions[2];
        pixel_ray(x + 1, y, origins[0], directions[0]);
        pixel_ray(x, y + 1, origins[1], directions[1]);
        hit.albedo = glm::vec3(surface_albedo_alpha(source.geometry, hit.triangle, hit.barycentric, camera_ray_lod(source.geometry, hit, origins, directions)));
      }
      const glm::vec3 n = glm::dot(hit.normal, direction) < 0.0f ? hit.normal : -hit.normal;
      const std::uint32_t key = static_cast<std::uint32_t>(y * width + x);
      const glm::vec3 direct = direct_irradiance(rays, source.light, irradiance, hit.position, n);
      const glm::vec3 bounce = one_bounce_irradiance(rays, source.light, irradiance, hit.position, n, samples, seed, key);
      out.radiance.at(x, height - 1 - y) = glm::vec4(diffuse_radiance(hit.albedo, direct, 1.0f, bounce), 1.0f);
      out.indirect.at(x, height - 1 - y) = glm::vec4(bounce, 1.0f);
    }
    progress.advance();
  });
  progress.finish();
  return out;
}

}  // namespace vplkit
