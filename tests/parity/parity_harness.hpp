// The CPU/GPU parity harness: runs a GLSL kernel on a grid of inputs under a headless OSMesa
// context, runs the C++ float instantiation on the same inputs, and compares texel by texel.
//
// Inputs go in as RGBA32F / RGBA32UI textures (fragment stage) or as vertex attributes
// (vertex stage, outputs captured with transform feedback). The test writes the GLSL body that
// calls the kernel: it reads `fin0..` (vec4) and `uin0..` (uvec4) and assigns `fout0..` (vec4)
// and `uout0..` (uvec4). Outputs come back in texel order (index = y * width + x).
//
// Comparison reports the count, the number outside tolerance, the max abs / rel / ulp error,
// and the worst texel with its coordinates and every input, so a failure says where and why.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "frontend/gl/program.hpp"
#include "frontend/image/image.hpp"

namespace vplkit::parity {

/// The process-wide headless context and the source-tree shader library (created once).
const shader_library& test_shaders();
/// The kind of the tests' context ("EGL device 0 (...)", "EGL surfaceless", "OSMesa").
std::string test_context_kind();

struct kernel_source {
  std::string name;                   ///< for messages ("pixel_light_irradiance")
  std::vector<std::pair<std::string, std::string>> defines;  ///< #define NAME VALUE lines before the includes
  std::vector<std::string> includes;  ///< lib files, e.g. "lib/irradiance.glsl"
  std::string declarations;           ///< uniforms and helper functions placed before main
  std::string body;                   ///< statements: read fin*/uin*, write fout*/uout*
  int float_outputs = 0;
  int uint_outputs = 0;
};

struct kernel_inputs {
  int width = 0;   ///< grid width (the vertex stage uses width * height vertices)
  int height = 0;
  std::vector<std::vector<glm::vec4>> floats;   ///< each width * height long
  std::vector<std::vector<glm::uvec4>> uints;   ///< each width * height long
  std::size_t size() const { return static_cast<std::size_t>(width) * static_cast<std::size_t>(height); }
};

/// The grid of a whole image compared texel by texel with its CPU mirror (a pass's output): its
/// coordinates, no inputs.
inline kernel_inputs coordinates_of(const image& pass_output) {
  kernel_inputs inputs;
  inputs.width = pass_output.width;
  inputs.height = pass_output.height;
  return inputs;
}

struct kernel_outputs {
  std::vector<std::vector<glm::vec4>> floats;
  std::vector<std::vector<glm::uvec4>> uints;
};

using uniform_setter = std::function<void(const program&)>;

/// Evaluates the kernel in a fragment shader, one fragment per grid texel, into RGBA32F /
/// RGBA32UI render targets.
kernel_outputs run_fragment(const kernel_source& source, const kernel_inputs& inputs, const uniform_setter& uniforms = {});

/// Evaluates the kernel in a vertex shader, one vertex per grid texel, captured by transform
/// feedback with rasterisation discarded.
kernel_outputs run_vertex(const kernel_source& source, const kernel_inputs& inputs, const uniform_setter& uniforms = {});

/// Per-test tolerance. A value passes when any of the bounds holds: |gpu - cpu| <= max_abs,
/// or <= max_rel * max(|gpu|, |cpu|), or the two are at most max_ulp floats apart.
/// A non-finite value on either side always fails.
struct tolerance {
  float max_abs = 0.0f;
  float max_rel = 0.0f;
  std::int64_t max_ulp = 0;
  /// Fraction of texels allowed outside the bounds (discrete decisions that flip on near-ties);
  /// the failing texels are listed in the report either way.
  double allowed_mismatch_fraction = 0.0;
  /// Why these bounds: written next to every test.
  std::string reason;
};

struct comparison {
  std::string kernel;
  std::size_t values = 0;        ///< texels * channels compared
  std::size_t mismatches = 0;    ///< values outside tolerance (or non-finite)
  std::size_t allowed_mismatches = 0;
  double max_abs = 0.0;
  double max_rel = 0.0;
  std::int64_t max_ulp = 0;
  std::string worst;             ///< the worst texel: coordinates, values, inputs
  std::string mismatch_list;     ///< the first mismatching texels
  bool passed() const { return mismatches <= allowed_mismatches; }
  /// One line with the measured errors, printed by every parity test.
  std::string summary() const;
};

/// ULP distance between two finite floats (0 for equal values, including +0 / -0).
std::int64_t ulp_distance(float a, float b);

/// Compares float outputs channel by channel (`channels` of the 4, from x).
comparison compare(const std::string& kernel, const std::vector<glm::vec4>& gpu, const std::vector<glm::vec4>& cpu,
                   const kernel_inputs& inputs, const tolerance& bounds, int channels = 4);

/// Compares integer outputs: exact, except the stated fraction of flipped texels.
comparison compare_exact(const std::string& kernel, const std::vector<glm::uvec4>& gpu,
                         const std::vector<glm::uvec4>& cpu, const kernel_inputs& inputs,
                         double allowed_mismatch_fraction = 0.0, int channels = 4);

/// doctest: prints the summary, and fails with the worst texel when the comparison failed.
void require_parity(const comparison& result);

}  // namespace vplkit::parity
