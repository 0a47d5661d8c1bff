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
#include <vplkit/std140.hpp>

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

/// Where a kernel runs: the shading languages and APIs a user ships the twins in.
///   gl33    GL 3.3 core, `#version 330 core`: fragment and vertex (the default of every run)
///   gl45    GL 4.5 core, `#version 450 core`: fragment, vertex and compute
///   gles3   OpenGL ES 3.0 (the WebGL2 subset), `#version 300 es` with highp precision:
///           fragment and vertex; ES 3.0 has no compute shaders
///   vulkan  Vulkan 1.0, `#version 450` compiled to SPIR-V by glslang at run time: compute only
/// Each GL target has its own headless context (EGL; GLES through EGL_OPENGL_ES_API), made on
/// first use on the thread of the first parity call; the default (gl33) context is current again
/// after a run on another target, so textures made between runs stay in it. Vulkan takes the
/// first device that has a compute queue (Mesa's lavapipe on a machine without a GPU).
enum class target { gl33, gl45, gles3, vulkan };
/// "gl33", "gl45", "gles3", "vulkan".
const char* target_name(target where);
/// Every target, in the order above.
const std::vector<target>& all_targets();
/// Empty when this machine runs kernels on `where`; otherwise why not, naming what is missing
/// (the context that failed and why, the Vulkan loader or a device, with the Debian package).
/// Tests skip a target only on this reason and print it.
std::string target_unavailable(target where);
/// The first lines of every shader a run compiles for `where`: its #version line, and for gles3
/// the precision statements (highp float, int, sampler2D and usampler2D: ES defaults to mediump
/// floats in fragment shaders and has no default for integer samplers). The one place a lib file
/// is wrapped for a target; docs/glsl-twins.md shows the same lines for one's own shaders.
std::string glsl_preamble(target where);

/// A read-only 2D table a kernel reads (an RSM, a cube map laid out flat, a packed RSM's words),
/// the same on every target: of vec4 (kernel_table), its declarations call `vec4 <name>(ivec2
/// texel)`; of uvec4 (kernel_uint_table), `uvec4 <name>(ivec2 texel)`, every bit as given. In a
/// fragment or vertex run it is a texture read with texelFetch: RGBA32F through a sampler2D, or
/// RGBA32UI through a usampler2D; in a compute run a std430 storage buffer of vec4 or uvec4 read
/// at texel.y * width + texel.x. A texel outside the table is undefined, as texelFetch's is.
template <typename Texel>
struct basic_kernel_table {
  std::string name;
  int width = 0;
  int height = 0;
  std::vector<Texel> texels;  ///< width * height, texel (x, y) at y * width + x
};
using kernel_table = basic_kernel_table<glm::vec4>;
using kernel_uint_table = basic_kernel_table<glm::uvec4>;

/// A std140 uniform block holding one value of a GLSL struct: declared by the run as
///   layout(std140[, set = 0, binding = N]) uniform <member>_block { <type> <member>; };
/// (std140_block's text; Vulkan adds the set and binding), and filled from `bytes`. Make it with
/// settings_block(member, settings) for a vplkit settings struct.
struct kernel_block {
  std::string type;    ///< the GLSL struct's name, e.g. "rsm_gather_settings"
  std::string member;  ///< the name the kernel reads it by, e.g. "settings"
  std::vector<std::byte> bytes;
};

/// `settings` in a uniform block (std140_bytes of vplkit/std140.hpp) read as `member`.
template <typename Settings>
kernel_block settings_block(const std::string& member, const Settings& settings) {
  const auto bytes = std140_bytes(settings);
  return {settings_description<Settings>::name, member, std::vector<std::byte>(bytes.begin(), bytes.end())};
}

/// What a run binds besides its inputs: tables of vec4 and of uvec4, uniform blocks, and, on the
/// GL targets only, a setter for default-block uniforms (Vulkan has no default block: a run on
/// vulkan with a setter throws). The uint tables come last so that {tables, blocks, setter} still
/// reads as it did before they existed. Every table and block needs a name of its own.
struct kernel_resources {
  std::vector<kernel_table> tables;
  std::vector<kernel_block> blocks;
  uniform_setter uniforms = {};
  std::vector<kernel_uint_table> uint_tables = {};
};

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

/// The runs on a chosen target, with tables and uniform blocks that work the same on all of
/// them. In every stage the body also reads `ivec2 texel`, the grid texel it computes.
/// run_fragment and run_vertex throw for vulkan (vplkit runs Vulkan kernels as compute shaders),
/// run_compute for gl33 and gles3 (no compute shaders before GL 4.3 / GLES 3.1; WebGL2 has
/// none), each naming the targets that do; every run throws, with target_unavailable's reason,
/// on a target this machine cannot run. A compute run has one invocation per texel (index =
/// y * width + x), inputs and outputs in std430 storage buffers, the same fin*/uin*/fout*/uout*
/// names, and as many storage blocks as GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS (or the device's
/// maxPerStageDescriptorStorageBuffers) allows for inputs, outputs and tables together.
kernel_outputs run_fragment(const kernel_source& source, const kernel_inputs& inputs, target where, const kernel_resources& resources = {});
kernel_outputs run_vertex(const kernel_source& source, const kernel_inputs& inputs, target where, const kernel_resources& resources = {});
kernel_outputs run_compute(const kernel_source& source, const kernel_inputs& inputs, target where, const kernel_resources& resources = {});

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
