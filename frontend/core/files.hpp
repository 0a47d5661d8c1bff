// Reading and writing whole files with the guarantees the CLI promises: a file is read only when
// it is a regular file within a size limit (so /dev/zero or a 10 GB file is refused by name before
// anything is allocated), and outputs are written whole or not at all: each to a temporary file
// next to its target, renamed over it only after every temporary of the set was written.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace vplkit {

/// The whole contents of `path`. Throws vplkit::error naming the path and `what` it was read as
/// ("OBJ file", "shader file") when it does not exist, is not a regular file, is larger than
/// `max_bytes`, or cannot be read.
std::string read_file(const std::filesystem::path& path, std::uintmax_t max_bytes, const std::string& what);

/// Writes `bytes` to `path` whole or not at all (temporary file + rename). Throws vplkit::error
/// naming the path.
void write_bytes_atomically(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes);

/// One output of a command: its path and the function that encodes its bytes.
struct output_file {
  std::filesystem::path path;
  std::function<std::vector<std::uint8_t>()> encode;
};

/// Writes every file or none: all are encoded and written to temporaries first; only then are
/// the temporaries renamed over their targets, and if a rename fails the targets already renamed
/// and the remaining temporaries are removed. Two outputs with the same path are an error.
/// Throws vplkit::error naming the file that failed and why.
void write_all_or_nothing(const std::vector<output_file>& files);

}  // namespace vplkit
