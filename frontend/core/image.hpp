// The one image type of the frontend: linear float RGBA with rows bottom-up, the order in which
// GL reads a render target back and in which a PFM file stores its rows. It sits in core, below
// both gl (render targets read back into it) and image (its conversions, metrics and codecs in
// frontend/image/), so that gl uses it without linking the image library and its codecs.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace vplkit {

/// The largest image side vplkit renders, reads or allocates a render target for (per axis);
/// GL_MAX_TEXTURE_SIZE is checked as well where a texture is made.
constexpr int max_image_side = 16384;

/// Empty when width x height is a size vplkit renders, else the reason.
inline std::string validate_image_size(int width, int height) {
  if (width < 1 || height < 1 || width > max_image_side || height > max_image_side)
    return "image size must be in [1, " + std::to_string(max_image_side) + "] per side, got " + std::to_string(width) + "x" + std::to_string(height);
  return {};
}

/// Linear RGBA floats, rows bottom-up: texel (x, y) has y = 0 at the bottom, as in GL.
struct image {
  int width = 0;
  int height = 0;
  std::vector<glm::vec4> texels;

  image() = default;
  image(int w, int h, glm::vec4 fill = glm::vec4(0.0f))
      : width(w), height(h), texels(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), fill) {}
  std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x); }
  const glm::vec4& at(glm::ivec2 texel) const { return texels[index(texel.x, texel.y)]; }
  glm::vec4& at(glm::ivec2 texel) { return texels[index(texel.x, texel.y)]; }
  const glm::vec4& at(int x, int y) const { return texels[index(x, y)]; }
  glm::vec4& at(int x, int y) { return texels[index(x, y)]; }
  bool same_size(const image& other) const { return width == other.width && height == other.height; }
};

}  // namespace vplkit
