// Reading and writing whole files with the guarantees the CLI promises: a file is read only when
// it is a regular file within a size limit (so /dev/zero or a 10 GB file is refused by name before
// anything is allocated), and outputs are written whole or not at all: each to a temporary file
// next to its target; then, holding a lock on the output folder, every previous file is moved
// aside and every new one renamed in; any failure puts the previous files back. An output that
// exists and is not a regular file (a device, a FIFO) is written through, as cp does, and never
// renamed over, moved or deleted. Every message names the file and keeps the system's reason
// (strerror).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <streambuf>
#include <string>
#include <system_error>
#include <vector>

#include "frontend/core/error.hpp"

namespace vplkit {

/// The whole contents of `path`. Throws vplkit::error naming the path and `what` it was read as
/// ("OBJ file", "shader file") when it does not exist, is not a regular file, is larger than
/// `max_bytes`, or cannot be read.
std::string read_file(const std::filesystem::path& path, std::uintmax_t max_bytes, const std::string& what);

/// The same into a byte vector (tinygltf's buffers), without a second copy.
void read_file_into(const std::filesystem::path& path, std::uintmax_t max_bytes, const std::string& what, std::vector<unsigned char>& out);

/// Writes `bytes` to `path` whole or not at all (write_all_or_nothing with one file).
void write_bytes_atomically(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes);

/// One output of a command: its path and the function that encodes its bytes. encode may throw
/// vplkit::error (e.g. a non-finite pixel); the message then names the path.
struct output_file {
  std::filesystem::path path;
  std::function<std::vector<std::uint8_t>()> encode;
};

/// How write_all_or_nothing installs a set.
struct write_options {
  /// How long to wait while another process holds the lock of an output folder (its install
  /// phase takes milliseconds; a holder that long is stuck). Then the write fails, naming it.
  double lock_wait_seconds = 60.0;
  /// The file system's rename(2), as an error code; tests replace it to make a rename fail.
  std::function<std::error_code(const std::filesystem::path& from, const std::filesystem::path& to)> rename;
};

/// An exclusive lock on a folder, held while the object lives: flock on the file `name` in it,
/// created when taken and removed when released. write_all_or_nothing takes
/// ".vplkit-output.lock" for the milliseconds it installs a set; `vplkit sweep` takes
/// ".vplkit-sweep.lock" for its whole run (another file: its own writes take the first, and flock
/// refuses a second lock on one file even within the process). Waits at most `wait_seconds`
/// while another process holds it, then throws folder_lock_busy naming the lock; throws
/// vplkit::error when the lock file cannot be made.
class folder_lock {
 public:
  folder_lock(const std::filesystem::path& folder, double wait_seconds, const std::string& name = ".vplkit-output.lock");
  ~folder_lock();
  folder_lock(const folder_lock&) = delete;
  folder_lock& operator=(const folder_lock&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  int descriptor_ = -1;
};

/// What folder_lock throws when another process held the lock for all of `wait_seconds`.
class folder_lock_busy : public error {
 public:
  using error::error;
};

/// Writes every file or none, and keeps the previous set when it fails:
///  1. every file is encoded and written to a new temporary next to its target (O_EXCL; the
///     name is "." + at most 64 bytes of the target's name + ".partial-" + 16 hex digits, so a
///     legal 255-byte target name still has a legal temporary);
///  2. a lock file in each target folder (".vplkit-output.lock", flock) is taken, so that two
///     runs writing to the same folder install their sets one after the other, never mixed;
///  3. each existing target is moved aside (".<name>.old-<hex>") and its temporary renamed in;
///  4. on any failure the new files are removed and the previous ones renamed back; on success
///     the previous ones are deleted. The lock file is removed when released.
/// Only regular files are replaced (output_target says how each path is treated):
///  - a path that exists and is not a regular file (a character or block device, a FIFO) is
///    written through, as cp does: opened for writing (never created, truncated, renamed or
///    removed) and given the bytes after every temporary of step 1 is written and before any
///    lock is taken (a FIFO waits for its reader, as with cp). A failed write (ENOSPC on
///    /dev/full) is an error with the system's reason and installs nothing; bytes a device has
///    taken cannot be taken back. A socket, which cannot be opened, is refused by name;
///  - a symbolic link is followed: to an existing regular file, that file is replaced whole (the
///    link stays a link); to a device or FIFO, it is written through; a dangling link is refused
///    by name (as cp refuses to write through one), so that no file appears where a link points;
///  - an entry that is not a regular file when step 3 reaches it (one put there meanwhile) is
///    refused and left as it is.
/// Two outputs with the same path are an error. Throws vplkit::error naming the file that failed
/// and the system's reason (and where a previous file is kept if it could not be put back).
void write_all_or_nothing(const std::vector<output_file>& files, const write_options& options = {});

/// How write_all_or_nothing treats an output path.
struct output_target {
  /// The regular file to replace whole (the link's target for a link to one), or the path to
  /// write through.
  std::filesystem::path path;
  bool write_through = false;  ///< a device or FIFO (or a link to one): written through
};

/// Classifies `path` as write_all_or_nothing does. Throws vplkit::error naming it for a dangling
/// link, a link whose target cannot be told, or an entry that cannot be written (a socket).
output_target output_target_of(const std::filesystem::path& path);

/// A stream buffer writing to a file descriptor (the executable's standard output) with write(2),
/// keeping the first failure's errno: a command's printed results are its output too, and a lost
/// one (`> /dev/full`, a closed descriptor) must fail the command with the system's reason
/// instead of exiting 0. Buffered in 64 KiB blocks, by line on a terminal; once a write fails,
/// the stream goes bad and the rest is dropped.
class descriptor_output : public std::streambuf {
 public:
  explicit descriptor_output(int descriptor);
  ~descriptor_output() override;
  descriptor_output(const descriptor_output&) = delete;
  descriptor_output& operator=(const descriptor_output&) = delete;
  /// The errno of the first failed write, 0 while none failed.
  int failure() const { return failure_; }

 protected:
  std::streamsize xsputn(const char* text, std::streamsize count) override;
  int_type overflow(int_type c) override;
  int sync() override;

 private:
  bool write_pending();
  int descriptor_;
  bool by_line_;
  int failure_ = 0;
  std::string pending_;
};

/// The temporary name step 1 uses for `target` with `tag` ("partial", "old") and a random suffix:
/// at most 1 + 64 + 1 + tag + 1 + 16 bytes, in the target's folder.
std::filesystem::path sibling_temporary_name(const std::filesystem::path& target, const std::string& tag);

/// Whether `a` and `b` name the same file, whether or not it exists yet: what a command checks so
/// that an output cannot overwrite one of its inputs (through a link or "dir/../name" included).
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

}  // namespace vplkit
