#include "frontend/gl/debug_output.hpp"

#include <atomic>
#include <sstream>
#include <vector>

#include "frontend/core/error.hpp"
#include "frontend/gl/gl.hpp"

namespace vplkit {
namespace {

// One GL context is current per thread; its messages are collected per thread.
thread_local std::vector<std::string> pending_messages;
std::atomic<std::size_t> unchecked_errors{0};

const char* type_name(GLenum type) {
  switch (type) {
    case GL_DEBUG_TYPE_ERROR: return "error";
    case GL_DEBUG_TYPE_DEPRECATED_BEHAVIOR: return "deprecated behaviour";
    case GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR: return "undefined behaviour";
    default: return "message";
  }
}

void GLAD_API_PTR on_debug_message(GLenum source, GLenum type, GLuint id, GLenum severity,
                                   GLsizei length, const GLchar* message, const void* user) {
  (void)source, (void)id, (void)user;
  // Errors and undefined behaviour are failures; performance notes and other chatter are not.
  const bool failure = type == GL_DEBUG_TYPE_ERROR || type == GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR ||
                       severity == GL_DEBUG_SEVERITY_HIGH;
  if (!failure) return;
  unchecked_errors.fetch_add(1, std::memory_order_relaxed);
  const std::string text = length >= 0 ? std::string(message, static_cast<std::size_t>(length)) : std::string(message);
  pending_messages.push_back(std::string(type_name(type)) + ": " + text);
}

const char* error_name(GLenum code) {
  switch (code) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    default: return "unknown GL error";
  }
}

}  // namespace

void install_debug_output() {
  pending_messages.clear();
  if (!GLAD_GL_KHR_debug) return;
  glEnable(GL_DEBUG_OUTPUT);
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(on_debug_message, nullptr);
}

void discard_pending_gl_messages() {
  unchecked_errors.fetch_sub(pending_messages.size(), std::memory_order_relaxed);
  pending_messages.clear();
  while (glGetError() != GL_NO_ERROR) {
  }
}

std::size_t unchecked_gl_error_count() { return unchecked_errors.load(std::memory_order_relaxed); }

void check_gl(const std::string& what) {
  std::vector<std::string> messages;
  messages.swap(pending_messages);
  unchecked_errors.fetch_sub(messages.size(), std::memory_order_relaxed);  // reported now, by the exception below
  for (GLenum code = glGetError(); code != GL_NO_ERROR; code = glGetError())
    messages.push_back(error_name(code));
  if (messages.empty()) return;
  std::ostringstream out;
  out << "GL error during " << what << ":";
  for (const std::string& message : messages) out << "\n  " << message;
  throw error(out.str());
}

}  // namespace vplkit
