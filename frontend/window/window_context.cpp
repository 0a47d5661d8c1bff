#include "frontend/window/window_context.hpp"

// glad first: it defines the GL types and blocks the system GL header.
#include "frontend/gl/gl.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "frontend/core/error.hpp"

namespace vplkit {
namespace {

std::string glfw_last_error() {
  const char* description = nullptr;
  glfwGetError(&description);
  return description ? description : "no reason given";
}

}  // namespace

window_context::window_context(int width, int height, const std::string& title) {
  if (!glfwInit()) throw error("no GL context: GLFW could not initialise: " + glfw_last_error());
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) {
    const std::string reason = glfw_last_error();
    glfwTerminate();
    throw error("no GL context: GLFW could not open a " + std::to_string(width) + "x" +
                std::to_string(height) + " window with GL 3.3 core: " + reason);
  }
  make_current();
}

window_context::~window_context() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

void window_context::make_current() {
  glfwMakeContextCurrent(window_);
  load_gl(glfwGetProcAddress, "GLFW window");
}

bool window_context::should_close() const { return glfwWindowShouldClose(window_) != 0; }

std::pair<int, int> window_context::framebuffer_size() const {
  int width = 0, height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  return {width, height};
}

void window_context::swap_and_poll() {
  glfwSwapBuffers(window_);
  glfwPollEvents();
}

}  // namespace vplkit
