// A GLFW window with a core 3.3 context: `vplkit view`, `vplkit info`'s window line and the
// viewer's tests. Kept out of the headless GL library (frontend/gl) so that headless code, and
// vplkit::parity above all, links no window system.
#pragma once

#include <string>
#include <utility>

#include "frontend/gl/context.hpp"

struct GLFWwindow;

namespace vplkit {

/// A window with a core 3.3 context, current on return. Throws vplkit::error with GLFW's reason
/// (for example no display) when the window cannot be opened.
class window_context final : public gl_context {
 public:
  window_context(int width, int height, const std::string& title);
  ~window_context() override;
  window_context(const window_context&) = delete;
  window_context& operator=(const window_context&) = delete;
  void make_current() override;
  std::string kind() const override { return "GLFW window"; }
  GLFWwindow* window() const { return window_; }
  bool should_close() const;
  /// Size of the window's default framebuffer in pixels.
  std::pair<int, int> framebuffer_size() const;
  void swap_and_poll();

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace vplkit
