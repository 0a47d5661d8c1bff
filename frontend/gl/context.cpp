#include "frontend/gl/context.hpp"

// glad first: it defines the GL types and blocks <GL/gl.h>, which osmesa.h would include.
#include "frontend/gl/gl.hpp"

#include <GL/osmesa.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <sstream>
#include <vector>

#include "frontend/gl/debug_output.hpp"
#include "frontend/core/error.hpp"

namespace vplkit {

std::string describe_current_context() {
  auto text = [](GLenum name) {
    const GLubyte* value = glGetString(name);
    return value ? std::string(reinterpret_cast<const char*>(value)) : std::string("(unknown)");
  };
  std::ostringstream out;
  out << "GL_VERSION  " << text(GL_VERSION) << "\nGL_RENDERER " << text(GL_RENDERER)
      << "\nGL_VENDOR   " << text(GL_VENDOR);
  return out.str();
}

namespace {

GLADapiproc osmesa_get_proc(const char* name) {
  return reinterpret_cast<GLADapiproc>(OSMesaGetProcAddress(name));
}

void load_gl(GLADloadfunc loader, const std::string& kind) {
  const int version = gladLoadGL(loader);
  if (version == 0) throw error("no GL context: glad could not load GL entry points for the " + kind + " context");
  if (GLAD_VERSION_MAJOR(version) * 10 + GLAD_VERSION_MINOR(version) < 33)
    throw error("no GL context: the " + kind + " context offers GL " +
                std::to_string(GLAD_VERSION_MAJOR(version)) + "." +
                std::to_string(GLAD_VERSION_MINOR(version)) + ", vplkit needs 3.3 core");
  install_debug_output();
}

class osmesa_context final : public gl_context {
 public:
  osmesa_context() {
    const int attributes[] = {OSMESA_FORMAT,          OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,      24,
                              OSMESA_PROFILE,         OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION, 3,
                              OSMESA_CONTEXT_MINOR_VERSION, 3,
                              0};
    context_ = OSMesaCreateContextAttribs(attributes, nullptr);
    if (!context_)
      throw error("no GL context: OSMesaCreateContextAttribs could not create a 3.3 core context "
                  "(is libosmesa6 from Mesa >= 12 installed?)");
    make_current();
  }
  ~osmesa_context() override { OSMesaDestroyContext(context_); }
  osmesa_context(const osmesa_context&) = delete;
  osmesa_context& operator=(const osmesa_context&) = delete;

  void make_current() override {
    if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, buffer_width, buffer_height))
      throw error("no GL context: OSMesaMakeCurrent failed");
    load_gl(osmesa_get_proc, "OSMesa");
  }
  std::string kind() const override { return "OSMesa"; }

 private:
  static constexpr int buffer_width = 16;
  static constexpr int buffer_height = 16;
  OSMesaContext context_ = nullptr;
  std::vector<unsigned char> buffer_ = std::vector<unsigned char>(buffer_width * buffer_height * 4);
};

std::string glfw_last_error() {
  const char* description = nullptr;
  glfwGetError(&description);
  return description ? description : "no reason given";
}

}  // namespace

std::unique_ptr<gl_context> create_headless_context() { return std::make_unique<osmesa_context>(); }

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
