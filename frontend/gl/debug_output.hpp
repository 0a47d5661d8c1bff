// KHR_debug messages routed to the error path. The driver calls back from inside GL calls, where
// throwing would cross C frames, so the callback records errors and check_gl throws them (with
// glGetError's code) at the next check point, naming the operation that was being done.
#pragma once

#include <cstddef>
#include <string>

namespace vplkit {

/// Enables KHR_debug output on the current context (synchronous) when the driver has it.
void install_debug_output();

/// GL errors (and undefined-behaviour or high-severity messages) the driver reported through
/// KHR_debug that no check_gl has turned into a vplkit::error (on any thread, since the process
/// started). The test binaries and the CLI fail when it is not 0 at exit, so an error after a
/// pipeline's last check point, or one a new context's setup dropped, still fails the run.
std::size_t unchecked_gl_error_count();

/// Drops the messages pending since the last check without throwing, and stops counting them:
/// for the driver's copy of a compile or link log that the caller reports itself.
void discard_pending_gl_messages();

/// Throws vplkit::error "GL error during <what>: ..." if the driver reported an error since the
/// last check (through KHR_debug or glGetError). Clears the pending errors either way.
void check_gl(const std::string& what);

}  // namespace vplkit
