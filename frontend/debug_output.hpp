// KHR_debug messages routed to the error path. The driver calls back from inside GL calls, where
// throwing would cross C frames, so the callback records errors and check_gl throws them (with
// glGetError's code) at the next check point, naming the operation that was being done.
#pragma once

#include <string>

namespace vplkit {

/// Enables KHR_debug output on the current context (synchronous) when the driver has it.
void install_debug_output();

/// Throws vplkit::error "GL error during <what>: ..." if the driver reported an error since the
/// last check (through KHR_debug or glGetError). Clears the pending errors either way.
void check_gl(const std::string& what);

}  // namespace vplkit
