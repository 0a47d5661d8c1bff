// The targets vplkit's own parity tests run a kernel on, and how: gl33 and gles3 in a fragment
// shader, gl45 in a compute shader (its fragment path is gl33's with another #version line) and
// vulkan in a compute shader on lavapipe (every_target). A kernel that vplkit evaluates per
// vertex runs in the vertex stage on the three GL targets and, as the same GLSL function, in a
// compute shader on gl45 and vulkan (every_vertex_target). scripts/setup.sh installs every driver these need, so a
// target this machine cannot run fails the test with target_unavailable's reason instead of
// being skipped: on vplkit's own machines a skip would hide a lost driver. (The consumer test,
// tests/consumer/parity, which proves an installed package on whatever machine it lands on,
// skips visibly instead.)
#pragma once

#include <doctest/doctest.h>

#include <cstdlib>
#include <string>
#include <vector>

#include <vplkit/parity/parity.hpp>

namespace vplkit::testing {

struct target_run {
  parity::target where;
  const char* stage;  // "fragment", "vertex" or "compute"
  parity::kernel_outputs (*run)(const parity::kernel_source&, const parity::kernel_inputs&, parity::target, const parity::kernel_resources&);
  std::string name() const { return std::string(parity::target_name(where)) + " " + stage; }
};

inline parity::kernel_outputs fragment_run(const parity::kernel_source& source, const parity::kernel_inputs& inputs, parity::target where,
                                           const parity::kernel_resources& resources) {
  return parity::run_fragment(source, inputs, where, resources);
}

inline parity::kernel_outputs vertex_run(const parity::kernel_source& source, const parity::kernel_inputs& inputs, parity::target where,
                                         const parity::kernel_resources& resources) {
  return parity::run_vertex(source, inputs, where, resources);
}

inline parity::kernel_outputs compute_run(const parity::kernel_source& source, const parity::kernel_inputs& inputs, parity::target where,
                                          const parity::kernel_resources& resources) {
  return parity::run_compute(source, inputs, where, resources);
}

inline const std::vector<target_run>& every_target() {
  static const std::vector<target_run> runs = {{parity::target::gl33, "fragment", fragment_run},
                                                {parity::target::gl45, "compute", compute_run},
                                                {parity::target::gles3, "fragment", fragment_run},
                                                {parity::target::vulkan, "compute", compute_run}};
  return runs;
}

// Transform feedback on every GL target (its capture, the vertex attributes and the tables as
// vertex-stage textures are the vertex path's own), then compute where there is one: Vulkan has no
// vertex path in vplkit::parity.
inline const std::vector<target_run>& every_vertex_target() {
  static const std::vector<target_run> runs = {{parity::target::gl33, "vertex", vertex_run},
                                                {parity::target::gl45, "vertex", vertex_run},
                                                {parity::target::gles3, "vertex", vertex_run},
                                                {parity::target::gl45, "compute", compute_run},
                                                {parity::target::vulkan, "compute", compute_run}};
  return runs;
}

/// Whether to run `where`: true when this machine runs it. Otherwise the test fails, naming the
/// target and why, except in one case: under VPLKIT_CONTEXT=osmesa (the slow tier's OSMesa repeat
/// of the parity tests) gl45 and gles3 cannot be made, OSMesa having GL 3.3 core only; the run is
/// left out with a message that says so.
inline bool target_runs(parity::target where) {
  const std::string reason = parity::target_unavailable(where);
  if (reason.empty()) return true;
  const char* api = std::getenv("VPLKIT_CONTEXT");
  if (api && std::string(api) == "osmesa" && (where == parity::target::gl45 || where == parity::target::gles3)) {
    MESSAGE("target " << std::string(parity::target_name(where)) << " not run: VPLKIT_CONTEXT=osmesa, whose contexts are GL 3.3 core only");
    return false;
  }
  FAIL("target " << std::string(parity::target_name(where)) << " is unavailable (scripts/setup.sh installs every driver): " << reason);
  return false;
}

}  // namespace vplkit::testing
