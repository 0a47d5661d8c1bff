#include "frontend/gl/render_target.hpp"

#include <cmath>
#include <cstring>

#include "frontend/gl/debug_output.hpp"
#include "frontend/core/error.hpp"

namespace vplkit {
namespace {

struct format_info {
  GLenum internal_format;
  GLenum format;
  GLenum type;
};

format_info info(texel_format format) {
  switch (format) {
    case texel_format::rgba32f: return {GL_RGBA32F, GL_RGBA, GL_FLOAT};
    case texel_format::rgba16f: return {GL_RGBA16F, GL_RGBA, GL_FLOAT};
    case texel_format::rgba32ui: return {GL_RGBA32UI, GL_RGBA_INTEGER, GL_UNSIGNED_INT};
    case texel_format::depth32f: return {GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT};
  }
  throw error("unknown texel format");
}

}  // namespace

const char* format_name(texel_format format) {
  switch (format) {
    case texel_format::rgba32f: return "rgba32f";
    case texel_format::rgba16f: return "rgba16f";
    case texel_format::rgba32ui: return "rgba32ui";
    case texel_format::depth32f: return "depth32f";
  }
  return "unknown";
}

void check_texture_size(int width, int height, const std::string& what) {
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  if (width < 1 || height < 1 || width > max_size || height > max_size)
    throw error(what + ": " + std::to_string(width) + "x" + std::to_string(height) +
                " is outside 1.." + std::to_string(max_size) + " (GL_MAX_TEXTURE_SIZE of this context)");
}

texture_2d::texture_2d(int width, int height, texel_format format, const void* initial)
    : name_(generate_texture()), width_(width), height_(height), format_(format) {
  check_texture_size(width, height, std::string("texture ") + format_name(format));
  const format_info f = info(format);
  // Leave the caller's binding on the active unit alone: creating a render target must not
  // silently unbind an input texture that was bound before it.
  GLint previous = 0;
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &previous);
  glBindTexture(GL_TEXTURE_2D, name_.get());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(f.internal_format), width, height, 0, f.format, f.type, initial);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(previous));
  const int bytes_per_texel = format == texel_format::rgba16f ? 8 : format == texel_format::depth32f ? 4 : 16;
  const double mebibytes = static_cast<double>(width) * height * bytes_per_texel / (1024.0 * 1024.0);
  check_gl(std::string("allocating a ") + std::to_string(width) + "x" + std::to_string(height) + " " + format_name(format) +
           " texture (" + std::to_string(static_cast<long long>(std::ceil(mebibytes))) + " MiB)");
}

void texture_2d::bind(int unit) const {
  glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
  glBindTexture(GL_TEXTURE_2D, name_.get());
}

void texture_2d::enable_depth_compare() const {
  glBindTexture(GL_TEXTURE_2D, name_.get());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
}

framebuffer::framebuffer(int width, int height, const std::vector<texel_format>& colour_formats, bool with_depth)
    : name_(generate_framebuffer()), width_(width), height_(height) {
  glBindFramebuffer(GL_FRAMEBUFFER, name_.get());
  colours_.reserve(colour_formats.size());
  for (std::size_t i = 0; i < colour_formats.size(); ++i) {
    if (colour_formats[i] == texel_format::depth32f) throw error("depth32f is not a colour format");
    colours_.emplace_back(width, height, colour_formats[i]);
    glFramebufferTexture2D(GL_FRAMEBUFFER, static_cast<GLenum>(GL_COLOR_ATTACHMENT0 + i), GL_TEXTURE_2D,
                           colours_.back().id(), 0);
  }
  if (with_depth) {
    depth_.emplace_back(width, height, texel_format::depth32f);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth_.back().id(), 0);
  }
  bind();
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw error("framebuffer " + std::to_string(width) + "x" + std::to_string(height) +
                " is incomplete (glCheckFramebufferStatus " + std::to_string(status) + ")");
  check_gl("creating a framebuffer");
}

void framebuffer::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, name_.get());
  glViewport(0, 0, width_, height_);
  std::vector<GLenum> buffers;
  for (std::size_t i = 0; i < colours_.size(); ++i) buffers.push_back(static_cast<GLenum>(GL_COLOR_ATTACHMENT0 + i));
  if (buffers.empty()) glDrawBuffer(GL_NONE);
  else glDrawBuffers(static_cast<GLsizei>(buffers.size()), buffers.data());
}

void framebuffer::bind_for_reading(std::size_t index) const {
  if (index >= colours_.size()) throw error("bind_for_reading: no colour attachment " + std::to_string(index));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, name_.get());
  glReadBuffer(static_cast<GLenum>(GL_COLOR_ATTACHMENT0 + index));
}

image texture_2d::read_image() const {
  image texels;
  read_image_into(texels);
  return texels;
}

void texture_2d::read_image_into(image& texels) const {
  if (format_ != texel_format::rgba32f && format_ != texel_format::rgba16f) throw error(std::string("read_image on a ") + format_name(format_) + " texture");
  texels.width = width_;
  texels.height = height_;
  texels.texels.resize(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_));
  static_assert(sizeof(glm::vec4) == 4 * sizeof(float), "glGetTexImage writes packed RGBA floats");
  glBindTexture(GL_TEXTURE_2D, name_.get());
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, texels.texels.data());
  glBindTexture(GL_TEXTURE_2D, 0);
  check_gl(std::string("reading back a ") + format_name(format_) + " texture");
}

image framebuffer::read_image(std::size_t index) const { return colours_.at(index).read_image(); }

std::vector<std::uint32_t> framebuffer::read_uint(std::size_t index) const {
  const texture_2d& texture = colours_.at(index);
  if (texture.format() != texel_format::rgba32ui) throw error("read_uint on a float attachment");
  std::vector<std::uint32_t> texels(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * 4);
  bind_for_reading(index);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, width_, height_, GL_RGBA_INTEGER, GL_UNSIGNED_INT, texels.data());
  check_gl("reading back colour attachment " + std::to_string(index));
  return texels;
}

}  // namespace vplkit
