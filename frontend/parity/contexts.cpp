// vplkit::parity (vplkit/parity/parity.hpp): the headless contexts, one per GL target, the
// shader search path, and the targets. The GLSL is made in glsl_sources.cpp, the runs are in
// runs.cpp, the comparison is in compare.cpp. No test framework: the adapters in
// include/vplkit/parity/ turn a comparison into an assertion.
#include <vplkit/parity/parity.hpp>

#include <cstdlib>
#include <memory>
#include <optional>
#include <sstream>
#include <thread>

#include "frontend/core/error.hpp"
#include "frontend/gl/context.hpp"
#include "frontend/parity/internal.hpp"
#include "frontend/parity/vulkan_compute.hpp"

namespace vplkit::parity {
namespace fs = std::filesystem;
using detail::context_for;
using detail::default_context_again;
using detail::shaders_for;

namespace {

std::string environment_text(const char* name) {
  const char* value = std::getenv(name);
  return std::string(name) + (value && *value ? "=" + std::string(value) : " not set");
}

// The process's headless contexts, one per GL target, made on first use as the CLI makes them
// (VPLKIT_CONTEXT, VPLKIT_EGL_DEVICE); a failure is thrown again on the next use, which tries
// again. A context is current on one thread: the thread of the first parity call is kept so that
// a call from another one says so, instead of running GL calls without a context (they fail one
// by one and the first error a user sees is an empty "GLSL compile error").
struct parity_contexts {
  std::unique_ptr<gl_context> made[3];  // gl33, gl45, gles3
  const gl_context* current = nullptr;
  std::optional<std::thread::id> owner;
};

parity_contexts& contexts() {
  // Never destroyed: a static's destructor runs after the driver's own exit handlers, and Mesa
  // 22.3's OSMesaDestroyContext then crashes (SIGSEGV at exit, after every test passed, once a
  // vertex-stage run had compiled through llvmpipe's draw module). The process's end frees it.
  static parity_contexts& state = *new parity_contexts;
  return state;
}

std::string thread_name(std::thread::id thread) {
  std::ostringstream text;
  text << thread;
  return text.str();
}

// The first parity call's thread owns the contexts and the shader library; others are refused.
void check_owner_thread(const std::string& call) {
  parity_contexts& state = contexts();
  if (!state.owner) state.owner = std::this_thread::get_id();
  if (std::this_thread::get_id() == *state.owner) return;
  throw error("vplkit::parity: " + call + " was called on thread " + thread_name(std::this_thread::get_id()) +
              ", but the headless GL context is current on thread " + thread_name(*state.owner) +
              " (the thread of the first parity call, which made it): a GL context is current on one thread, so make every "
              "parity call on that one");
}

gl_profile profile_of(target where) {
  return where == target::gl45 ? gl_profile::core45 : where == target::gles3 ? gl_profile::es30 : gl_profile::core33;
}

}  // namespace

const gl_context& detail::context_for(target where, const std::string& call) {
  check_owner_thread(call);
  parity_contexts& state = contexts();
  std::unique_ptr<gl_context>& slot = state.made[static_cast<int>(where)];
  if (!slot) {
    headless_request request;
    request.profile = profile_of(where);
    try {
      slot = create_headless_context(request);
    } catch (const error& failure) {
      // Making a context may have left none current: the next use of another makes its own current.
      state.current = nullptr;
      const std::string what = where == target::gl33 ? std::string("GL context")
                                                     : std::string(gl_profile_name(request.profile)) + " context for target " + target_name(where);
      throw error("vplkit::parity needs a headless " + what + " and could not make one (" + environment_text("VPLKIT_CONTEXT") + ", " +
                  environment_text("VPLKIT_EGL_DEVICE") + "): " + failure.what());
    }
    state.current = slot.get();
  } else if (state.current != slot.get()) {
    slot->make_current();
    state.current = slot.get();
  }
  return *slot;
}

detail::default_context_again::~default_context_again() {
  parity_contexts& state = contexts();
  const gl_context* default_context = state.made[0].get();
  if (!default_context || state.current == default_context) return;
  try {
    state.made[0]->make_current();
    state.current = default_context;
  } catch (const error&) {
    state.current = nullptr;  // the next run makes it current, or says why it cannot
  }
}

namespace {

// Where vplkit's shaders are when $VPLKIT_SHADER_DIR does not say: recorded by the header
// (VPLKIT_PARITY_SHADER_DIR of the CMake target) before main.
std::optional<fs::path>& recorded_vplkit_shader_dir() {
  static std::optional<fs::path> folder;
  return folder;
}

fs::path vplkit_shader_dir() {
  if (const char* from_environment = std::getenv("VPLKIT_SHADER_DIR"); from_environment && *from_environment) return from_environment;
  if (recorded_vplkit_shader_dir()) return *recorded_vplkit_shader_dir();
  throw error("vplkit::parity does not know where vplkit's shaders are: link the CMake target vplkit::parity (it records them), "
              "or set VPLKIT_SHADER_DIR to vplkit's shaders/ folder");
}

// The folders added before the library was made, and the library once made.
struct shader_search {
  std::vector<fs::path> pending_roots;
  std::unique_ptr<shader_library> library;
};

shader_search& search() {
  static shader_search state;
  return state;
}

}  // namespace

namespace detail {
bool record_vplkit_shader_dir(const char* folder) {
  recorded_vplkit_shader_dir() = fs::path(folder);
  return true;
}
}  // namespace detail

void add_shader_root(const fs::path& folder) {
  std::error_code ignored;
  if (!fs::is_directory(folder, ignored))
    throw error("vplkit::parity::add_shader_root: " + folder.string() + " is not a folder");
  shader_search& state = search();
  // Once made, the library is the context thread's (test_shaders hands it out there).
  if (state.library) {
    check_owner_thread("add_shader_root");
    state.library->add_root(folder);
  } else {
    state.pending_roots.push_back(folder);
  }
}

const shader_library& detail::shaders_for(const std::string& call) {
  check_owner_thread(call);
  shader_search& state = search();
  if (!state.library) {
    auto library = std::make_unique<shader_library>(vplkit_shader_dir());
    for (const fs::path& root : state.pending_roots) library->add_root(root);
    state.library = std::move(library);
    state.pending_roots.clear();
  }
  return *state.library;
}

const shader_library& test_shaders() {
  context_for(target::gl33, "test_shaders");
  return shaders_for("test_shaders");
}

// The kind is a fact about the process, not a GL call: any thread may ask once it is made.
std::string test_context_kind() {
  if (const gl_context* made = contexts().made[0].get()) return made->kind();
  return context_for(target::gl33, "test_context_kind").kind();
}

const char* target_name(target where) {
  switch (where) {
    case target::gl33: return "gl33";
    case target::gl45: return "gl45";
    case target::gles3: return "gles3";
    case target::vulkan: return "vulkan";
  }
  return "unknown target";
}

const std::vector<target>& all_targets() {
  static const std::vector<target> targets = {target::gl33, target::gl45, target::gles3, target::vulkan};
  return targets;
}

std::string target_unavailable(target where) {
  if (where == target::vulkan) return detail::vulkan_unavailable();
  try {
    default_context_again restore;
    context_for(where, std::string("target_unavailable(") + target_name(where) + ")");
    return "";
  } catch (const error& failure) {
    return failure.what();
  }
}

std::string glsl_preamble(target where) {
  switch (where) {
    case target::gl33: return "#version 330 core\n";
    case target::gl45: return "#version 450 core\n";
    case target::gles3:
      return "#version 300 es\nprecision highp float;\nprecision highp int;\nprecision highp sampler2D;\nprecision highp usampler2D;\n";
    case target::vulkan: return "#version 450\n";
  }
  throw error("glsl_preamble: unknown target " + std::to_string(static_cast<int>(where)));
}

}  // namespace vplkit::parity
