// Whole-file reads and all-or-nothing writes (frontend/core/files.hpp): a failed rename at any
// step leaves the previous set in place, temporaries have bounded names, the output lock keeps
// two writers from mixing their sets, every message keeps the system's reason, and same_file
// sees one file under two names. Outputs that are not regular files (device nodes made with
// mknod in a scratch folder, never the real /dev; FIFOs; links) are written through and stay what
// they are, and descriptor_output reports a lost write with its errno.
#include <doctest/doctest.h>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "frontend/core/error.hpp"
#include "frontend/core/files.hpp"
#include "tests/gl_test_helpers.hpp"

namespace fs = std::filesystem;
using namespace vplkit;

namespace {

using vplkit::testing::scratch_folder;

std::string contents(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

output_file text_file(const fs::path& path, const std::string& text) {
  return {path, [text] { return std::vector<std::uint8_t>(text.begin(), text.end()); }};
}

// Every name in the folder, sorted.
std::vector<std::string> names_in(const fs::path& folder) {
  std::vector<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

TEST_CASE("a failed rename at any step of the install leaves the previous set whole, and nothing else") {
  const scratch_folder folder("files");
  const fs::path a = folder.path / "a.png", b = folder.path / "a-indirect.pfm", c = folder.path / "a-indirect.png";
  write_all_or_nothing({text_file(a, "old a"), text_file(b, "old b"), text_file(c, "old c")});
  // Three targets: each moved aside, then its new file renamed in: 6 renames; fail each in turn.
  for (int failing = 0; failing < 6; ++failing) {
    CAPTURE(failing);
    write_options options;
    int count = 0;
    options.rename = [&](const fs::path& from, const fs::path& to) -> std::error_code {
      if (count++ == failing) return std::make_error_code(std::errc::device_or_resource_busy);
      std::error_code code;
      fs::rename(from, to, code);
      return code;
    };
    CHECK_THROWS_WITH_AS(write_all_or_nothing({text_file(a, "new a"), text_file(b, "new b"), text_file(c, "new c")}, options),
                         doctest::Contains("busy"), vplkit::error);
    CHECK(contents(a) == "old a");
    CHECK(contents(b) == "old b");
    CHECK(contents(c) == "old c");
    CHECK(names_in(folder.path) == std::vector<std::string>{"a-indirect.pfm", "a-indirect.png", "a.png"});  // no temporary, no lock
  }
  // A set whose second file is new: a failure removes the first new file and keeps no second.
  const fs::path d = folder.path / "d.png";
  write_options failing_second;
  int count = 0;
  failing_second.rename = [&](const fs::path& from, const fs::path& to) -> std::error_code {
    if (++count == 3) return std::make_error_code(std::errc::operation_not_permitted);
    std::error_code code;
    fs::rename(from, to, code);
    return code;
  };
  const std::string expected = "cannot write " + d.string() + ": Operation not permitted";
  CHECK_THROWS_WITH_AS(write_all_or_nothing({text_file(a, "new a"), text_file(d, "new d")}, failing_second), doctest::Contains(expected.c_str()),
                       vplkit::error);
  CHECK(contents(a) == "old a");
  CHECK(!fs::exists(d));
  // Without failures the new set replaces the old one whole.
  write_all_or_nothing({text_file(a, "new a"), text_file(b, "new b"), text_file(c, "new c")});
  CHECK(contents(a) == "new a");
  CHECK(contents(c) == "new c");
  CHECK(names_in(folder.path) == std::vector<std::string>{"a-indirect.pfm", "a-indirect.png", "a.png"});
}

TEST_CASE("a previous file that cannot be put back is named with where it is kept") {
  const scratch_folder folder("files");
  const fs::path a = folder.path / "a.png", b = folder.path / "b.png";
  write_all_or_nothing({text_file(a, "old a"), text_file(b, "old b")});
  write_options options;
  int count = 0;
  // 1: a aside, 2: new a in, 3: b aside fails; then putting a back (4) fails too.
  options.rename = [&](const fs::path& from, const fs::path& to) -> std::error_code {
    ++count;
    if (count == 3 || count == 4) return std::make_error_code(std::errc::device_or_resource_busy);
    std::error_code code;
    fs::rename(from, to, code);
    return code;
  };
  try {
    write_all_or_nothing({text_file(a, "new a"), text_file(b, "new b")}, options);
    FAIL("the write should have failed");
  } catch (const vplkit::error& failure) {
    const std::string message = failure.what();
    CHECK(message.find("cannot move the previous file aside") != std::string::npos);
    CHECK(message.find("could not be put back") != std::string::npos);
    const std::size_t kept = message.find("is kept as ");
    REQUIRE(kept != std::string::npos);
    CHECK(contents(message.substr(kept + 11)) == "old a");  // the old a, intact where the message says
  }
  CHECK(contents(b) == "old b");
}

TEST_CASE("temporary names stay short: a legal 255-byte output name is written") {
  const scratch_folder folder("files");
  const std::string name = std::string(251, 'n') + ".png";  // 255 bytes, the most a Linux file name has
  const fs::path target = folder.path / name;
  write_bytes_atomically(target, {1, 2, 3});
  CHECK(fs::file_size(target) == 3);
  const fs::path temporary = sibling_temporary_name(target, "partial");
  CHECK(temporary.parent_path() == target.parent_path());
  CHECK(temporary.filename().string().size() <= 1 + 64 + 1 + 7 + 1 + 16);
  // A name one byte too long is refused with the system's reason, not "cannot create a file".
  CHECK_THROWS_WITH_AS(write_bytes_atomically(folder.path / (std::string(256, 'n')), {1}), doctest::Contains("File name too long"), vplkit::error);
  CHECK(names_in(folder.path) == std::vector<std::string>{name});
}

TEST_CASE("every write message keeps the system's reason") {
  const scratch_folder folder("files");
  write_bytes_atomically(folder.path / "a-file", {1});
  CHECK_THROWS_WITH_AS(write_bytes_atomically(folder.path / "a-file" / "x.png", {1}), doctest::Contains("cannot create folder"), vplkit::error);
  fs::create_directories(folder.path / "x.png");
  CHECK_THROWS_WITH_AS(write_bytes_atomically(folder.path / "x.png", {1}), doctest::Contains("a folder of that name is in the way"), vplkit::error);
  // An encoder's error names the file and writes nothing.
  const output_file refusing{folder.path / "y.pfm", []() -> std::vector<std::uint8_t> { throw vplkit::error("pixel (0, 0) is NaN"); }};
  CHECK_THROWS_WITH_AS(write_all_or_nothing({text_file(folder.path / "z.png", "z"), refusing}), doctest::Contains("y.pfm: pixel (0, 0) is NaN"),
                       vplkit::error);
  CHECK(!fs::exists(folder.path / "z.png"));
  CHECK_THROWS_WITH_AS(read_file(folder.path / "missing.obj", 100, "OBJ file"), doctest::Contains("no such OBJ file"), vplkit::error);
  CHECK_THROWS_WITH_AS(read_file("/dev/zero", 100, "OBJ file"), doctest::Contains("not a regular file"), vplkit::error);
  std::vector<unsigned char> bytes;
  read_file_into(folder.path / "a-file", 100, "buffer", bytes);
  CHECK(bytes == std::vector<unsigned char>{1});
  CHECK_THROWS_WITH_AS(read_file_into(folder.path / "a-file", 0, "buffer", bytes), doctest::Contains("more than the 0 bytes"), vplkit::error);
}

TEST_CASE("the output lock: writers to one folder install one after the other, a stuck holder is named") {
  const scratch_folder folder("files");
  const fs::path a = folder.path / "a.png", b = folder.path / "a-indirect.pfm";
  // Two writers, each writing its own pair many times: the pair on disk is always one writer's.
  std::atomic<bool> mixed{false};
  std::atomic<int> failures{0};
  const auto writer = [&](const std::string& tag) {
    for (int k = 0; k < 200; ++k) {
      try {
        write_all_or_nothing({text_file(a, tag), text_file(b, tag)});
      } catch (const vplkit::error&) {
        ++failures;
      }
    }
  };
  std::thread first(writer, "first"), second(writer, "second");
  // Meanwhile a reader takes the lock the writers' way (flock, then the file must still be the
  // one at the path; released by unlink and close) and checks the pair between two installs.
  const fs::path lock_path = folder.path / ".vplkit-output.lock";
  for (int k = 0; k < 200; ++k) {
    int lock = -1;
    for (;;) {
      lock = ::open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
      REQUIRE(lock >= 0);
      REQUIRE(::flock(lock, LOCK_EX) == 0);
      struct stat opened {}, at_path {};
      if (::fstat(lock, &opened) == 0 && ::stat(lock_path.c_str(), &at_path) == 0 && opened.st_ino == at_path.st_ino) break;
      ::close(lock);
    }
    if (fs::exists(a) && fs::exists(b) && contents(a) != contents(b)) mixed = true;
    ::unlink(lock_path.c_str());
    ::close(lock);
  }
  first.join();
  second.join();
  CHECK(!mixed);
  CHECK(failures == 0);
  CHECK(contents(a) == contents(b));
  // A holder that does not let go: the write waits, then fails naming the lock.
  const int held = ::open((folder.path / ".vplkit-output.lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  REQUIRE(::flock(held, LOCK_EX) == 0);
  write_options impatient;
  impatient.lock_wait_seconds = 0.2;
  CHECK_THROWS_WITH_AS(write_all_or_nothing({text_file(a, "third")}, impatient), doctest::Contains("has held its output lock"), vplkit::error);
  ::close(held);
  CHECK(contents(a) != "third");
  CHECK(names_in(folder.path) == std::vector<std::string>{".vplkit-output.lock", "a-indirect.pfm", "a.png"});  // no temporary left
}

TEST_CASE("same_file: one file under two names is the same, existing or not; two names are not") {
  scratch_folder scratch("files");
  const fs::path file = scratch.path / "input.pfm";
  std::ofstream(file) << "x";
  fs::create_directories(scratch.path / "sub");
  fs::create_symlink(file, scratch.path / "link.pfm");

  CHECK(same_file(file, file));
  CHECK(same_file(file, scratch.path / "sub" / ".." / "input.pfm"));
  CHECK(same_file(file, scratch.path / "link.pfm"));
  CHECK_FALSE(same_file(file, scratch.path / "other.pfm"));
  // Neither exists yet: the same name still is the same file, two names are not.
  CHECK(same_file(scratch.path / "new.pfm", scratch.path / "sub" / ".." / "new.pfm"));
  CHECK_FALSE(same_file(scratch.path / "new.pfm", scratch.path / "new2.pfm"));
}

namespace {

// A character device node like /dev/null (1, 3) or /dev/full (1, 7) at `path`; false (with the
// reason in `why`) where mknod is not permitted (no CAP_MKNOD, a nodev mount).
bool make_char_device(const fs::path& path, unsigned minor, std::string& why) {
  if (::mknod(path.c_str(), S_IFCHR | 0666, ::makedev(1, minor)) == 0) return true;
  why = std::strerror(errno);
  return false;
}

// What `path` is now, not following a link: its type bits and, for a device, its numbers.
struct entry_kind {
  mode_t type = 0;
  dev_t device = 0;
};
entry_kind kind_of(const fs::path& path) {
  struct stat entry {};
  REQUIRE(::lstat(path.c_str(), &entry) == 0);
  return {static_cast<mode_t>(entry.st_mode & S_IFMT), entry.st_rdev};
}

}  // namespace

TEST_CASE("device nodes are written through and stay device nodes; ENOSPC is an error that installs nothing") {
  const scratch_folder folder("files");
  const fs::path null = folder.path / "null", full = folder.path / "full", png = folder.path / "a.png";
  std::string why;
  if (!make_char_device(null, 3, why) || !make_char_device(full, 7, why)) {
    MESSAGE("skipped the device-node cases: mknod is not permitted here (" << why << ")");
    return;
  }
  // The old bug: the node was moved aside and a regular file renamed over it.
  write_all_or_nothing({text_file(null, "to the null device"), text_file(png, "new a")});
  CHECK(kind_of(null).type == S_IFCHR);
  CHECK(kind_of(null).device == ::makedev(1, 3));
  CHECK(contents(png) == "new a");
  CHECK(output_target_of(null).write_through);
  CHECK_FALSE(output_target_of(png).write_through);
  // /dev/full takes no byte: ENOSPC with the system's words, the regular file of the same set is
  // not installed (the previous one stays), and the node is still the node.
  CHECK_THROWS_WITH_AS(write_all_or_nothing({text_file(png, "newer a"), text_file(full, "lost")}),
                       doctest::Contains("full (a character device, written through): No space left on device"), vplkit::error);
  CHECK(contents(png) == "new a");
  CHECK(kind_of(full).type == S_IFCHR);
  CHECK(kind_of(full).device == ::makedev(1, 7));
  // A link to a device is written through too, and stays a link.
  fs::create_symlink(full, folder.path / "to-full");
  CHECK_THROWS_WITH_AS(write_bytes_atomically(folder.path / "to-full", {1, 2}), doctest::Contains("No space left on device"), vplkit::error);
  CHECK(fs::is_symlink(folder.path / "to-full"));
  CHECK(kind_of(full).type == S_IFCHR);
  // Nothing else was left: no temporary, no moved-aside node.
  CHECK(names_in(folder.path) == std::vector<std::string>{"a.png", "full", "null", "to-full"});
}

TEST_CASE("a FIFO's reader gets the bytes, and the FIFO stays a FIFO") {
  const scratch_folder folder("files");
  const fs::path fifo = folder.path / "frame.png";
  REQUIRE(::mkfifo(fifo.c_str(), 0666) == 0);
  std::string received;
  std::thread reader([&] {
    std::ifstream in(fifo, std::ios::binary);
    received.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  });
  const std::string bytes(200000, 'p');  // more than a pipe's buffer: the writer waits for the reader
  try {
    write_all_or_nothing({text_file(fifo, bytes), text_file(folder.path / "frame-indirect.pfm", "pfm")});
  } catch (...) {
    // The reader still waits for a writer: open the FIFO once it is there, so that it sees the end.
    for (int attempt = 0; attempt < 1000; ++attempt) {
      const int writer = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC);
      if (writer >= 0) {
        ::close(writer);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    reader.join();
    throw;
  }
  reader.join();
  CHECK(received == bytes);
  CHECK(kind_of(fifo).type == S_IFIFO);
  CHECK(contents(folder.path / "frame-indirect.pfm") == "pfm");
}

TEST_CASE("links: to a regular file, that file is replaced and the link stays; a dangling link and a socket are refused by name") {
  const scratch_folder folder("files");
  fs::create_directories(folder.path / "real");
  const fs::path target = folder.path / "real" / "out.glsl", link = folder.path / "out.glsl";
  std::ofstream(target) << "old";
  fs::create_symlink(target, link);
  write_bytes_atomically(link, {'n', 'e', 'w'});
  CHECK(fs::is_symlink(link));
  CHECK(fs::read_symlink(link) == target);
  CHECK(contents(target) == "new");
  CHECK(output_target_of(link).path == fs::canonical(target));
  CHECK(names_in(folder.path / "real") == std::vector<std::string>{"out.glsl"});  // the temporary was made next to the target
  // A dangling link: refused (as cp refuses), and no file appears where it points.
  const fs::path dangling = folder.path / "dangling.png";
  fs::create_symlink(folder.path / "nowhere" / "x.png", dangling);
  CHECK_THROWS_WITH_AS(write_bytes_atomically(dangling, {1}), doctest::Contains("dangling.png: it is a link to"), vplkit::error);
  CHECK_THROWS_WITH_AS(write_bytes_atomically(dangling, {1}), doctest::Contains("which does not exist"), vplkit::error);
  CHECK(fs::is_symlink(dangling));
  CHECK_FALSE(fs::exists(folder.path / "nowhere"));
  // A socket cannot be opened as a file: refused, left in place.
  const fs::path socket_path = folder.path / "s.png";
  const int listener = ::socket(AF_UNIX, SOCK_STREAM, 0);
  REQUIRE(listener >= 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  REQUIRE(socket_path.string().size() < sizeof address.sun_path);
  std::strcpy(address.sun_path, socket_path.c_str());
  REQUIRE(::bind(listener, reinterpret_cast<const sockaddr*>(&address), sizeof address) == 0);
  CHECK_THROWS_WITH_AS(write_bytes_atomically(socket_path, {1}), doctest::Contains("s.png: it is a socket, not a file"), vplkit::error);
  CHECK(kind_of(socket_path).type == S_IFSOCK);
  ::close(listener);
}

TEST_CASE("descriptor_output: the bytes in order, and a lost write's errno (ENOSPC, EBADF)") {
  int ends[2];
  REQUIRE(::pipe(ends) == 0);
  {
    // The pipe holds 64 KiB, less than is written: read while it is written.
    std::string received;
    std::thread reader([&] {
      char chunk[4096];
      for (ssize_t got; (got = ::read(ends[0], chunk, sizeof chunk)) > 0;) received.append(chunk, static_cast<std::size_t>(got));
    });
    descriptor_output buffer(ends[1]);
    std::ostream out(&buffer);
    out << "first " << 42 << '\n' << std::string(100000, 'x');
    out.flush();
    CHECK(out.good());
    CHECK(buffer.failure() == 0);
    ::close(ends[1]);
    reader.join();
    CHECK(received == "first 42\n" + std::string(100000, 'x'));
  }
  ::close(ends[0]);
  // A descriptor not open for writing (a pipe's read end): EBADF, and the stream goes bad.
  REQUIRE(::pipe(ends) == 0);
  {
    descriptor_output buffer(ends[0]);
    std::ostream out(&buffer);
    out << "lost\n";
    out.flush();
    CHECK_FALSE(out.good());
    CHECK(buffer.failure() == EBADF);
  }
  ::close(ends[0]);
  ::close(ends[1]);
  const scratch_folder folder("files");
  std::string why;
  if (!make_char_device(folder.path / "full", 7, why)) {
    MESSAGE("skipped the ENOSPC case: mknod is not permitted here (" << why << ")");
    return;
  }
  const int full = ::open((folder.path / "full").c_str(), O_WRONLY | O_CLOEXEC);
  REQUIRE(full >= 0);
  {
    descriptor_output buffer(full);
    std::ostream out(&buffer);
    out << std::string(200000, 'y');  // past the 64 KiB block: the failure is seen before the flush
    CHECK(buffer.failure() == ENOSPC);
    out << "more";
    out.flush();
    CHECK_FALSE(out.good());
    CHECK(buffer.failure() == ENOSPC);
  }
  ::close(full);
}

TEST_CASE("two outputs with one path are found among 100,000 by sorting, not by comparing every pair, before anything is encoded") {
  // A --poses sequence of 50,000 frames has 100,000 outputs; the check compared every pair (5 * 10^9
  // comparisons of normalised paths, hours). The repeat is the very last output, spelt differently
  // ("./"), and names the later of the two.
  scratch_folder scratch("files");
  std::vector<output_file> files;
  std::atomic<int> encoded{0};
  for (int i = 0; i < 100000; ++i)
    files.push_back({scratch.path / ("frame-" + std::to_string(i) + ".pfm"), [&encoded] {
                       ++encoded;
                       return std::vector<std::uint8_t>{};
                     }});
  files.back().path = scratch.path / "." / "frame-77777.pfm";
  const auto start = std::chrono::steady_clock::now();
  const std::string expected = "two outputs would be written to " + (scratch.path / "." / "frame-77777.pfm").string();
  CHECK_THROWS_WITH_AS(write_all_or_nothing(files), doctest::Contains(expected.c_str()), vplkit::error);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // About 0.1 s in Release and 1 s under the sanitizers on idle cores, 11 s under the sanitizers
  // with six such processes on two cores; pairwise (5 * 10^9 path comparisons) takes hours. So the
  // bound separates the two orders of growth whatever the machine's load, and times nothing finer.
  CHECK(seconds < 120.0);
  CHECK(encoded == 0);
  CHECK(names_in(scratch.path).empty());

  // Without the repeat, the same check lets the set through to the encoder.
  files.resize(3);
  files.push_back({scratch.path / "frame-last.pfm", [] { return std::vector<std::uint8_t>{'x'}; }});
  write_all_or_nothing(files);
  CHECK(encoded == 3);
  CHECK(contents(scratch.path / "frame-last.pfm") == "x");
}
