// Scenes the frontend renders: triangle geometry with a diffuse albedo per vertex (times a
// base-colour texture on the triangles a material range names, frontend/scene/material.hpp), a
// camera and up to max_scene_lights lights (spot, directional or point). Built-in scenes are made in code, so the
// default job needs no files; OBJ files load through frontend/scene/obj_loader.hpp, glTF files
// through frontend/scene/gltf_scene.hpp.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <vplkit/direct_light.hpp>

#include "frontend/scene/material.hpp"

namespace vplkit {

struct vertex {
  glm::vec3 position;
  glm::vec3 normal;
  glm::vec3 albedo;  ///< the material's colour factor (the whole albedo where no texture is)
  glm::vec2 texcoord{0.0f};  ///< glTF's TEXCOORD_0 (OBJ: vt with v flipped); read only where a material range has a texture
};

struct mesh {
  std::vector<vertex> vertices;
  std::vector<std::uint32_t> indices;  // triangles, counter-clockwise seen from the normal side
  /// Textured or alpha-tested triangles: ranges of `indices` in increasing order, not
  /// overlapping, each naming a material of `materials`. A triangle outside every range is
  /// plain: its vertex albedo, opaque. Built-in scenes have none. Code that reorders or drops
  /// triangles must keep the ranges (check_mesh refuses ranges that do not fit).
  std::vector<material_range> material_ranges;
  std::shared_ptr<const material_library> materials;
  std::size_t triangle_count() const { return indices.size() / 3; }
};

/// The material of triangle `triangle` (index triple 3 * triangle), or null for a plain one.
const surface_material* material_of_triangle(const mesh& geometry, std::size_t triangle);

/// Albedo (linear RGB) and alpha at the point (1 - u - v) a + u b + v c of triangle `triangle`:
/// the interpolated vertex albedo times the material's texture sampled at the interpolated
/// texture coordinate with level of detail `lod` (material.hpp says how the CPU's level differs
/// from GL's), and the material's alpha.
glm::vec4 surface_albedo_alpha(const mesh& geometry, std::size_t triangle, glm::vec2 barycentric, float lod = 0.0f);

/// Emitted radiance (linear RGB) at the point (1 - u - v) a + u b + v c of triangle `triangle`:
/// material_emission at the interpolated texture coordinate; 0 for a plain triangle.
glm::vec3 surface_emission(const mesh& geometry, std::size_t triangle, glm::vec2 barycentric, float lod = 0.0f);

/// Whether the point is cut out: an alpha-tested (MASK) material with alpha below its cutoff.
bool surface_cut_out(const mesh& geometry, std::size_t triangle, glm::vec2 barycentric, float lod = 0.0f);

struct bounding_box {
  glm::vec3 minimum{0.0f};
  glm::vec3 maximum{0.0f};
  glm::vec3 centre() const { return 0.5f * (minimum + maximum); }
  float radius() const { return 0.5f * glm::length(maximum - minimum); }
};

bounding_box bounds(const mesh& geometry);

/// The largest coordinate magnitude a scene may have. Positions are floats (at 1e7 their step is
/// one unit) and the ray tracer's bounds must stay finite through its arithmetic.
inline constexpr float max_scene_coordinate = 1.0e7f;

/// The largest coordinate magnitude of a loaded mesh: a tenth of the scene's, because frame_mesh
/// puts a floor and a light up to 3 bounding radii from the mesh's centre.
inline constexpr float max_mesh_coordinate = max_scene_coordinate / 10.0f;

/// The largest light intensity (a spot's W/sr) or irradiance (a sun's W/m^2) per channel. The
/// Monte Carlo reference's radiance is at most about 10^4 times it (the 0.01 distance clamp), and
/// a pixel's sum over 2^20 samples stays below 10^31, far from FLT_MAX: its outputs stay finite.
/// (A frame_mesh light of a mesh at max_mesh_coordinate is 2 x 10^13.) Render targets in
/// rgba16f overflow much earlier (65504); the writers refuse a non-finite pixel.
inline constexpr float max_light_power = 1.0e20f;

struct camera {
  glm::vec3 position{0.0f, 1.0f, 3.8f};
  glm::vec3 target{0.0f, 1.0f, 0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float vertical_fov_degrees = 40.0f;
  float near_plane = 0.05f;
  float far_plane = 50.0f;
};

enum class light_kind { spot, directional, point };

/// One of a scene's lights: a spot, a sun or a point light (KHR_lights_punctual's three kinds).
struct scene_light {
  light_kind kind = light_kind::spot;
  spot_light<float> spot;                ///< used when kind == spot
  directional_light<float> directional;  ///< used when kind == directional
  point_light<float> point;              ///< used when kind == point
};

/// The most lights a scene may have: every technique renders each light's own RSM (six for a
/// point light) or VPLs and shadow maps, so the cost grows linearly with them.
inline constexpr std::size_t max_scene_lights = 8;

/// "spot", "directional" or "point".
const char* light_kind_name(light_kind kind);

/// A named node of the file a scene came from (glTF) and the triangles it and its descendants
/// added: indices [first_index, first_index + index_count) of the scene's geometry (the reader
/// walks the tree depth first, so a subtree's triangles are one run). --object-node takes one
/// out of the environment as final gathering's object.
struct scene_node {
  std::string name;
  std::uint32_t first_index = 0;
  std::uint32_t index_count = 0;
};

struct scene {
  std::string name;
  mesh geometry;
  camera view;
  /// The lights, at most max_scene_lights (none is allowed: a scene lit by nothing is black). The
  /// techniques and references sum the light of each; the viewer moves one of them.
  std::vector<scene_light> lights;
  /// One line each: what a loader met and did not read (a glTF feature, once per feature) and
  /// how frame_mesh placed a camera or light the file did not have. The command line prints them.
  std::vector<std::string> notes;
  std::vector<scene_node> nodes;  ///< glTF's named nodes, in the walk's order; empty for other scenes
};

/// Throws vplkit::error starting with `name` at the first bad value: a position that is not
/// finite or beyond max_scene_coordinate, a non-finite normal, albedo or texture coordinate, an
/// index out of range, no triangles, or material ranges that do not fit the indices or name a
/// material or texture that does not exist.
void check_mesh(const mesh& geometry, const std::string& name);
/// The material part of check_mesh: ranges in order on whole triangles within the indices,
/// materials and textures that exist, finite transforms, alpha values in [0, 1], texture levels
/// whose pixels match their size.
void check_materials(const mesh& geometry, const std::string& name);
/// Whether a material of the mesh is alpha-tested (MASK): the passes that draw it need the alpha
/// test; a mesh without cut-outs can be drawn by shaders without it (VPLKIT_MATERIAL_NO_ALPHA_TEST).
bool has_alpha_cutouts(const mesh& geometry);
/// Whether a material range of the mesh names a material that emits: only then is an emission
/// pass drawn (a scene without emission pays nothing for it).
bool has_emission(const mesh& geometry);

/// The scene's light, for code that draws exactly one: throws vplkit::error naming the scene and
/// `what` ("the RSM pipeline") when it has none or several (choose one with --lights k).
const scene_light& single_light(const scene& s, const std::string& what);

/// Throws vplkit::error starting with `owner` when the camera has a non-finite value, bad near/far
/// planes, a field of view outside (0, 180) degrees, its target at its position or its up vector
/// along its view direction.
void check_camera(const camera& view, const std::string& owner);
/// Throws vplkit::error starting with `owner` when the light has a non-finite value, a power
/// beyond max_light_power, or fails its kernel's validate (a zero direction, cone angles out of
/// order, ...).
void check_light(const scene_light& light, const std::string& owner);
/// check_light for each light (named "light k"), and more than max_scene_lights refused.
void check_lights(const std::vector<scene_light>& lights, const std::string& owner);

/// Throws vplkit::error naming the scene and the first bad value: check_mesh's, or a non-finite
/// camera or light value. Loaders check their input as they read it; this is the last gate before
/// a pipeline or the ray tracer sees a scene.
void check_scene(const scene& s);

/// Half-angle of a square shadow-map frustum that holds a spot light's outer cone, with a
/// 2-degree margin, at most 85 degrees.
float spot_light_frustum_half_angle(const spot_light<float>& light);

/// Names accepted by built_in_scene, for help texts and messages.
std::vector<std::string> built_in_scene_names();

/// The Cornell box's room alone: floor, ceiling, back wall, red left and green right wall
/// ([-1, 1] x [0, 2] x [-1, 1], normals pointing in, open towards +z).
void add_cornell_room(mesh& target);

/// The Cornell box (2 x 2 x 2, floor at y = 0, open towards +z) with a tall and a short block,
/// red left wall, green right wall, and a spot light under the ceiling pointing down: the
/// classic light-leak case (the tall block's shadow side should not see the red wall's light
/// through the block).
scene make_cornell_box();

/// The indirect-shadow scene: a brightly lit red wall, a white floor as the receiver, and a
/// white panel standing between them. A directional light from the side opposite the wall
/// lights the wall head-on; behind the panel the floor is directly lit but sees less of the
/// wall, so the panel casts an indirect shadow away from its direct one.
scene make_indirect_shadow_scene();

/// The occluder scene: a red wall lit by a spot light, a floor as the receiver, and a panel
/// (0.7 high, 1.4 wide) standing 0.5 in front of the wall, within reach of the RSM gather: the
/// floor behind it sees less of the wall. `dark_panel` (scene "occluder"): albedo 0.03, so the
/// panel only blocks; otherwise ("occluder-white") it also reflects.
scene make_occluder_scene(bool dark_panel);

/// Triangle count of the atrium at its default tessellation: about the thesis's Sponza (262k).
inline constexpr int atrium_default_tessellation = 56;

/// The atrium, in the spirit of the thesis's Sponza: a 12 x 6 court with two storeys of
/// colonnades and semicircular arches on both long sides, galleries behind them, coloured
/// curtains hanging in every other bay, and a sun (directional light) at an angle that lights
/// one colonnade, so that the other side and the galleries live on bounced light. `tessellation`
/// (4..512) is the number of segments of each column, arch and curtain.
scene make_atrium_scene(int tessellation);

/// Appends a cylinder's side (no caps) standing on `base`, `segments` around, `stacks` high.
void add_cylinder(mesh& target, glm::vec3 base, float radius, float height, int segments, int stacks, glm::vec3 albedo);

/// A room with 16 x 16 instances of a 1024-triangle sphere on its floor: 262,154 triangles,
/// the scale of the thesis's Sponza (262k), for timing the geometry passes.
scene make_instanced_scene();

/// Light Wave's box scene ([LW]): three boxes, 36 triangles, a spot light above them.
scene make_boxes_scene();

/// Light Wave's teapot scenes: the npm `teapot` mesh (992 triangles, meshes/teapot.obj from the
/// setup script) refined by longest-edge bisection to the thesis's 6565 triangles, on a floor;
/// `copies` = 10 gives the ten-teapot scene (65,650 triangles plus the floor).
/// Throws vplkit::error naming the missing file when the mesh has not been fetched.
scene make_teapot_scene(int copies);

/// Splits the longest edge of the mesh (and both triangles beside it, so no crack opens) until
/// it has at least `target_triangles`. Vertices at the same position are welded first; a new
/// vertex takes the mean position, normal (renormalised) and albedo of its edge.
mesh refine_longest_edges(const mesh& source, std::size_t target_triangles);

/// Bisects every triangle at the midpoint of its longest edge, recursively, until no edge is
/// longer than `max_edge`; empty when that takes more than `max_triangles` triangles. Every
/// vertex keeps its triangle's own attributes (a box keeps its flat faces and colours; a new
/// vertex takes the mean of its edge's, the normal renormalised), the new points lie on the
/// triangles' planes, and two triangles that share an edge split it at the same points whatever
/// their attributes (the decision depends on the edge's length alone), so no T-junction opens a
/// crack. Vertices equal in position, normal and albedo are shared.
std::optional<mesh> subdivide_long_edges(const mesh& source, float max_edge, std::size_t max_triangles);

/// Throws vplkit::error listing the known names when `name` is not one of them.
scene built_in_scene(const std::string& name);

/// Appends an axis-aligned quad-faced box (outward normals), rotated about y by `yaw_degrees`.
void add_box(mesh& target, glm::vec3 centre, glm::vec3 size, float yaw_degrees, glm::vec3 albedo);

/// Appends the quad a, b, c, d (counter-clockwise seen from where `normal` points).
void add_quad(mesh& target, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 normal, glm::vec3 albedo);

/// Appends a UV sphere of `stacks` x `slices` quads (2 * stacks * slices triangles, less the
/// degenerate ones at the poles are kept for a uniform count).
void add_sphere(mesh& target, glm::vec3 centre, float radius, int stacks, int slices, glm::vec3 albedo);

/// Sets the light's intensity (a spot's, W/sr) or irradiance (a sun's, W/m^2): its brightest
/// channel becomes `intensity`, its colour kept (white for a black light). Throws vplkit::error
/// for a negative or non-finite value.
void set_light_intensity(scene_light& light, float intensity);
/// The lights scaled together so that the brightest channel of the brightest light becomes
/// `intensity`: their colours and ratios kept (one light: set_light_intensity). Lights all black
/// each become white at `intensity`. Throws vplkit::error for a negative or non-finite value.
void scale_light_intensities(std::vector<scene_light>& lights, float intensity);
/// The light's power per channel: a spot's or point light's intensity (W/sr), a sun's irradiance (W/m^2).
glm::vec3 light_power(const scene_light& light);

/// What frame_mesh places: the file had no camera, no light, or neither.
struct framing_needs {
  bool camera = true;
  bool light = true;
};

/// What frame_mesh's floor adds to a mesh. A loader that sizes its arrays to the mesh leaves
/// this much room, so that adding the floor does not reallocate them: a vector grown past its
/// capacity holds the old and the new array at once (a faceted 2^21-triangle OBJ: 277 MB of
/// vertices twice, the load's peak).
inline constexpr std::size_t framing_floor_vertices = 4;
inline constexpr std::size_t framing_floor_indices = 6;

/// Places a camera and a spot light for a mesh without them (OBJ files, glTF files without a
/// camera or a light; frontend/scene/framing.hpp measures what the mesh is):
/// - a closed room (rays from an inside point meet, in nearly every direction, a surface facing
///   that point, at a median distance of at least a quarter of the bounding radius: not a hollow in
///   an object): the camera inside, below the ceiling, near the wall opposite the room's longest
///   free direction, looking across and down at the contents; the spot light under the ceiling
///   above the camera, aimed at what the camera looks at, its cone wider than the view;
/// - anything else (an object, an open scene): a raised three-quarter view of the bounds (35
///   degrees around from +z, 25 degrees up), the spot light from above on the other side, and a
///   floor under the mesh, added only here, so that the light has somewhere to bounce.
/// Without `needs.light` no floor is added and the light stays default (the caller sets its own).
/// A note says what was placed and how, with the pose as --camera/--light arguments.
scene frame_mesh(std::string name, mesh geometry, framing_needs needs = {});

}  // namespace vplkit
