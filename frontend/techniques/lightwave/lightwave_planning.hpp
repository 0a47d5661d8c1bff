// Light Wave's planning ([LW], chapter 4; docs/lightwave-shadows.md): what the pipeline decides on
// the CPU, without GL: the flux energy's receivers (the scene subdivided, their sample points, the
// grids and uniform blocks of the sum), its VPLs from the light's view of the scene and a ray's
// samples merged, and the shadow casters (drawn the thesis's way, or grouped by importance, and
// the matrices aimed at what they light). The library links no GL: its tests run in the kernel
// test binary (tests/frontend/techniques/test_lightwave_planning.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <vplkit/lightwave.hpp>

#include "frontend/image/image.hpp"
#include "frontend/scene/camera.hpp"
#include "frontend/scene/scene.hpp"

namespace vplkit {

/// The most VPL shadow maps a frame uses (accurate or integrated): the size of the shader's
/// arrays of shadow matrices and casters, which it gets as VPLKIT_MAX_SHADOW_MAPS.
constexpr int lightwave_max_shadow_maps = 64;

/// The integrated shadows of a point light (lightwave_pipeline::integrated_by_importance): the
/// in-between lookups of two maps run only where their view directions (their VPLs' normals) are
/// within acos(0.9) = 26 degrees: interpolating a fragment's coordinates between two maps stands
/// for a light between their VPLs only when the two views nearly agree; between a floor's map and
/// a wall's (90 degrees apart) the in-between points land on unrelated texels of either map
/// (measured on three rooms, docs/scenes.md: worst 0.89 of the reference with the limit, 0.87
/// stepping between every pair). Each map's own lookup still votes in every pair.
constexpr float lightwave_integrated_pair_cos = 0.9f;

enum class lightwave_mode { direct = 0, faked = 1, unshadowed = 2, accurate = 3, integrated = 4 };

enum class lightwave_shadow_variant { importance = 0, thesis = 1 };

/// What the VPLs carry. thesis: strength 1 - attenuation, no distance falloff, on hemispheres
/// in space (Eq. 4.1, 4.2, 4.5: the Tables 5.x); flux: the flux the light brings to each ray's patch
/// of its cone, reflected where the ray meets the scene, with a diffuse bounce's falloff.
enum class lightwave_energy { thesis = 0, flux = 1 };

/// The side of the square map of what the spot light sees (position, normal, albedo) in which the
/// flux layout looks its rays up: under half a degree a texel for a cone 120 degrees across, finer than
/// the layout's samples (the VPL sits where its ray meets the texel's plane, not at the texel).
constexpr int lightwave_surface_map_size = 256;

/// A grid of width x rows >= `receivers` texels, receiver i at texel (i % width, i / width), for
/// the fragment pass that sums the flux energy's VPLs: rows a multiple of 4 (a software
/// rasteriser shades 4x4 blocks; a 2-row grid left half of each block's lanes idle, +40 % on the
/// boxes) and as few as rows of at most 1024 allow; the width a multiple of 4 too, wider than 1024
/// where the rows would pass `max_side` (the caller checks the width against the GL's largest
/// texture).
glm::ivec2 lightwave_receiver_grid(std::size_t receivers, int max_side);

/// The grid of one band of lightwave_capture.frag, which sums lightwave_sum_receivers receivers
/// per fragment: lightwave_receiver_grid of ceil(receivers / lightwave_sum_receivers) texels with
/// at most max_texture_side / lightwave_sum_receivers rows, so that the bands stacked hold every
/// receiver in one texture of at most max_texture_side rows.
glm::ivec2 lightwave_sum_grid(std::size_t receivers, int max_texture_side);

/// The passes (uniform blocks) that sum `vpls` VPLs per_pass at a time: at least one.
int lightwave_vpl_pass_count(std::size_t vpls, int per_pass);

/// The receivers' VPLs as the uniform blocks of lightwave_capture.frag's passes: per_pass VPLs a
/// block (the last one's tail zero), three vec4 each, [position | radius], [normal | 0], [flux | 0];
/// block k at byte k x stride_bytes (a multiple of 16 and of the GL's offset alignment, at least
/// 48 x per_pass). At least one block.
std::vector<glm::vec4> lightwave_vpl_blocks(const std::vector<lightwave_flux_vpl<float>>& vpls, int per_pass, std::size_t stride_bytes);

/// The mesh whose vertices the flux energy's indirect light is summed at: `geometry` subdivided
/// (subdivide_long_edges) until no edge exceeds `spacing` times its bounding radius (the setting
/// receiver_spacing), the bound grown by half until at most `max_triangles` triangles result.
/// The thesis sums Eq. 4.5 at the scene's own vertices, which a diffuse bounce's falloff cannot
/// afford: a wall's corner vertices see the floor that lights it edge-on (docs/lightwave-shadows.md).
mesh lightwave_receivers(const mesh& geometry, float spacing, int max_triangles);

/// Where the flux energy evaluates each vertex's indirect light: the mean of the centroids of the
/// triangles that use the vertex, moved into the vertex's tangent plane. Inside a surface that is
/// the vertex, near enough; on its border it lies inside the surface, a third of a triangle in:
/// a wall's bottom vertex sits in the plane of the floor that lights the wall and gets none of its
/// light (the floor is seen edge-on), while the wall just above gets the most, and interpolating
/// from the corner would darken the whole band of triangles along it.
std::vector<glm::vec3> lightwave_receiver_samples(const mesh& receivers);

/// Bytes of a depth texture array of `maps` layers of width x height 32-bit depths: the memory
/// figure of Eq. 5.4 / 5.5 (3840 x 2160 x 21 x 4 bytes = 664.45 MiB).
std::uint64_t lightwave_shadow_map_bytes(int width, int height, int maps);

/// Indices of the VPLs of the layout (`angle_deg`, `per_ray`) that get shadow maps in the thesis's
/// way: `maps` distinct VPLs drawn uniformly with the seed (accurate), or the axis VPL and
/// `maps` - 1 at equal turns apart, 45 degrees off the axis, of the innermost hemisphere
/// (integrated: "equidistant, for maximum coverage"); none for the other modes.
std::vector<int> lightwave_shadow_vpls(lightwave_mode mode, int angle_deg, int per_ray, int maps, std::uint32_t seed);

/// A surface point the shadow casters are chosen and aimed for.
struct lightwave_receiver_point {
  glm::vec3 position;
  glm::vec3 normal;
};

/// One accurate indirect shadow map of the importance variant: the group of VPLs it stands for
/// and the VPL it is rendered from.
struct lightwave_shadow_caster {
  int vpl = 0;  ///< the VPL the map is rendered from (an index into the pipeline's VPLs)
  /// The group as one light, for the share of a fragment's indirect light the map stands for:
  /// its members' power-weighted position and normal, their spread (the RMS distance from that
  /// position, with their own patch radii), and their total power (the channel mean of the flux,
  /// or the thesis's 1 - attenuation).
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 1.0f, 0.0f};
  float radius = 0.0f;
  float power = 0.0f;
  std::vector<int> members;  ///< the group's VPLs (indices into the pipeline's VPLs)
};

/// What lightwave_cluster_casters needs of a VPL.
struct lightwave_cluster_vpl {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 1.0f, 0.0f};
  float importance = 0.0f;  ///< its light on the visible scene; 0: no group
  float power = 0.0f;
  float radius = 0.0f;
};

/// Splits the VPLs of importance > 0 into `count` groups (fewer when fewer VPLs light anything),
/// each compact and of about equal importance: a k-d split at the importance median along the
/// widest extent of position and normal (the normal scaled by `normal_scale`, scene units),
/// recursively. Each group's map is rendered from its medoid: the member nearest the group's
/// importance-weighted mean position and normal, the one point whose view stands best for the
/// group's. Deterministic: no seed, so the shadows do not depend on one.
std::vector<lightwave_shadow_caster> lightwave_cluster_casters(const std::vector<lightwave_cluster_vpl>& vpls, int count, float normal_scale);

/// The flux VPLs the receivers sum: the samples of one ray of the layout (layout index modulo
/// `rays`) that met one plane (unit normals within 1e-3 of each other, positions within
/// `plane_tolerance` of the first's plane) merged into one VPL: their flux summed, at their
/// flux-weighted mean position, with the radius of their patches' total area (sqrt of the sum
/// of the radii squared). Beyond a few patch radii the merged VPL gives the receivers the light
/// of its samples (the same flux from the same patch of surface); closer, the exitance of their
/// joint patch. Samples of a ray that met different surfaces stay apart. The order: by the first
/// sample's place in `vpls`. The capture sums per_ray times fewer VPLs. `merged_index`, when
/// given, receives for each of `vpls` the merged VPL it went into.
std::vector<lightwave_flux_vpl<float>> lightwave_merge_ray_samples(const std::vector<lightwave_flux_vpl<float>>& vpls, const std::vector<int>& layout_index,
                                                                   int rays, float plane_tolerance, std::vector<int>* merged_index = nullptr);

/// The view-projection of a shadow map from `eye` that holds the points of weight > 0: looking at
/// their weighted mean direction, with the field of view of the farthest of them plus a margin
/// (at most 160 degrees; points beyond do not vote). Looks along `fallback_direction` with
/// `fallback_fov_degrees` when no point has weight.
glm::mat4 lightwave_aimed_shadow_matrix(const glm::vec3& eye, const glm::vec3& fallback_direction, const std::vector<lightwave_receiver_point>& points,
                                        const std::vector<float>& weights, float near_plane, float far_plane, float aspect, float fallback_fov_degrees);


/// The VPLs of either energy as the shadow casters see them: where each is, its normal, its
/// power and its weight (the light it gives) at a point. Exactly one of thesis and flux is set.
struct lightwave_vpl_view {
  const std::vector<lightwave_vpl<float>>* thesis = nullptr;
  const std::vector<lightwave_flux_vpl<float>>* flux = nullptr;
  float min_distance = 0.01f;  ///< the flux VPLs' distance clamp
  std::size_t size() const { return thesis ? thesis->size() : flux->size(); }
  glm::vec3 position(std::size_t i) const { return thesis ? (*thesis)[i].position : (*flux)[i].position; }
  glm::vec3 normal(std::size_t i) const { return thesis ? (*thesis)[i].normal : (*flux)[i].normal; }
  float weight(std::size_t i, const lightwave_receiver_point& point) const {
    return thesis ? lightwave_vpl_weight(point.position, point.normal, (*thesis)[i])
                  : lightwave_bounce_weight(point.position, point.normal, (*flux)[i], min_distance);
  }
  float power(std::size_t i) const {
    if (thesis) return std::max(0.0f, 1.0f - (*thesis)[i].attenuation);
    const glm::vec3& f = (*flux)[i].flux;
    return (f.x + f.y + f.z) / 3.0f;
  }
  float radius(std::size_t i) const { return thesis ? 0.0f : (*flux)[i].radius; }
};

/// Points spread over the surface of `geometry` in proportion to area (systematic over the
/// triangles' cumulative areas, barycentric coordinates from the hash), with a camera (`view`,
/// null: none) kept when it can see them (inside its frustum, facing it): what the shadow casters
/// are chosen and aimed for. Vertices alone would weigh a 36-triangle box scene by its corners;
/// for the thesis energy, without the camera test the underside of the floor would draw VPLs below it.
std::vector<lightwave_receiver_point> lightwave_surface_points(const mesh& geometry, const camera* view, float aspect, int count);

/// The accurate shadows' importance variant: each VPL's light on `points`, then
/// lightwave_cluster_casters into `maps` groups (normals scaled by `normal_scale`). With
/// `merged` (the flux energy's receiver VPLs, lightwave_merge_ray_samples, and `merged_of`, each
/// VPL's merged one) the light is summed for the merged VPLs and shared by flux: the samples of a
/// patch light a distant point alike, and the sum costs per_ray times less. Sums on every core,
/// each in a fixed order: the result does not depend on the threads.
std::vector<lightwave_shadow_caster> lightwave_importance_casters(const lightwave_vpl_view& view, const std::vector<lightwave_receiver_point>& points,
                                                                  const std::vector<lightwave_flux_vpl<float>>* merged, const std::vector<int>& merged_of,
                                                                  int maps, float normal_scale);

/// The thesis's casters (lightwave_shadow_vpls' layout indices) among the VPLs there are: with
/// `flux_layout_index` (the flux energy keeps only the VPLs that carry light, in layout order)
/// a drawn VPL that carries none gets no map.
std::vector<lightwave_shadow_caster> lightwave_layout_casters(const std::vector<int>& layout_indices, const std::vector<int>* flux_layout_index);

/// A view from `position` along `direction` (up: +y, or -z when looking nearly straight up or down).
glm::mat4 lightwave_look_along(const glm::vec3& position, const glm::vec3& direction);

/// The flux energy's VPLs: each ray of `cone`'s layout (lightwave_cone_sample) looked up in the
/// map of what the spot light sees (`positions` with w = 1 where a surface is, `normals`,
/// `albedos`, square, drawn with `light_view_projection`); a ray that meets a lit surface inside
/// the cone gets a VPL there reflecting the flux its patch brings (lightwave_ray_flux), in layout
/// order. `layout_index` receives each VPL's index in the layout.
std::vector<lightwave_flux_vpl<float>> lightwave_flux_vpls_from_map(const spot_light<float>& light, const lightwave_cone_settings<float>& cone,
                                                                   const glm::mat4& light_view_projection, const image& positions, const image& normals,
                                                                   const image& albedos, std::vector<int>& layout_index);

/// What a light sees through one map: world position (w = 1 where a surface is), normal and
/// albedo per texel of square images drawn with `view_projection`.
struct lightwave_surface_map {
  glm::mat4 view_projection{1.0f};
  const image* positions = nullptr;
  const image* normals = nullptr;
  const image* albedos = nullptr;
};

/// A point light's flux VPLs: each sample of the sphere layout (lightwave_sphere_sample around
/// cone.light_direction) looked up in the cube face its direction falls in (cube_face_of; `faces`
/// in OpenGL's order, each a 90-degree view from the light), a VPL where it meets a surface that
/// faces the light, reflecting lightwave_ray_flux(point), in sample order; `layout_index` gets
/// each VPL's sample index.
std::vector<lightwave_flux_vpl<float>> lightwave_point_flux_vpls(const point_light<float>& light, const lightwave_cone_settings<float>& cone,
                                                                 const std::array<lightwave_surface_map, 6>& faces, std::vector<int>& layout_index);

/// A sun's flux VPLs: each sample of the parallel layout (lightwave_parallel_sample of angle_deg,
/// per_ray) a ray along the light's direction from `view_origin` + (x right + y up) half_extent,
/// (`right`, `up` unit, spanning the orthographic map `map` of half-side half_extent), a VPL where
/// it meets a surface that faces the light, reflecting lightwave_ray_flux(directional) of its
/// share of the window's area, in sample order; `layout_index` gets each VPL's sample index.
std::vector<lightwave_flux_vpl<float>> lightwave_sun_flux_vpls(const directional_light<float>& light, int angle_deg, int per_ray,
                                                               const glm::vec3& view_origin, const glm::vec3& right, const glm::vec3& up, float half_extent,
                                                               const lightwave_surface_map& map, std::vector<int>& layout_index);

/// The ray each flux sample belongs to, for lightwave_merge_ray_samples (which merges the
/// samples of one ray on one plane): a spot's and a sun's ray is the layout index modulo its
/// rays; a point light's sphere has twice the rays of a hemisphere, the second hemisphere's after
/// the first's (two rays of the same number on either side must not merge). Returns the ray of
/// each of `layout_index` and sets `rays` to their count.
std::vector<int> lightwave_sample_rays(light_kind kind, int angle_deg, int per_ray, const std::vector<int>& layout_index, int& rays);

}  // namespace vplkit
