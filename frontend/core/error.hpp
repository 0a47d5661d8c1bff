// The frontend's one error type. Every failure a user can cause or meet (a missing file, a shader
// that does not compile, no GL context, an out-of-range setting) becomes a vplkit::error whose
// message names the thing and where it is, so the CLI prints it and exits non-zero.
//
// Why exceptions rather than result values here: a failure deep in a pipeline must unwind GL
// objects and temporary files on the way out (RAII does that), and no frontend function can
// usefully continue past one. The kernels in include/ never throw; they validate with
// `validate(...)` functions that return a message.
#pragma once

#include <stdexcept>
#include <string>

namespace vplkit {

class error : public std::runtime_error {
 public:
  explicit error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace vplkit
