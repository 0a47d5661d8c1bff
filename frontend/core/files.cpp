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
    if (failure != 0) {
      ::unlink(temporary.c_str());
      throw error("cannot write " + shown_path(path) + ": " + reason_of(failure));
    }
    return temporary;
  }
}

std::error_code system_rename(const fs::path& from, const fs::path& to) {
  std::error_code code;
  fs::rename(from, to, code);
  return code;
}

// An exclusive lock on a folder's output set: flock on ".vplkit-output.lock" in it, removed on
// release. The file is checked to be the one still at the path after locking (a releasing run
// may have unlinked the one we opened), so two runs never both hold it.
class folder_lock {
 public:
  folder_lock(const fs::path& folder, double wait_seconds) : path_(folder / ".vplkit-output.lock") {
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
        throw error("cannot write to " + shown_path(folder) + ": another process has held its output lock " + shown_path(path_) + " for more than " +
                    std::to_string(static_cast<long>(wait_seconds)) + " s");
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  ~folder_lock() {
    ::unlink(path_.c_str());
    ::close(descriptor_);
  }
  folder_lock(const folder_lock&) = delete;
  folder_lock& operator=(const folder_lock&) = delete;

 private:
  fs::path path_;
  int descriptor_ = -1;
};

}  // namespace

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

  // 1. Every temporary, or none.
  std::vector<fs::path> temporaries;
  const auto remove_temporaries = [&] {
    for (const fs::path& temporary : temporaries) ::unlink(temporary.c_str());
  };
  try {
    for (const output_file& file : files) {
      std::vector<std::uint8_t> bytes;
      try {
        bytes = file.encode();
      } catch (const error& failure) {
        throw error("cannot write " + shown_path(file.path) + ": " + failure.what());
      }
      temporaries.push_back(write_temporary(file.path, bytes));
    }
  } catch (...) {
    remove_temporaries();
    throw;
  }

  // 2. The folders' locks, in a fixed order (two runs never wait on each other crosswise).
  std::set<fs::path> folders;
  for (const output_file& file : files) folders.insert(fs::absolute(file.path).lexically_normal().parent_path());
  std::vector<std::unique_ptr<folder_lock>> locks;
  try {
    for (const fs::path& folder : folders) locks.push_back(std::make_unique<folder_lock>(folder, options.lock_wait_seconds));
  } catch (...) {
    remove_temporaries();
    throw;
  }

  // 3. Each previous file aside, each new one in; 4. back on failure.
  struct installed {
    fs::path target;
    std::optional<fs::path> previous;  ///< where the previous file was moved aside
    bool new_in = false;
  };
  std::vector<installed> done;
  const auto roll_back = [&]() -> std::string {
    std::string kept;
    for (auto entry = done.rbegin(); entry != done.rend(); ++entry) {
      if (entry->new_in) ::unlink(entry->target.c_str());
      if (entry->previous) {
        if (const std::error_code code = rename(*entry->previous, entry->target))
          kept += "; the previous " + shown_path(entry->target) + " could not be put back (" + code.message() + ") and is kept as " +
                  shown_path(*entry->previous);
      }
    }
    for (std::size_t i = done.size(); i < temporaries.size(); ++i) ::unlink(temporaries[i].c_str());
    if (!done.empty() && !done.back().new_in) ::unlink(temporaries[done.size() - 1].c_str());
    return kept;
  };
  for (std::size_t i = 0; i < files.size(); ++i) {
    const fs::path& target = files[i].path;
    done.push_back({target, std::nullopt, false});
    struct stat existing {};
    if (::lstat(target.c_str(), &existing) == 0) {
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
