#include "frontend/reference/reference.hpp"

#include <vplkit/shading.hpp>

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <numeric>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/direct_light.hpp>
#include <vplkit/hash.hpp>
#include <vplkit/irradiance.hpp>
#include <vplkit/rsm_gather.hpp>
#include <vplkit/transform.hpp>

#include "frontend/core/error.hpp"
#include "frontend/core/parallel.hpp"
#include "frontend/scene/camera.hpp"
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

namespace {

// The brute-force gather's pixel lights and per-receiver work, shared by the run and its estimate.
class brute_force_gather {
 public:
  brute_force_gather(const ray_scene& rays, const rsm_pass_buffers& buffers, const rsm_frame_constants& constants, const rsm_brute_force_options& options)
      : rays_(rays), buffers_(buffers), constants_(constants), options_(options), to_world_(glm::inverse(constants.light.view)) {
    if (options.receiver_stride < 1) throw error("brute-force RSM gather: receiver_stride must be >= 1");
    if (!(options.max_radius >= 0.0f)) throw error("brute-force RSM gather: max_radius must be >= 0");
    // Every lit RSM texel is a pixel light. Eq. 3.2 in the light's eye space, like the gather's
    // receivers; the occlusion rays in the world, each light's world position and normal computed once.
    const std::vector<rsm_texel<float>> rsm = unpack_rsm(buffers, constants);
    for (int y = 0; y < buffers.rsm.height; ++y)
      for (int x = 0; x < buffers.rsm.width; ++x) {
        const rsm_texel<float>& texel = rsm[static_cast<std::size_t>(y) * static_cast<std::size_t>(buffers.rsm.width) + static_cast<std::size_t>(x)];
        if (texel.position.z < 0.0f && texel.flux != glm::vec3(0.0f))
          lights_.push_back({texel.position, texel.normal, texel.flux, glm::vec2(x, y) + 0.5f, transform_point(to_world_, texel.position),
                             transform_direction(to_world_, texel.normal)});
      }
    columns_ = (constants.indirect_size.x + options.receiver_stride - 1) / options.receiver_stride;
    rows_ = (constants.indirect_size.y + options.receiver_stride - 1) / options.receiver_stride;
  }

  std::size_t light_count() const { return lights_.size(); }
  /// Receivers computed (every stride-th per axis), numbered row by row.
  std::uint64_t receiver_count() const { return static_cast<std::uint64_t>(columns_) * static_cast<std::uint64_t>(rows_); }
  glm::ivec2 texel_of(std::uint64_t receiver) const {
    return glm::ivec2(static_cast<int>(receiver % static_cast<std::uint64_t>(columns_)), static_cast<int>(receiver / static_cast<std::uint64_t>(columns_))) *
           options_.receiver_stride;
  }

  /// [irradiance | visible fraction] at the receiver of `texel`, nothing where there is none.
  std::optional<glm::vec4> gather(glm::ivec2 texel) const {
    const std::optional<gather_receiver<float>> receiver = gather_receiver_at(texel, buffers_, constants_);
    if (!receiver) return std::nullopt;
    const glm::vec3 p = receiver->position, n = receiver->normal;
    const glm::vec3 world_p = transform_point(to_world_, p), world_n = transform_direction(to_world_, n);
    const float radius_squared = options_.max_radius * options_.max_radius;
    glm::vec3 all(0.0f), seen(0.0f);
    for (const light_texel& light : lights_) {
      if (radius_squared > 0.0f) {
        const glm::vec2 d = light.texel_centre - receiver->rsm_coordinate;
        if (glm::dot(d, d) > radius_squared) continue;
      }
      const glm::vec3 e = pixel_light_irradiance(p, n, light.position, light.normal, light.flux, constants_.gather.irradiance);
      if (e == glm::vec3(0.0f)) continue;
      all += e;
      if (!options_.exact_visibility || !light_occluded(rays_, world_p, world_n, light.world_position, light.world_normal)) seen += e;
    }
    const float total = all.x + all.y + all.z;
    return glm::vec4(seen * 0.318309886183790671538f, total > 0.0f ? (seen.x + seen.y + seen.z) / total : 1.0f);
  }

 private:
  struct light_texel {
    glm::vec3 position, normal, flux;
    glm::vec2 texel_centre;
    glm::vec3 world_position, world_normal;
  };
  const ray_scene& rays_;
  const rsm_pass_buffers& buffers_;
  const rsm_frame_constants& constants_;
  rsm_brute_force_options options_;
  glm::mat4 to_world_;
  std::vector<light_texel> lights_;
  int columns_ = 0, rows_ = 0;
};

// Items in a scrambled order: k -> k * stride mod count, with a stride coprime with the count
// near 0.618 count. The finished part is then a sample of the whole image (not its empty top
// rows first), so the progress and its time left are fair from the start.
class scrambled_order {
 public:
  explicit scrambled_order(std::uint64_t count) : count_(std::max<std::uint64_t>(count, 1)) {
    stride_ = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(0.6180339887 * static_cast<double>(count_)));
    while (std::gcd(stride_, count_) != 1) ++stride_;
  }
  std::uint64_t operator()(std::uint64_t k) const { return k * stride_ % count_; }  // k, stride < count <= 2^31: no overflow

 private:
  std::uint64_t count_, stride_ = 1;
};

// Runs `work(i)` for `count` items spread evenly over [0, total) on `threads` and returns the wall time.
template <typename Work>
double time_sample(std::uint64_t total, std::uint64_t count, int threads, const Work& work) {
  const double start = steady_seconds();
  parallel_for(static_cast<int>(count), threads, [&](int k) {
    work(static_cast<std::uint64_t>((static_cast<double>(k) + 0.5) / static_cast<double>(count) * static_cast<double>(total)));
  });
  return steady_seconds() - start;
}

}  // namespace

image reference_rsm_gather(const ray_scene& rays, const rsm_pass_buffers& buffers, const rsm_frame_constants& constants,
                                  const rsm_brute_force_options& options, const progress_settings& progress_to) {
  const brute_force_gather gather(rays, buffers, constants, options);
  image out = empty_indirect(constants);
  progress_monitor progress(options.exact_visibility ? "brute-force RSM gather with visibility" : "brute-force RSM gather", gather.receiver_count(),
                            "receivers", progress_to);
  const int columns = (out.width + options.receiver_stride - 1) / options.receiver_stride;
  const int rows = (out.height + options.receiver_stride - 1) / options.receiver_stride;
  const scrambled_order order(static_cast<std::uint64_t>(rows));
  parallel_for(rows, options.threads, [&](int k) {
    const auto row = static_cast<int>(order(static_cast<std::uint64_t>(k)));
    for (int column = 0; column < columns && !progress.stopped(); ++column) {
      const glm::ivec2 texel = gather.texel_of(static_cast<std::uint64_t>(row) * static_cast<std::uint64_t>(columns) + static_cast<std::uint64_t>(column));
      if (const std::optional<glm::vec4> value = gather.gather(texel)) out.at(texel) = *value;
      progress.advance();
    }
  });
  progress.finish();
  return out;
}

reference_cost estimate_rsm_gather(const ray_scene& rays, const rsm_pass_buffers& buffers, const rsm_frame_constants& constants,
                                   const rsm_brute_force_options& options) {
  const brute_force_gather gather(rays, buffers, constants, options);
  reference_cost cost;
  cost.units = gather.receiver_count();
  cost.unit = "receivers";
  const double pairs = static_cast<double>(cost.units) * static_cast<double>(gather.light_count());
  cost.rays = options.exact_visibility ? pairs : 0.0;
  cost.what = count_text(static_cast<double>(cost.units)) + " receivers x " + count_text(static_cast<double>(gather.light_count())) + " lit RSM texels" +
              (options.exact_visibility ? ", a shadow ray per pair with light" : " (no rays: no visibility)");
  // A receiver costs a shadow ray per lit texel (a 512^2 RSM: up to 262144): a few are enough.
  const std::uint64_t sample = std::min<std::uint64_t>(cost.units, static_cast<std::uint64_t>(std::max(options.threads, 8)));
  if (sample == 0) return cost;
  const double seconds = time_sample(cost.units, sample, options.threads, [&](std::uint64_t receiver) { (void)gather.gather(gather.texel_of(receiver)); });
  cost.seconds = seconds * static_cast<double>(cost.units) / static_cast<double>(sample);
  return cost;
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
  // The coverage's coarse lights as the frame gathered them (none without coverage).
  const std::vector<coarse_light<float>> coarse = coarse_lights_of(buffers);
  const int blocks = buffers.coarse[0].width;
  const auto coarse_fetch = [&](glm::ivec2 block) {
    return coarse[static_cast<std::size_t>(block.y) * static_cast<std::size_t>(blocks) + static_cast<std::size_t>(block.x)];
  };
  const auto gather = [&](const gather_receiver<float>& receiver) {
    ray_cast_visibility visibility(rays, to_world, receiver);
    if (constants.technique.pattern == rsm_pattern::disk)
      return coarse.empty() ? gather_rsm_with<rsm_pattern::disk>(receiver, fetch, constants.gather, visibility)
                            : gather_rsm_with<rsm_pattern::disk>(receiver, fetch, coarse_fetch, constants.gather, visibility);
    return coarse.empty() ? gather_rsm_with<rsm_pattern::radial>(receiver, fetch, constants.gather, visibility)
                          : gather_rsm_with<rsm_pattern::radial>(receiver, fetch, coarse_fetch, constants.gather, visibility);
  };
  const int rows = (out.height + receiver_stride - 1) / receiver_stride;
  parallel_for(rows, threads, [&](int row) {
    const int y = row * receiver_stride;
    for (int x = 0; x < out.width; x += receiver_stride) {
      const glm::ivec2 texel(x, y);
      const std::optional<gather_receiver<float>> receiver = gather_receiver_at(texel, buffers, constants);
      if (!receiver) continue;
      const glm::vec3 e = gather(*receiver);
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

// One pixel of the Monte Carlo reference: [radiance, indirect irradiance], whether the camera
// sees the back of the surface (its normal faces away), nothing for a miss.
struct one_bounce_pixel {
  glm::vec3 radiance, indirect;
  bool back_facing = false;
};

std::optional<one_bounce_pixel> trace_one_bounce_pixel(const ray_scene& rays, const scene& source, const camera_rays& primary, int x, int y, int width,
                                                       int samples, std::uint32_t seed) {
  const irradiance_settings<float> irradiance;
  const camera_rays::ray ray = primary.at(x, y);
  ray_scene::hit hit = rays.intersect(ray.origin, ray.direction);
  if (!hit.found) return std::nullopt;
  if (material_of_triangle(source.geometry, hit.triangle)) {
    // A textured surface at GL's level of detail: the rays through the next pixel to the right
    // and the next one down (camera_ray_lod).
    const camera_rays::ray right = primary.at(x + 1, y), down = primary.at(x, y + 1);
    const glm::vec3 origins[2] = {right.origin, down.origin}, directions[2] = {right.direction, down.direction};
    hit.albedo = glm::vec3(surface_albedo_alpha(source.geometry, hit.triangle, hit.barycentric, camera_ray_lod(source.geometry, hit, origins, directions)));
  }
  // The surface is lit on the side its normal faces, wherever the camera is: as the GL techniques
  // light it (their G-buffers, RSMs and Light Wave's receivers keep the mesh's normals), and as the
  // bounce below treats the surfaces it meets. A reference that turned the normal towards the
  // camera would light the back of a one-sided surface that no technique lights, and a scene
  // with reversed faces would read as a technique's missing light.
  const glm::vec3& n = hit.normal;
  const std::uint32_t key = static_cast<std::uint32_t>(y * width + x);
  const glm::vec3 direct = direct_irradiance(rays, source.light, irradiance, hit.position, n);
  const glm::vec3 bounce = samples > 0 ? one_bounce_irradiance(rays, source.light, irradiance, hit.position, n, samples, seed, key) : glm::vec3(0.0f);
  return one_bounce_pixel{diffuse_radiance(hit.albedo, direct, 1.0f, bounce), bounce, glm::dot(hit.normal, ray.direction) > 0.0f};
}

}  // namespace

one_bounce_images reference_one_bounce(const ray_scene& rays, const scene& source, int width, int height, int samples, std::uint32_t seed, int threads,
                                       const progress_settings& progress_to) {
  const camera_rays primary(source.view, width, height);
  one_bounce_images out;
  out.radiance = image(width, height, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  out.indirect = out.radiance;
  progress_monitor progress("one-bounce Monte Carlo reference", static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height), "pixels",
                            progress_to);
  std::atomic<std::uint64_t> back_facing{0};
  // Rows counted from the top (the estimate's seed key is y * width + x), stored bottom-up.
  const scrambled_order order(static_cast<std::uint64_t>(height));
  parallel_for(height, threads, [&](int k) {
    const auto y = static_cast<int>(order(static_cast<std::uint64_t>(k)));
    for (int x = 0; x < width && !progress.stopped(); ++x) {
      if (const std::optional<one_bounce_pixel> pixel = trace_one_bounce_pixel(rays, source, primary, x, y, width, samples, seed)) {
        out.radiance.at(x, height - 1 - y) = glm::vec4(pixel->radiance, 1.0f);
        out.indirect.at(x, height - 1 - y) = glm::vec4(pixel->indirect, 1.0f);
        if (pixel->back_facing) back_facing.fetch_add(1, std::memory_order_relaxed);
      }
      progress.advance();
    }
  });
  progress.finish();
  out.back_facing_pixels = back_facing.load();
  return out;
}

one_bounce_images reference_one_bounce(const scene& source, int width, int height, int samples, std::uint32_t seed, int threads) {
  const ray_scene rays(source.geometry);
  return reference_one_bounce(rays, source, width, height, samples, seed, threads);
}

reference_cost estimate_one_bounce(const ray_scene& rays, const scene& source, int width, int height, int samples, std::uint32_t seed, int threads) {
  const camera_rays primary(source.view, width, height);
  reference_cost cost;
  cost.units = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
  cost.unit = "pixels";
  cost.rays = static_cast<double>(cost.units) * (2.0 + 2.0 * static_cast<double>(samples));
  cost.what = count_text(static_cast<double>(cost.units)) + " pixels x (a camera and a shadow ray + " + std::to_string(samples) +
              " x (a bounce and a shadow ray))";
  // Two timed runs over the same pixels, without and with some samples: a pixel's cost is
  // linear in its samples, and the difference isolates the part that is.
  const std::uint64_t sample = std::min<std::uint64_t>(cost.units, 2048);
  const int calibration_samples = std::min(samples, 32);
  const auto run = [&](int with_samples) {
    return time_sample(cost.units, sample, threads, [&](std::uint64_t pixel) {
      (void)trace_one_bounce_pixel(rays, source, primary, static_cast<int>(pixel % static_cast<std::uint64_t>(width)),
                                   static_cast<int>(pixel / static_cast<std::uint64_t>(width)), width, with_samples, seed);
    });
  };
  const double base = run(0), with = run(calibration_samples);
  const double per_sample = std::max(with - base, 0.0) / static_cast<double>(calibration_samples);
  cost.seconds = (base + per_sample * static_cast<double>(samples)) * static_cast<double>(cost.units) / static_cast<double>(sample);
  return cost;
}

}  // namespace vplkit
