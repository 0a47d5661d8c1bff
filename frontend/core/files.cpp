#include "frontend/core/files.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>
#include <random>
#include <set>
#include <thread>

#include "frontend/core/error.hpp"

namespace vplkit {
namespace fs = std::filesystem;

namespace {

std::string size_text(std::uintmax_t bytes) {
  if (bytes >= (std::uintmax_t{1} << 30) && bytes % (std::uintmax_t{1} << 30) == 0) return std::to_string(bytes >> 30) + " GiB";
  if (bytes >= (std::uintmax_t{1} << 20) && bytes % (std::uintmax_t{1} << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
  return std::to_string(bytes) + " bytes";
}

std::string shown_path(const fs::path& path) { return excerpt_path(path.string()); }

std::string reason_of(int code) { return std::generic_category().message(code); }

// The checks read_file and read_file_into share: a regular file within the limit; its size.
std::uintmax_t checked_size(const fs::path& path, std::uintmax_t max_bytes, const std::string& what) {
  std::error_code code;
  const fs::file_status status = fs::status(path, code);
  if (code && code != std::errc::no_such_file_or_directory) throw error(shown_path(path) + ": cannot read the " + what + " (" + code.message() + ")");
  if (code || !fs::exists(status)) throw error(shown_path(path) + ": no such " + what);
  if (!fs::is_regular_file(status)) throw error(shown_path(path) + ": not a regular file (expected an " + what + ")");
  const std::uintmax_t bytes = fs::file_size(path, code);
  if (code) throw error(shown_path(path) + ": cannot read the " + what + " (" + code.message() + ")");
  if (bytes > max_bytes)
    throw error(shown_path(path) + ": the " + what + " is " + size_text(bytes) + ", more than the " + size_text(max_bytes) + " vplkit reads");
  return bytes;
}

// Reads exactly `bytes` bytes of `path` into `data`.
void read_exactly(const fs::path& path, const std::string& what, char* data, std::uintmax_t bytes) {
  const int descriptor = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (descriptor < 0) throw error(shown_path(path) + ": cannot open the " + what + " (" + reason_of(errno) + ")");
  std::uintmax_t done = 0;
  while (done < bytes) {
    const std::size_t chunk = static_cast<std::size_t>(std::min<std::uintmax_t>(bytes - done, std::uintmax_t{1} << 30));
    const ssize_t got = ::read(descriptor, data + done, chunk);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) {
      const int code = got < 0 ? errno : 0;
      ::close(descriptor);
      throw error(shown_path(path) + ": the " + what + " could not be read whole (" + (code ? reason_of(code) : "it shrank while being read") + ")");
    }
    done += static_cast<std::uintmax_t>(got);
  }
  ::close(descriptor);
}

// The folder `path` goes into, created if needed.
fs::path parent_folder_of(const fs::path& path) {
  const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code code;
  fs::create_directories(parent, code);
  if (code || !fs::is_directory(parent))
    throw error("cannot write " + shown_path(path) + ": cannot create folder " + shown_path(parent) +
                (code ? " (" + code.message() + ")" : std::string(" (a file is in the way)")));
  return parent;
}

std::string random_hex() {
  static thread_local std::mt19937_64 generator{std::random_device{}() ^ (static_cast<std::uint64_t>(::getpid()) << 32)};
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(generator()));
  return text;
}

// Writes all of `bytes` to `descriptor` and closes it: 0, or the errno of the first failure
// (NFS and full disks may report only on close).
int write_and_close(int descriptor, const std::vector<std::uint8_t>& bytes) {
  std::size_t done = 0;
  int failure = 0;
  while (done < bytes.size()) {
    const ssize_t written = ::write(descriptor, bytes.data() + done, std::min<std::size_t>(bytes.size() - done, std::size_t{1} << 30));
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) {
      failure = written < 0 ? errno : EIO;
      break;
    }
    done += static_cast<std::size_t>(written);
  }
  if (::close(descriptor) != 0 && failure == 0) failure = errno;  // NFS and full disks report on close
  return failure;
}

// Writes `bytes` to a new temporary file next to `path` (O_EXCL: never an existing file or a
// link someone placed there) and returns its name.
fs::path write_temporary(const fs::path& path, const std::vector<std::uint8_t>& bytes) {
  parent_folder_of(path);
  std::error_code code;
  if (fs::is_directory(path, code)) throw error("cannot write " + shown_path(path) + ": a folder of that name is in the way");
  for (int attempt = 0;; ++attempt) {
    const fs::path temporary = sibling_temporary_name(path, "partial");
    const int descriptor = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (descriptor < 0) {
      const int reason = errno;
      if (reason == EEXIST && attempt < 16) continue;
      throw error("cannot write " + shown_path(path) + ": cannot create a temporary file next to it (" + reason_of(reason) + ")");
    }
    if (const int failure = write_and_close(descriptor, bytes); failure != 0) {
      ::unlink(temporary.c_str());
      throw error("cannot write " + shown_path(path) + ": " + reason_of(failure));
    }
    return temporary;
  }
}

// What a file-system entry is, for messages.
std::string kind_of(mode_t mode) {
  if (S_ISREG(mode)) return "a regular file";
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISLNK(mode)) return "a symbolic link";
  return "a special file";
}

// Gives `bytes` to the device or FIFO at `path` as cp does: opened for writing, following links,
// never created or truncated. What was opened is checked not to be a regular file: an entry
// swapped in since it was classified would otherwise be overwritten in place, not whole.
void write_through(const fs::path& path, const std::vector<std::uint8_t>& bytes) {
  const int descriptor = ::open(path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
  if (descriptor < 0) throw error("cannot write " + shown_path(path) + ": " + reason_of(errno));
  struct stat opened {};
  if (::fstat(descriptor, &opened) != 0 || S_ISREG(opened.st_mode)) {
    ::close(descriptor);
    throw error("cannot write " + shown_path(path) + ": it became a regular file while the outputs were made; it is left as it is");
  }
  if (const int failure = write_and_close(descriptor, bytes); failure != 0)
    throw error("cannot write " + shown_path(path) + " (" + kind_of(opened.st_mode) + ", written through): " + reason_of(failure));
}

std::error_code system_rename(const fs::path& from, const fs::path& to) {
  std::error_code code;
  fs::rename(from, to, code);
  return code;
}

}  // namespace

// The lock's file is checked to be the one still at the path after locking (a releasing run may
// have unlinked the one we opened), so two runs never both hold it.
folder_lock::folder_lock(const fs::path& folder, double wait_seconds, const std::string& name) : path_(folder / name) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(std::max(wait_seconds, 0.0));
  for (;;) {
    descriptor_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (descriptor_ < 0) throw error("cannot lock the outputs in " + shown_path(folder) + ": cannot create " + shown_path(path_) + " (" + reason_of(errno) + ")");
    if (::flock(descriptor_, LOCK_EX | LOCK_NB) == 0) {
      struct stat opened {}, at_path {};
      if (::fstat(descriptor_, &opened) == 0 && ::stat(path_.c_str(), &at_path) == 0 && opened.st_dev == at_path.st_dev && opened.st_ino == at_path.st_ino)
        return;
      ::close(descriptor_);  // released and removed by its previous holder meanwhile: lock the new one
      continue;
    }
    const int reason = errno;
    ::close(descriptor_);
    descriptor_ = -1;
    if (reason != EWOULDBLOCK && reason != EINTR)
      throw error("cannot lock the outputs in " + shown_path(folder) + ": " + shown_path(path_) + " (" + reason_of(reason) + ")");
    if (std::chrono::steady_clock::now() >= deadline)
      throw folder_lock_busy("cannot write to " + shown_path(folder) + ": another process has held its output lock " + shown_path(path_) + " for more than " +
                             std::to_string(static_cast<long>(wait_seconds)) + " s");
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

folder_lock::~folder_lock() {
  ::unlink(path_.c_str());
  ::close(descriptor_);
}

fs::path sibling_temporary_name(const fs::path& target, const std::string& tag) {
  constexpr std::size_t kept = 64;
  const std::string name = target.filename().string();
  std::size_t cut = std::min(name.size(), kept);
  while (cut > 0 && cut < name.size() && (static_cast<unsigned char>(name[cut]) & 0xc0) == 0x80) --cut;
  std::string temporary = ".";
  temporary += name.substr(0, cut);
  temporary += ".";
  temporary += tag;
  temporary += "-";
  temporary += random_hex();
  return target.has_parent_path() ? target.parent_path() / temporary : fs::path(temporary);
}

output_target output_target_of(const fs::path& path) {
  struct stat entry {};
  // Not there (a new file), a regular file or a folder (write_temporary names it): replaced whole.
  if (::lstat(path.c_str(), &entry) != 0 || S_ISREG(entry.st_mode) || S_ISDIR(entry.st_mode)) return {path, false};
  struct stat target = entry;
  if (S_ISLNK(entry.st_mode) && ::stat(path.c_str(), &target) != 0) {
    const int reason = errno;
    std::error_code ignored;
    const fs::path to = fs::read_symlink(path, ignored);
    if (reason == ENOENT)
      throw error("cannot write " + shown_path(path) + ": it is a link to " + shown_path(to) +
                  ", which does not exist (vplkit writes through a link only to an existing file)");
    throw error("cannot write " + shown_path(path) + ": cannot follow the link (" + reason_of(reason) + ")");
  }
  if (S_ISSOCK(target.st_mode))
    throw error("cannot write " + shown_path(path) + ": it is " + std::string(S_ISLNK(entry.st_mode) ? "a link to " : "") + "a socket, not a file");
  if (S_ISDIR(target.st_mode)) return {path, false};
  if (!S_ISREG(target.st_mode)) return {path, true};
  // A link to a regular file: that file is replaced whole, in its own folder (a temporary next to
  // the link could be on another file system), and the link stays. The resolved path must still
  // name the file the link does (/proc's links to deleted files resolve to a name that does not).
  std::error_code code;
  const fs::path resolved = fs::canonical(path, code);
  struct stat at_resolved {};
  if (code || ::stat(resolved.c_str(), &at_resolved) != 0 || at_resolved.st_dev != target.st_dev || at_resolved.st_ino != target.st_ino)
    throw error("cannot write " + shown_path(path) + ": cannot tell which file the link names" + (code ? " (" + code.message() + ")" : std::string()));
  return {resolved, false};
}

descriptor_output::descriptor_output(int descriptor) : descriptor_(descriptor), by_line_(::isatty(descriptor) == 1) {}

descriptor_output::~descriptor_output() { write_pending(); }

std::streamsize descriptor_output::xsputn(const char* text, std::streamsize count) {
  if (failure_ != 0 || count <= 0) return 0;
  pending_.append(text, static_cast<std::size_t>(count));
  const bool line_ended = by_line_ && std::memchr(text, '\n', static_cast<std::size_t>(count)) != nullptr;
  if ((pending_.size() >= (std::size_t{1} << 16) || line_ended) && !write_pending()) return 0;
  return count;
}

descriptor_output::int_type descriptor_output::overflow(int_type c) {
  if (traits_type::eq_int_type(c, traits_type::eof())) return sync() == 0 ? traits_type::not_eof(c) : traits_type::eof();
  const char one = traits_type::to_char_type(c);
  return xsputn(&one, 1) == 1 ? c : traits_type::eof();
}

int descriptor_output::sync() { return write_pending() ? 0 : -1; }

bool descriptor_output::write_pending() {
  if (failure_ != 0) return false;
  std::size_t done = 0;
  while (done < pending_.size()) {
    const ssize_t written = ::write(descriptor_, pending_.data() + done, pending_.size() - done);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) {
      failure_ = written < 0 ? errno : EIO;
      pending_.clear();
      return false;
    }
    done += static_cast<std::size_t>(written);
  }
  pending_.clear();
  return true;
}

std::string read_file(const fs::path& path, std::uintmax_t max_bytes, const std::string& what) {
  const std::uintmax_t bytes = checked_size(path, max_bytes, what);
  std::string contents(static_cast<std::size_t>(bytes), '\0');
  read_exactly(path, what, contents.data(), bytes);
  return contents;
}

void read_file_into(const fs::path& path, std::uintmax_t max_bytes, const std::string& what, std::vector<unsigned char>& out) {
  const std::uintmax_t bytes = checked_size(path, max_bytes, what);
  out.assign(static_cast<std::size_t>(bytes), 0);
  read_exactly(path, what, reinterpret_cast<char*>(out.data()), bytes);
}

void write_bytes_atomically(const fs::path& path, const std::vector<std::uint8_t>& bytes) {
  write_all_or_nothing({{path, [&bytes] { return bytes; }}});
}

void write_all_or_nothing(const std::vector<output_file>& files, const write_options& options) {
  // Two outputs with the same lexically normal path: sorted, not compared pairwise (a 5,000-frame
  // --poses sequence has 10,000 outputs, and the pairs took a minute). The message names the
  // first output, in the order given, that repeats an earlier one.
  std::vector<std::pair<fs::path, std::size_t>> normal(files.size());
  for (std::size_t i = 0; i < files.size(); ++i) normal[i] = {files[i].path.lexically_normal(), i};
  std::sort(normal.begin(), normal.end());
  std::size_t repeated = files.size();
  for (std::size_t k = 1; k < normal.size(); ++k)
    if (normal[k].first == normal[k - 1].first) repeated = std::min(repeated, normal[k].second);
  if (repeated < files.size()) throw error("two outputs would be written to " + shown_path(files[repeated].path));
  const auto rename = options.rename ? options.rename : system_rename;

  // Each path as it is treated: a regular file replaced whole, or a device or FIFO written through.
  std::vector<output_target> targets;
  for (const output_file& file : files) targets.push_back(output_target_of(file.path));

  // 1. Every temporary, or none; the bytes of the outputs written through are kept for step 1b.
  std::vector<fs::path> temporaries(files.size());
  std::vector<std::vector<std::uint8_t>> through(files.size());
  const auto remove_temporaries = [&] {
    for (const fs::path& temporary : temporaries)
      if (!temporary.empty()) ::unlink(temporary.c_str());
  };
  try {
    for (std::size_t i = 0; i < files.size(); ++i) {
      std::vector<std::uint8_t> bytes;
      try {
        bytes = files[i].encode();
      } catch (const error& failure) {
        throw error("cannot write " + shown_path(files[i].path) + ": " + failure.what());
      }
      if (targets[i].write_through) through[i] = std::move(bytes);
      else temporaries[i] = write_temporary(targets[i].path, bytes);
    }
    // 1b. The devices and FIFOs, once every file is made (a failed encoding or temporary gives
    // them nothing) and before any lock (a FIFO waits for its reader, holding up no one else).
    std::string written_through;
    for (std::size_t i = 0; i < files.size(); ++i) {
      if (!targets[i].write_through) continue;
      try {
        write_through(targets[i].path, through[i]);
      } catch (const error& failure) {
        throw error(failure.what() + (written_through.empty() ? std::string() : "; " + written_through + " already got its bytes"));
      }
      written_through += (written_through.empty() ? "" : ", ") + shown_path(targets[i].path);
    }
  } catch (...) {
    remove_temporaries();
    throw;
  }

  // 2. The folders' locks, in a fixed order (two runs never wait on each other crosswise).
  std::set<fs::path> folders;
  for (const output_target& target : targets)
    if (!target.write_through) folders.insert(fs::absolute(target.path).lexically_normal().parent_path());
  std::vector<std::unique_ptr<folder_lock>> locks;
  try {
    for (const fs::path& folder : folders) locks.push_back(std::make_unique<folder_lock>(folder, options.lock_wait_seconds));
  } catch (...) {
    remove_temporaries();
    throw;
  }

  // 3. Each previous file aside, each new one in; 4. back on failure.
  struct installed {
    fs::path target, temporary;
    std::optional<fs::path> previous;  ///< where the previous file was moved aside
    bool new_in = false;
  };
  std::vector<installed> done;
  std::vector<bool> started(files.size(), false);
  const auto roll_back = [&]() -> std::string {
    std::string kept;
    for (auto entry = done.rbegin(); entry != done.rend(); ++entry) {
      ::unlink((entry->new_in ? entry->target : entry->temporary).c_str());
      if (entry->previous) {
        if (const std::error_code code = rename(*entry->previous, entry->target))
          kept += "; the previous " + shown_path(entry->target) + " could not be put back (" + code.message() + ") and is kept as " +
                  shown_path(*entry->previous);
      }
    }
    for (std::size_t i = 0; i < files.size(); ++i)
      if (!started[i] && !temporaries[i].empty()) ::unlink(temporaries[i].c_str());
    return kept;
  };
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (targets[i].write_through) continue;
    const fs::path& target = targets[i].path;
    started[i] = true;
    done.push_back({target, temporaries[i], std::nullopt, false});
    struct stat existing {};
    if (::lstat(target.c_str(), &existing) == 0) {
      // Only a regular file is moved aside: anything else put here since step 1 stays as it is.
      if (!S_ISREG(existing.st_mode)) {
        const std::string kept = roll_back();
        throw error("cannot write " + shown_path(target) + ": it is now " + kind_of(existing.st_mode) +
                    ", which appeared while the outputs were made; it is left as it is" + kept);
      }
      const fs::path aside = sibling_temporary_name(target, "old");
      if (const std::error_code code = rename(target, aside)) {
        const std::string kept = roll_back();
        throw error("cannot write " + shown_path(target) + ": cannot move the previous file aside (" + code.message() + ")" + kept);
      }
      done.back().previous = aside;
    }
    if (const std::error_code code = rename(temporaries[i], target)) {
      const std::string kept = roll_back();
      throw error("cannot write " + shown_path(target) + ": " + code.message() + kept);
    }
    done.back().new_in = true;
  }
  for (const installed& entry : done)
    if (entry.previous) ::unlink(entry.previous->c_str());
}

bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code code;
  if (fs::equivalent(a, b, code)) return true;
  return fs::weakly_canonical(a, code) == fs::weakly_canonical(b, code) && !code;
}

}  // namespace vplkit
