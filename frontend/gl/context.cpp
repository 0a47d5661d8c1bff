#include "frontend/gl/context.hpp"

// glad first: it defines the GL types and blocks <GL/gl.h>, which osmesa.h would include.
#include "frontend/gl/gl.hpp"

#if VPLKIT_HAVE_OSMESA
#include <GL/osmesa.h>
#endif
#define EGL_NO_X11
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdlib>
#include <cstring>
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

const char* gl_profile_name(gl_profile profile) {
  switch (profile) {
    case gl_profile::core33: return "GL 3.3 core";
    case gl_profile::core45: return "GL 4.5 core";
    case gl_profile::es30: return "GLES 3.0";
  }
  return "unknown profile";
}

void load_gl(GLADloadfunc loader, const std::string& kind, gl_profile profile) {
  // One merged loader serves both APIs (frontend/CMakeLists.txt): an ES context loads the ES
  // entry points, whose version check reads "OpenGL ES 3.2 ..." rather than a desktop version.
  const bool es = profile == gl_profile::es30;
  const int version = es ? gladLoadGLES2(loader) : gladLoadGL(loader);
  if (version == 0) throw error("no GL context: glad could not load " + std::string(es ? "GLES" : "GL") + " entry points for the " + kind + " context");
  const int needed = profile == gl_profile::core33 ? 33 : profile == gl_profile::core45 ? 45 : 30;
  if (GLAD_VERSION_MAJOR(version) * 10 + GLAD_VERSION_MINOR(version) < needed)
    throw error("no GL context: the " + kind + " context offers " + (es ? "GLES " : "GL ") + std::to_string(GLAD_VERSION_MAJOR(version)) + "." +
                std::to_string(GLAD_VERSION_MINOR(version)) + ", " + gl_profile_name(profile) + " was asked for");
  // Debug output is core in GLES 3.2; below it the pointers would be a desktop context's.
  if (!es || GLAD_GL_ES_VERSION_3_2) install_debug_output();
}

namespace {

#if VPLKIT_HAVE_OSMESA
GLADapiproc osmesa_get_proc(const char* name) {
  return reinterpret_cast<GLADapiproc>(OSMesaGetProcAddress(name));
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

#endif

// ---- EGL ------------------------------------------------------------------------------------


std::string egl_error_text() {
  char code[16];
  std::snprintf(code, sizeof code, "0x%04X", static_cast<unsigned>(eglGetError()));
  return std::string("EGL error ") + code;
}

bool has_extension(const char* list, const char* name) {
  if (!list) return false;
  const std::size_t length = std::strlen(name);
  for (const char* at = std::strstr(list, name); at; at = std::strstr(at + 1, name))
    if ((at == list || at[-1] == ' ') && (at[length] == ' ' || at[length] == '\0')) return true;
  return false;
}

GLADapiproc egl_get_proc(const char* name) { return reinterpret_cast<GLADapiproc>(eglGetProcAddress(name)); }

struct egl_device {
  EGLDeviceEXT handle = nullptr;
  bool software = false;
  std::string description;  // "software: EGL_MESA_device_software" or "hardware: /dev/dri/card0"
};

// The client extensions' entry points, or nulls where the EGL library lacks them.
struct egl_client {
  const char* extensions = nullptr;
  PFNEGLQUERYDEVICESEXTPROC query_devices = nullptr;
  PFNEGLQUERYDEVICESTRINGEXTPROC query_device_string = nullptr;
  PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display = nullptr;

  egl_client() {
    extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    eglGetError();  // without client extensions the query fails; that is not an error here
    if (has_extension(extensions, "EGL_EXT_device_enumeration") || has_extension(extensions, "EGL_EXT_device_base")) {
      query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
      query_device_string = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
    }
    if (has_extension(extensions, "EGL_EXT_platform_base"))
      get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  }
  bool device_platform() const {
    return query_devices && query_device_string && get_platform_display && has_extension(extensions, "EGL_EXT_platform_device");
  }
  bool surfaceless_platform() const { return get_platform_display && has_extension(extensions, "EGL_MESA_platform_surfaceless"); }

  std::vector<egl_device> devices() const {
    std::vector<egl_device> found;
    if (!device_platform()) return found;
    EGLint count = 0;
    if (!query_devices(0, nullptr, &count) || count <= 0) return found;
    std::vector<EGLDeviceEXT> handles(static_cast<std::size_t>(count));
    if (!query_devices(count, handles.data(), &count)) return found;
    for (EGLint i = 0; i < count; ++i) {
      egl_device device;
      device.handle = handles[static_cast<std::size_t>(i)];
      const char* device_extensions = query_device_string(device.handle, EGL_EXTENSIONS);
      device.software = has_extension(device_extensions, "EGL_MESA_device_software");
      const char* node = has_extension(device_extensions, "EGL_EXT_device_drm") ? query_device_string(device.handle, EGL_DRM_DEVICE_FILE_EXT) : nullptr;
      device.description = device.software ? "software: EGL_MESA_device_software" : std::string("hardware") + (node ? std::string(": ") + node : "");
      found.push_back(device);
    }
    eglGetError();
    return found;
  }
};

class egl_context final : public gl_context {
 public:
  egl_context(EGLDisplay display, std::string kind, gl_profile profile) : display_(display), kind_(std::move(kind)), profile_(profile) {
    EGLint major = 0, minor = 0;
    // A display is one per device and process, shared by every context on it; it is initialised
    // again (a no-op) per context and never terminated: eglTerminate on Mesa 22.3 leaves two of
    // its blocks unreachable (LeakSanitizer reports them), and the process ends soon after anyway.
    if (!eglInitialize(display_, &major, &minor)) throw error(kind_ + ": eglInitialize failed (" + egl_error_text() + ")");
    try {
      const bool es = profile_ == gl_profile::es30;
      if (!eglBindAPI(es ? EGL_OPENGL_ES_API : EGL_OPENGL_API))
        throw error(kind_ + ": " + (es ? "OpenGL ES" : "desktop OpenGL") + " is not offered (eglBindAPI: " + egl_error_text() + ")");
      const char* display_extensions = eglQueryString(display_, EGL_EXTENSIONS);
      if (!has_extension(display_extensions, "EGL_KHR_surfaceless_context"))
        throw error(kind_ + ": EGL_KHR_surfaceless_context is missing (vplkit renders to framebuffer objects only)");
      const EGLint config_attributes[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, es ? EGL_OPENGL_ES3_BIT : EGL_OPENGL_BIT, EGL_NONE};
      EGLConfig config = nullptr;
      EGLint configs = 0;
      if (!eglChooseConfig(display_, config_attributes, &config, 1, &configs) || configs < 1) {
        eglGetError();
        if (!has_extension(display_extensions, "EGL_KHR_no_config_context"))
          throw error(kind_ + ": no EGL config renders " + (es ? "OpenGL ES 3" : "desktop OpenGL") + ", and EGL_KHR_no_config_context is missing");
        config = EGL_NO_CONFIG_KHR;
      }
      const EGLint want_major = profile_ == gl_profile::core45 ? 4 : 3, want_minor = profile_ == gl_profile::core45 ? 5 : es ? 0 : 3;
      const EGLint desktop_attributes[] = {EGL_CONTEXT_MAJOR_VERSION, want_major, EGL_CONTEXT_MINOR_VERSION, want_minor,
                                           EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
      const EGLint es_attributes[] = {EGL_CONTEXT_MAJOR_VERSION, want_major, EGL_CONTEXT_MINOR_VERSION, want_minor, EGL_NONE};
      context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, es ? es_attributes : desktop_attributes);
      if (context_ == EGL_NO_CONTEXT)
        throw error(kind_ + ": eglCreateContext could not create a " + gl_profile_name(profile_) + " context (" + egl_error_text() + ")");
      make_current();
    } catch (...) {
      release();
      throw;
    }
  }
  ~egl_context() override { release(); }
  egl_context(const egl_context&) = delete;
  egl_context& operator=(const egl_context&) = delete;

  void make_current() override {
    // eglBindAPI is per thread, and eglMakeCurrent binds the context of the API bound now: a
    // process with a GL and an ES context switches it each time.
    eglBindAPI(profile_ == gl_profile::es30 ? EGL_OPENGL_ES_API : EGL_OPENGL_API);
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) throw error(kind_ + ": eglMakeCurrent failed (" + egl_error_text() + ")");
    load_gl(egl_get_proc, kind_, profile_);
  }
  std::string kind() const override { return kind_; }

 private:
  void release() {
    if (context_ != EGL_NO_CONTEXT) {
      if (eglGetCurrentContext() == context_) eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      eglDestroyContext(display_, context_);
      context_ = EGL_NO_CONTEXT;
    }
  }

  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  std::string kind_;
  gl_profile profile_;
};

// The device `device_index` (from --device or $VPLKIT_EGL_DEVICE, said by `device_source`), else
// the first hardware device, else the software one, else the surfaceless platform; only the last
// with `surfaceless_only`.
std::unique_ptr<gl_context> create_egl_context(int device_index, const std::string& device_source, bool surfaceless_only, gl_profile profile) {
  const egl_client client;
  const std::vector<egl_device> devices = surfaceless_only ? std::vector<egl_device>{} : client.devices();
  if (surfaceless_only && device_index >= 0)
    throw error("no GL context: " + std::string(device_source.empty() ? "--device" : "VPLKIT_EGL_DEVICE") + " picks an EGL device; egl-surfaceless has none");
  if (device_index >= 0) {
    if (static_cast<std::size_t>(device_index) >= devices.size())
      throw error("no EGL device " + std::to_string(device_index) + ": this machine has " + std::to_string(devices.size()) +
                  " (vplkit info lists them)" + device_source);
  } else {
    for (std::size_t i = 0; i < devices.size() && device_index < 0; ++i)
      if (!devices[i].software) device_index = static_cast<int>(i);
    for (std::size_t i = 0; i < devices.size() && device_index < 0; ++i) device_index = static_cast<int>(i);
  }
  std::string tried;
  if (device_index >= 0) {
    const egl_device& device = devices[static_cast<std::size_t>(device_index)];
    const EGLDisplay display = client.get_platform_display(EGL_PLATFORM_DEVICE_EXT, device.handle, nullptr);
    const std::string kind = "EGL device " + std::to_string(device_index) + " (" + device.description + ")";
    if (display == EGL_NO_DISPLAY) {
      tried = kind + ": no display (" + egl_error_text() + ")";
    } else {
      try {
        return std::make_unique<egl_context>(display, kind, profile);
      } catch (const error& failure) {
        tried = failure.what();
      }
    }
  }
  if (client.surfaceless_platform()) {
    const EGLDisplay display = client.get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display != EGL_NO_DISPLAY) {
      try {
        return std::make_unique<egl_context>(display, "EGL surfaceless", profile);
      } catch (const error& failure) {
        tried += (tried.empty() ? "" : "; ") + std::string(failure.what());
      }
    }
  }
  if (tried.empty())
    tried = surfaceless_only ? "the EGL library does not offer EGL_MESA_platform_surfaceless"
                             : "the EGL library offers neither EGL_EXT_platform_device nor EGL_MESA_platform_surfaceless";
  throw error("no GL context: " + tried);
}

}  // namespace

bool osmesa_built_in() { return VPLKIT_HAVE_OSMESA != 0; }

const std::vector<std::string>& headless_api_names() {
  static const std::vector<std::string> names = {"auto", "egl", "egl-surfaceless", "osmesa"};
  return names;
}

headless_api headless_api_from_name(const std::string& name, const std::string& what) {
  if (name == "auto") return headless_api::automatic;
  if (name == "egl") return headless_api::egl;
  if (name == "egl-surfaceless") return headless_api::egl_surfaceless;
  if (name == "osmesa") return headless_api::osmesa;
  throw error(what + " must be one of auto, egl, egl-surfaceless, osmesa; got '" + excerpt(name) + "'");
}

int egl_device_from_environment() {
  const char* from_environment = std::getenv("VPLKIT_EGL_DEVICE");
  if (!from_environment || !*from_environment) return -1;
  const std::string text(from_environment);
  if (text.size() > 4 || text.find_first_not_of("0123456789") != std::string::npos || std::stoi(text) > 1024)
    throw error("VPLKIT_EGL_DEVICE must be an EGL device index in [0, 1024] like --device (vplkit info lists them), got '" + excerpt(text) + "'");
  return std::stoi(text);
}

headless_api headless_api_from_environment() {
  const char* from_environment = std::getenv("VPLKIT_CONTEXT");
  if (!from_environment || !*from_environment) return headless_api::automatic;
  return headless_api_from_name(excerpt(from_environment), "VPLKIT_CONTEXT");
}

std::unique_ptr<gl_context> create_headless_context(const headless_request& request) {
  headless_api api = request.api;
  if (api == headless_api::automatic) api = headless_api_from_environment();
  // A device from the environment is a device asked for, like --device: no fallback to OSMesa,
  // and a malformed value is an error, never silently ignored.
  int device = request.device;
  std::string device_source;
  if (device < 0 && api != headless_api::osmesa) {
    device = egl_device_from_environment();
    if (device >= 0) device_source = "; VPLKIT_EGL_DEVICE asked for it";
  }
  if (api == headless_api::osmesa) {
    if (request.profile != gl_profile::core33)
      throw error(std::string("no GL context: OSMesa makes GL 3.3 core contexts only; ") + gl_profile_name(request.profile) + " needs EGL");
#if VPLKIT_HAVE_OSMESA
    return std::make_unique<osmesa_context>();
#else
    throw error("no GL context: this vplkit was built without OSMesa (VPLKIT_WITH_OSMESA=OFF); use the EGL context");
#endif
  }
  if (api == headless_api::egl || api == headless_api::egl_surfaceless)
    return create_egl_context(device, device_source, api == headless_api::egl_surfaceless, request.profile);
  try {
    return create_egl_context(device, device_source, false, request.profile);
  } catch (const error& egl_failure) {
#if VPLKIT_HAVE_OSMESA
    if (device >= 0 || request.profile != gl_profile::core33) throw;  // a device, or a profile OSMesa lacks, was asked for
    try {
      return std::make_unique<osmesa_context>();
    } catch (const error& osmesa_failure) {
      throw error(std::string(egl_failure.what()) + "; OSMesa: " + osmesa_failure.what());
    }
#else
    throw;
#endif
  }
}

std::vector<std::string> available_headless_contexts() {
  std::vector<std::string> lines;
  const egl_client client;
  const std::vector<egl_device> devices = client.devices();
  for (std::size_t i = 0; i < devices.size(); ++i) lines.push_back("egl --device " + std::to_string(i) + "  " + devices[i].description);
  if (!client.device_platform()) lines.push_back("egl devices: not offered (no EGL_EXT_platform_device)");
  lines.push_back(std::string("egl surfaceless: ") +
                  (client.surfaceless_platform() ? "offered (the fallback; --context egl-surfaceless)" : "not offered"));
  lines.push_back(std::string("osmesa: ") + (osmesa_built_in() ? "built in (--context osmesa)" : "not built in (VPLKIT_WITH_OSMESA=OFF)"));
  return lines;
}

}  // namespace vplkit
