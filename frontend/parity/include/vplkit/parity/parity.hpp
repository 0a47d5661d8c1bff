// vplkit::parity: property tests of GLSL functions against their C++ twins, texel by texel.
// find_package(vplkit REQUIRED COMPONENTS parity) and link vplkit::parity; a tutorial is
// docs/testing-your-shaders.md.
//
// A run evaluates a GLSL body on a grid of inputs under a headless GL context: in a fragment
// shader (one fragment per texel, inputs as RGBA32F / RGBA32UI textures, outputs read back from
// RGBA32F / RGBA32UI render targets) or in a vertex shader (one vertex per texel, inputs as
// vertex attributes, outputs captured with transform feedback). The body reads `fin0..` (vec4)
// and `uin0..` (uvec4) and assigns `fout0..` (vec4) and `uout0..` (uvec4); outputs come back in
// texel order (index = y * width + x). compare() then checks each value against the C++ result
// within a stated tolerance and reports the count, the number outside it, the largest absolute,
// relative and ulp errors, and the worst texel with its coordinates and every input, so a
// failure says where and why.
//
// The core depends on no test framework: vplkit/parity/doctest.hpp and vplkit/parity/gtest.hpp
// turn a comparison into an assertion. Errors (a GLSL file that does not compile, an include
// that is not found, no GL context, a call from a thread other than the context's, more inputs or
// outputs than the stage has, a tolerance or grid that would let a comparison pass without
// comparing) are thrown as std::runtime_error (vplkit::error) with a message naming the file and
// line, every context that was tried and why it failed, the threads, the limit, or the argument.
//
// The headless context is current on the thread that made it (the first call that needs it), and
// the shader roots belong to that thread too: a GL call from another thread would run without a
// context, so a run or test_shaders() there throws, naming both threads.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include <vplkit/gl/program.hpp>
#include <vplkit/gl/settings_uniforms.hpp>
#include <vplkit/parity/inputs.hpp>

namespace vplkit::parity {

// The GL types a test meets, also by these names: the program a uniform setter receives, the
// shader library, and set_uniforms(program, name, settings) for every vplkit settings struct.
using vplkit::program;
using vplkit::set_uniforms;
using vplkit::shader_library;

/// Adds a folder of one's own GLSL to the include search path. Folders are searched in the order
/// they were added, and all of them before vplkit's own shaders: `#include "my/lights.glsl"`
/// finds the file there, `#include "lib/irradiance.glsl"` finds vplkit's twin (unless a folder
/// added here has its own lib/irradiance.glsl). Adding a folder twice has no effect. Throws when
/// `folder` is not a folder.
void add_shader_root(const std::filesystem::path& folder);

/// The shader library the runs use: the folders given to add_shader_root, then vplkit's shaders
/// ($VPLKIT_SHADER_DIR when set, else the shaders installed with this vplkit). The first call
/// makes the headless context (see test_context_kind).
const shader_library& test_shaders();

/// The headless context the runs use, made on first use and chosen as the vplkit command line
/// chooses it: $VPLKIT_CONTEXT (auto, egl, egl-surfaceless, osmesa; auto: an EGL device, else
/// EGL's surfaceless platform, else OSMesa where built in) and $VPLKIT_EGL_DEVICE (an EGL device
/// index). Returns its kind: "EGL device 0 (software: EGL_MESA_device_software)", "EGL
/// surfaceless" or "OSMesa". Throws, naming every context tried and why it failed, when there is
/// none.
std::string test_context_kind();

/// The GLSL of one kernel run.
struct kernel_source {
  std::string name;                   ///< for messages ("pixel_light_irradiance")
  std::vector<std::pair<std::string, std::string>> defines;  ///< #define NAME VALUE lines before the includes
  std::vector<std::string> includes;  ///< files under a shader root, e.g. "lib/irradiance.glsl"
  std::string declarations;           ///< uniforms and helper functions placed before main
  std::string body;                   ///< statements: read fin*/uin*, write fout*/uout*
  int float_outputs = 0;
  int uint_outputs = 0;
};

struct kernel_outputs {
  std::vector<std::vector<glm::vec4>> floats;   ///< one per float output, width * height each
  std::vector<std::vector<glm::uvec4>> uints;   ///< one per uint output
};

/// Sets the uniforms of a run's program (its declarations' uniforms, with program::set and
/// set_uniforms) before it draws.
using uniform_setter = std::function<void(const program&)>;

/// Evaluates the kernel in a fragment shader (#version 330 core), one fragment per grid texel,
/// into RGBA32F / RGBA32UI render targets. Throws, before making anything, for an empty grid, an
/// input whose size is not width * height, no outputs, or more inputs than
/// GL_MAX_TEXTURE_IMAGE_UNITS or outputs than GL_MAX_DRAW_BUFFERS (at least 16 and 8 in GL 3.3).
kernel_outputs run_fragment(const kernel_source& source, const kernel_inputs& inputs, const uniform_setter& uniforms = {});

/// Evaluates the kernel in a vertex shader (#version 330 core), one vertex per grid texel,
/// captured by transform feedback with rasterisation discarded. Throws as run_fragment does, with
/// the vertex stage's limits: GL_MAX_VERTEX_ATTRIBS inputs (16 in GL 3.3, also llvmpipe's) and
/// GL_MAX_TRANSFORM_FEEDBACK_SEPARATE_ATTRIBS outputs (at least 4).
kernel_outputs run_vertex(const kernel_source& source, const kernel_inputs& inputs, const uniform_setter& uniforms = {});

/// A test's tolerance. A value passes when any of the bounds holds: |gpu - cpu| <= max_abs (times
/// the texel's abs_scale where given), or |gpu - cpu| <= max_rel * max(|gpu|, |cpu|), or the two
/// are at most max_ulp floats apart. A non-finite value on either side always fails. Every bound
/// (and every abs_scale value) must be finite and non-negative, and the fraction in [0, 1]:
/// compare() throws otherwise.
struct tolerance {
  float max_abs = 0.0f;
  float max_rel = 0.0f;
  std::int64_t max_ulp = 0;
  /// Fraction of values allowed outside the bounds (discrete decisions that flip on near-ties);
  /// the failing texels are listed in the report either way.
  double allowed_mismatch_fraction = 0.0;
  /// Why these bounds: written next to every test.
  std::string reason;
  /// Empty, or one scale per texel and channel (inputs' texel order): texel i's channel c passes
  /// at |gpu - cpu| <= max_abs * abs_scale[i][c]. For kernels whose rounding error follows the
  /// size of intermediate terms rather than of the result (a dot product that cancels, a 1/d^2),
  /// so that one bound in units of that size holds everywhere.
  std::vector<glm::vec4> abs_scale = {};
};

struct comparison {
  std::string kernel;
  std::size_t values = 0;        ///< texels * channels compared
  std::size_t mismatches = 0;    ///< values outside tolerance (or non-finite)
  std::size_t allowed_mismatches = 0;
  double max_abs = 0.0;
  double max_rel = 0.0;
  std::int64_t max_ulp = 0;
  double max_abs_over_bound = 0.0;  ///< the largest |gpu - cpu| / its absolute bound (finite values)
  /// The worst value: "texel (x, y).c: gpu=... cpu=... (abs ..., rel ..., ulp ...); fin0=(...) ...".
  /// For floats the value furthest outside (or nearest to leaving) the tolerance, a non-finite
  /// one first; for integers the first mismatch.
  std::string worst;
  std::string mismatch_list;     ///< the first 8 mismatching values, one per line
  tolerance bounds;              ///< what compare() checked against (compare_exact: exact)
  bool passed() const { return mismatches <= allowed_mismatches; }
  /// The measured errors and the worst texel, printed by every parity test; when it failed, also
  /// the tolerance and its reason.
  std::string summary() const;
};

/// ULP distance between two finite floats (0 for equal values, including +0 and -0).
std::int64_t ulp_distance(float a, float b);

/// Compares float outputs channel by channel (`channels` of the 4, from x: 1 to 4). Throws when
/// the grid is empty, when gpu, cpu or any input does not have one value per texel, when
/// `channels` is outside 1..4, or when the tolerance is not finite and non-negative with a
/// fraction in [0, 1]: each of these would otherwise pass without comparing, or read past the end.
comparison compare(const std::string& kernel, const std::vector<glm::vec4>& gpu, const std::vector<glm::vec4>& cpu,
                   const kernel_inputs& inputs, const tolerance& bounds, int channels = 4);

/// Compares integer outputs: exact, except the stated fraction of flipped values. Throws as
/// compare() does.
comparison compare_exact(const std::string& kernel, const std::vector<glm::uvec4>& gpu,
                         const std::vector<glm::uvec4>& cpu, const kernel_inputs& inputs,
                         double allowed_mismatch_fraction = 0.0, int channels = 4);

namespace detail {
/// Records where vplkit's own shaders are, for test_shaders() when $VPLKIT_SHADER_DIR is not set.
bool record_vplkit_shader_dir(const char* folder);
#ifdef VPLKIT_PARITY_SHADER_DIR
// The CMake target vplkit::parity defines VPLKIT_PARITY_SHADER_DIR for the code that links it:
// the shaders installed next to the library (share/vplkit/shaders of the prefix it was found
// in, wherever the prefix was moved), or the source tree's shaders/ in vplkit's own build. A
// static library cannot know where it was installed; this records it in every program that
// includes this header, before main.
inline const bool vplkit_shader_dir_recorded = record_vplkit_shader_dir(VPLKIT_PARITY_SHADER_DIR);
#endif
}  // namespace detail

}  // namespace vplkit::parity
