// What the parts of vplkit::parity share: contexts.cpp (the headless contexts, the shader
// search path, the targets), glsl_sources.cpp (a kernel's GLSL per stage and target), runs.cpp
// (the checks and the runs) and compare.cpp (the comparison and its report). Private: it is not
// under parity/include/, so it is neither installed nor reachable by a user of vplkit::parity.
#pragma once

#include <string>

#include <vplkit/parity/parity.hpp>

#include "frontend/gl/context.hpp"

namespace vplkit::parity::detail {

// The context of a GL target, made if need be and current on return; `call` names the function
// for the error when this is not the owner thread.
const gl_context& context_for(target where, const std::string& call);

// A run on gl45 or gles3 makes the default (gl33) context current again when it ends, also by an
// exception: a test makes its textures in the default context between runs. Declared before the
// run's GL objects, so that they are deleted in the run's own context first.
struct default_context_again {
  ~default_context_again();
};

// The shader library, made on the first call from vplkit's shaders and the added roots; `call`
// names the function for the error when this is not the owner thread.
const shader_library& shaders_for(const std::string& call);

// The grid and every input's size, for the runs and for compare: a grid of 0 texels would
// compare nothing and pass, and an input shorter than the grid would be read past its end (by the
// upload, and by the report that lists a texel's inputs).
void check_grid(const std::string& what, const kernel_inputs& inputs);

// A kernel's whole GLSL for one stage on one target, before expansion: the target's preamble, the
// source's defines and includes, the inputs, outputs, tables and blocks, then its declarations and body.
std::string fragment_source(const kernel_source& source, const kernel_inputs& inputs, target where, const kernel_resources& resources);
std::string vertex_source(const kernel_source& source, const kernel_inputs& inputs, target where, const kernel_resources& resources);
// One invocation per texel in work groups of 64; storage buffers in binding order: the float
// inputs, the uint inputs, the float outputs, the uint outputs, the vec4 tables, the uvec4
// tables (and on Vulkan the uniform blocks).
std::string compute_source(const kernel_source& source, const kernel_inputs& inputs, target where, const kernel_resources& resources);

}  // namespace vplkit::parity::detail
