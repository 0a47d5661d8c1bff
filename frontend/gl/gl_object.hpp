// Move-only ownership of one GL object name. The deleter runs on the context current at
// destruction; every frontend object is destroyed before its context.
#pragma once

#include <utility>

#include "frontend/gl/gl.hpp"

namespace vplkit {

template <typename Deleter>
class gl_object {
 public:
  gl_object() = default;
  explicit gl_object(GLuint name) : name_(name) {}
  ~gl_object() {
    if (name_ != 0) Deleter{}(name_);
  }
  gl_object(gl_object&& other) noexcept : name_(std::exchange(other.name_, 0)) {}
  gl_object& operator=(gl_object&& other) noexcept {
    if (this != &other) {
      if (name_ != 0) Deleter{}(name_);
      name_ = std::exchange(other.name_, 0);
    }
    return *this;
  }
  gl_object(const gl_object&) = delete;
  gl_object& operator=(const gl_object&) = delete;
  GLuint get() const { return name_; }
  /// Gives up ownership: the caller deletes the name.
  GLuint release() { return std::exchange(name_, 0); }

 private:
  GLuint name_ = 0;
};

struct texture_deleter {
  void operator()(GLuint name) const { glDeleteTextures(1, &name); }
};
struct framebuffer_deleter {
  void operator()(GLuint name) const { glDeleteFramebuffers(1, &name); }
};
struct buffer_deleter {
  void operator()(GLuint name) const { glDeleteBuffers(1, &name); }
};
struct vertex_array_deleter {
  void operator()(GLuint name) const { glDeleteVertexArrays(1, &name); }
};
struct query_deleter {
  void operator()(GLuint name) const { glDeleteQueries(1, &name); }
};
struct program_deleter {
  void operator()(GLuint name) const { glDeleteProgram(name); }
};
struct shader_deleter {
  void operator()(GLuint name) const { glDeleteShader(name); }
};
struct sampler_deleter {
  void operator()(GLuint name) const { glDeleteSamplers(1, &name); }
};

using gl_texture = gl_object<texture_deleter>;
using gl_framebuffer = gl_object<framebuffer_deleter>;
using gl_buffer = gl_object<buffer_deleter>;
using gl_vertex_array = gl_object<vertex_array_deleter>;
using gl_query = gl_object<query_deleter>;
using gl_program = gl_object<program_deleter>;
using gl_shader = gl_object<shader_deleter>;
using gl_sampler = gl_object<sampler_deleter>;

inline GLuint generate_texture() { GLuint name = 0; glGenTextures(1, &name); return name; }
inline GLuint generate_framebuffer() { GLuint name = 0; glGenFramebuffers(1, &name); return name; }
inline GLuint generate_buffer() { GLuint name = 0; glGenBuffers(1, &name); return name; }
inline GLuint generate_vertex_array() { GLuint name = 0; glGenVertexArrays(1, &name); return name; }
inline GLuint generate_query() { GLuint name = 0; glGenQueries(1, &name); return name; }
inline GLuint generate_sampler() { GLuint name = 0; glGenSamplers(1, &name); return name; }

}  // namespace vplkit
