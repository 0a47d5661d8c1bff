// GL contexts: headless (OSMesa, the default everywhere, including tests and CI) and a GLFW window.
//
// Each context loads glad from its own GetProcAddress when it becomes current. That matters when
// a process uses both: function pointers resolved through GLX are not OSMesa's, and OSMesa then
// silently returns NULL strings and 0 names instead of failing.
#pragma once

#include <memory>
#include <string>
#include <utility>

struct GLFWwindow;

namespace vplkit {

class gl_context {
 public:
  virtual ~gl_context() = default;
  /// Makes the context current on this thread and (re)loads the GL entry points for it.
  virtual void make_current() = 0;
  /// "OSMesa" or "GLFW window".
  virtual std::string kind() const = 0;
};

/// GL_VERSION, GL_RENDERER and GL_VENDOR of the current context, one per line.
std::string describe_current_context();

/// A headless OSMesa context with a core 3.3 profile, current on return. Rendering goes to
/// framebuffer objects; the default framebuffer is a small unused buffer.
/// Throws vplkit::error naming what failed when no such context can be made.
std::unique_ptr<gl_context> create_headless_context();

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
