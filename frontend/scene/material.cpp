#include "frontend/scene/material.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "frontend/core/error.hpp"
#include "frontend/image/image.hpp"

namespace vplkit {

namespace {

const std::array<float, 256>& srgb_table() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> values{};
    for (int code = 0; code < 256; ++code) values[static_cast<std::size_t>(code)] = srgb_to_linear(static_cast<float>(code) / 255.0f);
    return values;
  }();
  return table;
}

// The texel index GL's wrap mode gives integer coordinate i of a side of `size` texels.
int wrap_index(int i, int size, texture_wrap wrap) {
  switch (wrap) {
    case texture_wrap::clamp_to_edge: return std::clamp(i, 0, size - 1);
    case texture_wrap::repeat: {
      const int m = i % size;
      return m < 0 ? m + size : m;
    }
    case texture_wrap::mirrored_repeat: {
      int m = i % (2 * size);
      if (m < 0) m += 2 * size;
      return m < size ? m : 2 * size - 1 - m;
    }
  }
  return 0;
}

glm::vec4 texel(const texture_level& level, int x, int y) {
  const std::uint8_t* p = &level.rgba8[(static_cast<std::size_t>(y) * static_cast<std::size_t>(level.width) + static_cast<std::size_t>(x)) * 4];
  const std::array<float, 256>& table = srgb_table();
  return glm::vec4(table[p[0]], table[p[1]], table[p[2]], static_cast<float>(p[3]) / 255.0f);
}

// A coordinate far outside [0, 1] would overflow the integer texel index; any wrap mode repeats
// or clamps long before.
float bounded(float value) { return std::isfinite(value) ? std::clamp(value, -1.0e6f, 1.0e6f) : 0.0f; }

glm::vec4 sample_level(const texture_level& level, const texture_sampler& sampler, glm::vec2 uv, texture_filter filter) {
  const float s = bounded(uv.x) * static_cast<float>(level.width), t = bounded(uv.y) * static_cast<float>(level.height);
  if (filter == texture_filter::nearest)
    return texel(level, wrap_index(static_cast<int>(std::floor(s)), level.width, sampler.wrap_s),
                 wrap_index(static_cast<int>(std::floor(t)), level.height, sampler.wrap_t));
  const float x = s - 0.5f, y = t - 0.5f;
  const float x0 = std::floor(x), y0 = std::floor(y);
  const float a = x - x0, b = y - y0;
  const int i0 = static_cast<int>(x0), j0 = static_cast<int>(y0);
  const int i[2] = {wrap_index(i0, level.width, sampler.wrap_s), wrap_index(i0 + 1, level.width, sampler.wrap_s)};
  const int j[2] = {wrap_index(j0, level.height, sampler.wrap_t), wrap_index(j0 + 1, level.height, sampler.wrap_t)};
  return (1.0f - a) * (1.0f - b) * texel(level, i[0], j[0]) + a * (1.0f - b) * texel(level, i[1], j[0]) + (1.0f - a) * b * texel(level, i[0], j[1]) +
         a * b * texel(level, i[1], j[1]);
}

// "1 GiB", "300 MiB", "1000 bytes": the budget as its messages show it.
std::string budget_text(std::uint64_t bytes) {
  if (bytes >= (std::uint64_t{1} << 30) && bytes % (std::uint64_t{1} << 30) == 0) return std::to_string(bytes >> 30) + " GiB";
  if (bytes >= (std::uint64_t{1} << 20) && bytes % (std::uint64_t{1} << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
  return std::to_string(bytes) + " bytes";
}

}  // namespace

float srgb8_to_linear(std::uint8_t code) { return srgb_table()[code]; }

texture make_texture(std::string name, texture_level level0) {
  texture out;
  out.name = std::move(name);
  out.levels.push_back(std::move(level0));
  while (out.levels.back().width > 1 || out.levels.back().height > 1) {
    const texture_level& above = out.levels.back();
    texture_level next;
    next.width = std::max(1, above.width / 2);
    next.height = std::max(1, above.height / 2);
    next.rgba8.resize(static_cast<std::size_t>(next.width) * static_cast<std::size_t>(next.height) * 4);
    // The 2x2 block above each texel (one column or row when that side was already 1; an odd
    // side's last column or row is dropped, as GL's box filter does for non-power-of-two sides).
    const int step_x = above.width > 1 ? 2 : 1, step_y = above.height > 1 ? 2 : 1;
    for (int y = 0; y < next.height; ++y)
      for (int x = 0; x < next.width; ++x) {
        glm::vec4 sum(0.0f);
        for (int dy = 0; dy < step_y; ++dy)
          for (int dx = 0; dx < step_x; ++dx) sum += texel(above, x * step_x + dx, y * step_y + dy);
        const glm::vec4 mean = sum / static_cast<float>(step_x * step_y);
        std::uint8_t* p = &next.rgba8[(static_cast<std::size_t>(y) * static_cast<std::size_t>(next.width) + static_cast<std::size_t>(x)) * 4];
        for (int c = 0; c < 3; ++c) p[c] = linear_to_srgb8(mean[c]);
        p[3] = static_cast<std::uint8_t>(std::lround(std::clamp(mean.a, 0.0f, 1.0f) * 255.0f));
      }
    out.levels.push_back(std::move(next));
  }
  return out;
}

std::uint64_t texture_bytes_with_mipmaps(std::uint64_t width, std::uint64_t height) {
  std::uint64_t bytes = 0;
  for (;;) {
    bytes += 4 * width * height;
    if (width <= 1 && height <= 1) return bytes;
    width = std::max<std::uint64_t>(1, width / 2);
    height = std::max<std::uint64_t>(1, height / 2);
  }
}

int texture_budget::decode_into(material_library& library, std::string_view encoded, const std::string& what, std::string texture_name,
                                const texture_limits& limits) {
  // The header's size against the per-texture limits first (a claim of 2^32 x 2^32 must not reach
  // the sum below), then against what is left of the scene's budget, before anything is decoded.
  const texture_size claimed = claimed_texture_size(encoded);
  if (claimed.width >= 1 && claimed.height >= 1 && claimed.width <= static_cast<std::uint64_t>(limits.max_side) &&
      claimed.height <= static_cast<std::uint64_t>(limits.max_side)) {
    const std::uint64_t bytes = texture_bytes_with_mipmaps(claimed.width, claimed.height);
    if (used_bytes_ + bytes > max_bytes_)
      throw error(what + ": its " + std::to_string(claimed.width) + "x" + std::to_string(claimed.height) + " texels with mipmaps (" + std::to_string(bytes) +
                  " bytes) would bring the scene's decoded textures to " + std::to_string(used_bytes_ + bytes) + " bytes, more than the " +
                  budget_text(max_bytes_) + " budget for a scene's textures (" + origin_ + ")");
  }
  texture_pixels pixels = decode_texture(encoded, what, limits);
  // The decoded size is charged too: it is what was allocated, whatever the header said.
  const std::uint64_t bytes = texture_bytes_with_mipmaps(static_cast<std::uint64_t>(pixels.width), static_cast<std::uint64_t>(pixels.height));
  if (used_bytes_ + bytes > max_bytes_)
    throw error(what + ": its decoded texels with mipmaps (" + std::to_string(bytes) + " bytes) would bring the scene's decoded textures to " +
                std::to_string(used_bytes_ + bytes) + " bytes, more than the " + budget_text(max_bytes_) + " budget for a scene's textures (" + origin_ + ")");
  used_bytes_ += bytes;
  library.textures.push_back(make_texture(std::move(texture_name), texture_level{pixels.width, pixels.height, std::move(pixels.rgba8)}));
  return static_cast<int>(library.textures.size() - 1);
}

glm::vec2 material_texture_coordinate(const surface_material& material, glm::vec2 texcoord) {
  return material.texture_matrix * texcoord + material.texture_offset;
}

glm::vec2 material_emission_coordinate(const surface_material& material, glm::vec2 texcoord) {
  return material.emission_texture_matrix * texcoord + material.emission_texture_offset;
}

glm::vec3 material_emission(const material_library& library, const surface_material& material, glm::vec2 texcoord, float lod) {
  if (!emits(material)) return glm::vec3(0.0f);
  if (material.emission_texture < 0) return material.emission;
  const texture& t = library.textures[static_cast<std::size_t>(material.emission_texture)];
  return material.emission * glm::vec3(sample_texture(t, material.emission_sampler, material_emission_coordinate(material, texcoord), lod));
}

glm::vec4 sample_texture(const texture& t, const texture_sampler& sampler, glm::vec2 uv, float lod) {
  if (t.levels.empty()) return glm::vec4(1.0f);
  if (!(lod > 0.0f)) return sample_level(t.levels.front(), sampler, uv, sampler.mag);  // NaN: level 0
  if (!sampler.mipmaps) return sample_level(t.levels.front(), sampler, uv, sampler.min);
  const float top = static_cast<float>(t.levels.size() - 1);
  const float level = std::min(lod, top);
  if (sampler.between_levels == texture_filter::nearest) {
    // GL: the level ceil(lod + 0.5) - 1, i.e. lod rounded with halves down.
    const auto chosen = static_cast<std::size_t>(std::max(0.0f, std::ceil(level + 0.5f) - 1.0f));
    return sample_level(t.levels[chosen], sampler, uv, sampler.min);
  }
  const auto lower = static_cast<std::size_t>(std::floor(level));
  const float blend = level - std::floor(level);
  const glm::vec4 below = sample_level(t.levels[lower], sampler, uv, sampler.min);
  if (blend == 0.0f || lower + 1 >= t.levels.size()) return below;
  return (1.0f - blend) * below + blend * sample_level(t.levels[lower + 1], sampler, uv, sampler.min);
}

}  // namespace vplkit
