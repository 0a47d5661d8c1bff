// GL contexts: headless here; the GLFW window is frontend/window/window_context.hpp.
//
// Headless is EGL by default (render, tests, benchmarks): the device platform first
// (EGL_EXT_platform_device: a GPU when there is one, or Mesa's software device,
// EGL_MESA_device_software, i.e. llvmpipe), then the surfaceless platform
// (EGL_MESA_platform_surfaceless). OSMesa, which Mesa removed in 25.1, is a build option
// (VPLKIT_WITH_OSMESA) and a choice (`--context osmesa`, VPLKIT_CONTEXT=osmesa).
//
// Each context loads glad from its own GetProcAddress when it becomes current. That matters when
// a process uses several: function pointers resolved through GLX are not OSMesa's, and OSMesa then
// silently returns NULL strings and 0 names instead of failing.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "frontend/gl/gl.hpp"

namespace vplkit {

class gl_context {
 public:
  virtual ~gl_context() = default;
  /// Makes the context current on this thread and (re)loads the GL entry points for it.
  virtual void make_current() = 0;
  /// "EGL device 0 (software: EGL_MESA_device_software)", "EGL surfaceless", "OSMesa" or "GLFW window".
  virtual std::string kind() const = 0;
};

/// The API and version a context is made for. vplkit itself needs GL 3.3 core; vplkit::parity
/// also runs kernels in GL 4.5 core (compute shaders) and in OpenGL ES 3.0 (the WebGL2 subset).
enum class gl_profile {
  core33,  ///< desktop GL 3.3 core: vplkit's passes, the default
  core45,  ///< desktop GL 4.5 core
  es30,    ///< OpenGL ES 3.0 or later (EGL_OPENGL_ES_API; Mesa gives 3.2)
};
/// "GL 3.3 core", "GL 4.5 core", "GLES 3.0": for messages.
const char* gl_profile_name(gl_profile profile);

/// Loads the GL entry points of the context just made current through `loader` (its
/// GetProcAddress) and enables KHR_debug output; throws vplkit::error naming `kind` when the
/// context offers less than `profile` asks for (GL 3.3 core by default). Every context's
/// make_current calls it.
void load_gl(GLADloadfunc loader, const std::string& kind, gl_profile profile = gl_profile::core33);

/// GL_VERSION, GL_RENDERER and GL_VENDOR of the current context, one per line.
std::string describe_current_context();

enum class headless_api {
  automatic,        ///< $VPLKIT_CONTEXT when set, else EGL, else OSMesa when built in
  egl,              ///< an EGL device (see headless_request::device), else the surfaceless platform
  egl_surfaceless,  ///< EGL_MESA_platform_surfaceless only: the fallback, chosen outright
  osmesa,
};

/// The names of the APIs for --context and $VPLKIT_CONTEXT: auto, egl, egl-surfaceless, osmesa.
const std::vector<std::string>& headless_api_names();
/// The API of a name from headless_api_names(); throws vplkit::error naming `what` otherwise.
headless_api headless_api_from_name(const std::string& name, const std::string& what);

struct headless_request {
  headless_api api = headless_api::automatic;
  /// EGL device index (EGL_EXT_device_enumeration order); -1: $VPLKIT_EGL_DEVICE when set, else
  /// the first hardware device, else the software device, else the surfaceless platform.
  int device = -1;
  /// core45 and es30 are EGL only (OSMesa makes 3.3 core): asked of OSMesa, an error.
  gl_profile profile = gl_profile::core33;
};

/// $VPLKIT_EGL_DEVICE checked like --device: -1 when unset or empty, else an index in [0, 1024];
/// throws vplkit::error naming the variable for anything else ("junk", "-1", "7x").
int egl_device_from_environment();
/// $VPLKIT_CONTEXT checked like --context: automatic when unset or empty; throws vplkit::error
/// naming the variable for a name that is not one of headless_api_names().
headless_api headless_api_from_environment();

/// A headless context of request.profile (a core 3.3 profile by default), current on return. Rendering goes to framebuffer
/// objects. A device asked for (request.device or $VPLKIT_EGL_DEVICE) is that device or an
/// error, never another context. Throws vplkit::error naming what failed (every API tried, and
/// why) when no context can be made.
std::unique_ptr<gl_context> create_headless_context(const headless_request& request = {});

/// Whether this build has OSMesa (VPLKIT_WITH_OSMESA).
bool osmesa_built_in();

/// The headless contexts this build and machine offer, a line each: every EGL device (index,
/// software or hardware, its DRM node), the surfaceless platform, OSMesa. For `vplkit info`.
std::vector<std::string> available_headless_contexts();

}  // namespace vplkit
