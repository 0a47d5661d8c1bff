// Surface materials of users' scenes: a base-colour texture with its sampler and texture
// transform, an alpha test (glTF's alphaMode MASK) and an emission, for ranges of a mesh's
// triangles. What a surface's albedo and emission are, in one place for every reader of them:
//
//   albedo   = vertex.albedo (the material's colour factor) x texture.rgb (sRGB decoded)
//   alpha    = alpha_factor x texture.a; with alpha_mask, a fragment (or a ray's hit) whose alpha
//              is below alpha_cutoff is not there at all: it is not drawn, casts no shadow, blocks
//              no ray and reflects no light.
//   emission = material.emission (glTF's emissiveFactor x KHR_materials_emissive_strength) x
//              emission texture.rgb (sRGB decoded, its own sampler and transform, the same texture
//              coordinate set as the base colour's): radiance leaving the side the surface's normal
//              faces, added to what the camera sees there. It lights nothing: no technique or
//              reference takes it as a light (docs/scenes.md, "Emissive materials").
//
// Texture coordinates follow glTF: (0, 0) is the image's top-left corner and v grows downwards
// (the OBJ reader flips its vt's v). The GL passes sample with the sampler's wrap modes and
// filters and the mipmaps made here (frontend/gl/mesh_buffers.hpp, shaders/surface_material.glsl);
// the CPU references sample the same texels with sample_texture. Where the two differ: GL chooses
// the mip level from screen-space derivatives per 2x2 pixel quad (and isotropically, from the
// larger axis); the CPU has no derivatives, so its callers pass a level of detail: the Monte
// Carlo reference's camera rays compute GL's from ray differentials (the same value on a plane),
// every other ray (bounces, shadow rays and the alpha test of a cut-out) samples level 0, the
// texel itself. Both filters preserve a texture's mean over an area, so areas agree; a pixel can
// differ by up to the texture's contrast within the footprint of one pixel at grazing angles.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "frontend/image/texture_decode.hpp"

namespace vplkit {

enum class texture_wrap : std::uint8_t { repeat, clamp_to_edge, mirrored_repeat };
enum class texture_filter : std::uint8_t { nearest, linear };

/// A glTF sampler: wrap per axis, the magnification filter, the minification filter within a
/// level and between levels (mipmaps false: level 0 only).
struct texture_sampler {
  texture_wrap wrap_s = texture_wrap::repeat;
  texture_wrap wrap_t = texture_wrap::repeat;
  texture_filter mag = texture_filter::linear;
  texture_filter min = texture_filter::linear;
  bool mipmaps = true;
  texture_filter between_levels = texture_filter::linear;
};

/// One level of a texture: RGBA8, RGB sRGB-encoded, alpha linear, rows top-down.
struct texture_level {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba8;
};

/// A decoded texture with its full mip chain (level i + 1 halves level i per axis, rounding down,
/// at least 1; each texel the mean of the 2x2, 2x1 or 1x2 texels below it, in linear light).
struct texture {
  std::string name;
  std::vector<texture_level> levels;
};

/// The mip chain of level 0 (make_texture's; the GL upload and the CPU sampler read these levels).
texture make_texture(std::string name, texture_level level0);

struct surface_material {
  std::string name;
  int texture = -1;  ///< into material_library::textures; -1: no texture (the vertex albedo alone)
  texture_sampler sampler;
  /// KHR_texture_transform: uv' = texture_matrix * uv + texture_offset.
  glm::mat2 texture_matrix{1.0f};
  glm::vec2 texture_offset{0.0f};
  float alpha_factor = 1.0f;  ///< baseColorFactor.a
  bool alpha_mask = false;    ///< alphaMode MASK
  float alpha_cutoff = 0.5f;
  /// Emitted radiance (linear RGB, each in [0, max_emission]) before the emission texture; 0: none.
  glm::vec3 emission{0.0f};
  int emission_texture = -1;  ///< into material_library::textures; -1: the factor alone
  texture_sampler emission_sampler;
  glm::mat2 emission_texture_matrix{1.0f};  ///< the emission texture's KHR_texture_transform
  glm::vec2 emission_texture_offset{0.0f};
};

/// The largest emitted radiance per channel: the largest finite value of an rgba16f render target
/// (65504, the techniques' default output format) rounded down, so that the emission alone stays
/// finite in any technique's image (the reflected light added to it is not bounded here).
inline constexpr float max_emission = 6.0e4f;

/// Whether the material emits (a channel of its emission above 0).
inline bool emits(const surface_material& material) { return material.emission.r > 0.0f || material.emission.g > 0.0f || material.emission.b > 0.0f; }

/// The textures and materials a mesh's material ranges name; shared between copies of a mesh.
struct material_library {
  std::vector<texture> textures;
  std::vector<surface_material> materials;
};

/// RGBA8 bytes of a width x height texture with its whole mip chain (make_texture's levels).
std::uint64_t texture_bytes_with_mipmaps(std::uint64_t width, std::uint64_t height);

/// What one scene's textures may take once decoded: every texture's levels, mipmaps included,
/// count against one budget (texture_limits::max_scene_bytes, 1 GiB by default), and a texture
/// that would pass it is refused from its header, before it is decoded.
class texture_budget {
 public:
  /// `origin` names the setting in messages ("gltf_limits::textures.max_scene_bytes").
  texture_budget(std::uint64_t max_bytes, std::string origin) : max_bytes_(max_bytes), origin_(std::move(origin)) {}
  /// Decodes `encoded` (decode_texture with `limits`) into `library` after charging its size with
  /// mipmaps; returns its index. Throws vplkit::error starting with `what` (the scene file, the
  /// image and its file) and naming the budget when the scene's textures would pass it.
  int decode_into(material_library& library, std::string_view encoded, const std::string& what, std::string texture_name, const texture_limits& limits);
  std::uint64_t used_bytes() const { return used_bytes_; }

 private:
  std::uint64_t max_bytes_;
  std::string origin_;
  std::uint64_t used_bytes_ = 0;
};

/// Triangles [first_index, first_index + index_count) of a mesh's index list use `material`.
struct material_range {
  std::uint32_t first_index = 0;
  std::uint32_t index_count = 0;
  std::uint32_t material = 0;
};

/// Linear RGB and alpha of `t` at texture coordinate `uv` (after the material's transform), with
/// GL's rules for the wrap modes, the filters and the level of detail `lod` (log2 of texels per
/// pixel: <= 0 magnifies with sampler.mag at level 0, > 0 minifies with sampler.min and, with
/// mipmaps, between the levels).
glm::vec4 sample_texture(const texture& t, const texture_sampler& sampler, glm::vec2 uv, float lod);

/// The texture coordinate the material samples at for a vertex coordinate (its transform).
glm::vec2 material_texture_coordinate(const surface_material& material, glm::vec2 texcoord);
/// The same for the material's emission texture (its own transform).
glm::vec2 material_emission_coordinate(const surface_material& material, glm::vec2 texcoord);

/// The emitted radiance of `material` at vertex texture coordinate `texcoord`: its emission times
/// its emission texture sampled with level of detail `lod` (sample_texture's rules). 0 for a
/// material that does not emit, whatever its texture.
glm::vec3 material_emission(const material_library& library, const surface_material& material, glm::vec2 texcoord, float lod);

/// 8-bit sRGB code -> linear value (the table GL's sRGB decode is specified by).
float srgb8_to_linear(std::uint8_t code);

}  // namespace vplkit
