// Textures and float render targets: RGBA32F, RGBA16F and RGBA32UI colour attachments (several
// at once), an optional depth attachment, and readback of any attachment to host memory.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "frontend/core/image.hpp"
#include "frontend/gl/gl.hpp"
#include "frontend/gl/gl_object.hpp"

namespace vplkit {

enum class texel_format { rgba32f, rgba16f, rgba32ui, depth32f };

/// "rgba32f" etc., for messages and CLI values.
const char* format_name(texel_format format);

class texture_2d {
 public:
  /// Allocates width x height texels, nearest filtering, clamp to edge. `initial` may be null;
  /// otherwise it holds width * height * 4 floats (float formats) or uint32s (rgba32ui), or
  /// width * height floats for depth32f.
  texture_2d(int width, int height, texel_format format, const void* initial = nullptr);
  GLuint id() const { return name_.get(); }
  int width() const { return width_; }
  int height() const { return height_; }
  texel_format format() const { return format_; }
  void bind(int unit) const;
  /// Depth textures only: sample with a sampler2DShadow (GL_LEQUAL compare, bilinear PCF).
  void enable_depth_compare() const;
  /// Reads a float colour texture (rows bottom-up, as vplkit::image keeps them).
  image read_image() const;
  /// The same into `texels`, whose memory is reused when it has the size (a frame that reads back
  /// each time then touches no new pages: a page fault costs microseconds on a virtual machine).
  void read_image_into(image& texels) const;

 private:
  gl_texture name_;
  int width_;
  int height_;
  texel_format format_;
};

/// A framebuffer object owning its attachments.
class framebuffer {
 public:
  framebuffer(int width, int height, const std::vector<texel_format>& colour_formats, bool with_depth);
  void bind() const;  // binds for drawing, sets the viewport and the draw buffers
  /// Binds as the read framebuffer with colour attachment `index` as the read buffer (glReadPixels).
  void bind_for_reading(std::size_t index) const;
  int width() const { return width_; }
  int height() const { return height_; }
  const texture_2d& colour(std::size_t index) const { return colours_.at(index); }
  const texture_2d& depth() const { return depth_.at(0); }
  /// Reads float colour attachment `index` (texture_2d::read_image).
  image read_image(std::size_t index) const;
  /// Reads a rgba32ui colour attachment as width * height * 4 uint32s, rows bottom-up.
  std::vector<std::uint32_t> read_uint(std::size_t index) const;

 private:
  gl_framebuffer name_;
  int width_;
  int height_;
  std::vector<texture_2d> colours_;
  std::vector<texture_2d> depth_;  // empty or one
};

/// Throws vplkit::error when a texture of this size cannot be made on the current context.
void check_texture_size(int width, int height, const std::string& what);

}  // namespace vplkit
