// Helpers shared by the files of the GL test executable (vplkit_gl_tests): one definition each,
// because its files are compiled together in unity batches (tests/CMakeLists.txt), where two
// files' helpers of one name would clash or, differing only in their arguments, one file would
// silently call the other's.
#pragma once

#include <doctest/doctest.h>

#include <cstddef>
#include <filesystem>
#include <functional>
#include <random>
#include <string>
#include <system_error>

#include "frontend/core/error.hpp"
#include "frontend/image/image.hpp"

namespace vplkit::testing {

// A folder of its own under the system's temporary folder, removed with what it holds when the
// test case ends: vplkit-<name>-<random number>.
struct scratch_folder {
  std::filesystem::path path;
  explicit scratch_folder(const std::string& name)
      : path(std::filesystem::temp_directory_path() / ("vplkit-" + name + "-" + std::to_string(std::random_device{}()))) {
    std::filesystem::create_directories(path);
  }
  scratch_folder(const scratch_folder&) = delete;
  scratch_folder& operator=(const scratch_folder&) = delete;
  ~scratch_folder() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

// The message of the vplkit::error the action throws; "(no error)" when it throws nothing.
inline std::string message_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const vplkit::error& failure) {
    return failure.what();
  }
  return "(no error)";
}

// How many texels of two images of one size differ (exactly, in any channel).
inline std::size_t different_texels(const image& a, const image& b) {
  REQUIRE(a.width == b.width);
  REQUIRE(a.height == b.height);
  std::size_t different = 0;
  for (std::size_t i = 0; i < a.texels.size(); ++i) different += a.texels[i] != b.texels[i];
  return different;
}

// The checkout's root (VPLKIT_TEST_SOURCE_DIR is its tests/ folder).
inline std::filesystem::path source_dir() { return std::filesystem::path(VPLKIT_TEST_SOURCE_DIR).parent_path(); }

}  // namespace vplkit::testing
