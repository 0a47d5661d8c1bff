// The frontend's one error type. Every failure a user can cause or meet (a missing file, a shader
// that does not compile, no GL context, an out-of-range setting) becomes a vplkit::error whose
// message names the thing and where it is, so the CLI prints it and exits non-zero.
//
// Why exceptions rather than result values here: a failure deep in a pipeline must unwind GL
// objects and temporary files on the way out (RAII does that), and no frontend function can
// usefully continue past one. The kernels in include/ never throw; they validate with
// `validate(...)` functions that return a message.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace vplkit {

class error : public std::runtime_error {
 public:
  explicit error(const std::string& message) : std::runtime_error(message) {}
};

/// The longest piece of input a message echoes: a 16 MiB data URI or a 100 000-character path
/// makes a message nobody reads, and a log line nobody can grep.
inline constexpr std::size_t max_echoed_characters = 200;

/// `text` as a message echoes it: whole when it has at most `limit` bytes, else its first `limit`
/// (not cutting a UTF-8 sequence) and "... (N bytes)".
inline std::string excerpt(std::string_view text, std::size_t limit = max_echoed_characters) {
  if (text.size() <= limit) return std::string(text);
  std::size_t cut = limit;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xc0) == 0x80) --cut;  // a continuation byte
  std::string shortened(text.substr(0, cut));
  shortened += "... (";
  shortened += std::to_string(text.size());
  shortened += " bytes)";
  return shortened;
}

/// A path as a message echoes it: whole when it has at most `limit` bytes, else its start and its
/// end (the file name, which says most) around "...", and "(N bytes)".
inline std::string excerpt_path(std::string_view path, std::size_t limit = max_echoed_characters) {
  if (path.size() <= limit) return std::string(path);
  std::size_t head = limit / 4, tail = path.size() - (limit - head);
  while (head > 0 && (static_cast<unsigned char>(path[head]) & 0xc0) == 0x80) --head;
  while (tail < path.size() && (static_cast<unsigned char>(path[tail]) & 0xc0) == 0x80) ++tail;
  std::string shortened(path.substr(0, head));
  shortened += "...";
  shortened += path.substr(tail);
  shortened += " (";
  shortened += std::to_string(path.size());
  shortened += " bytes)";
  return shortened;
}

}  // namespace vplkit
