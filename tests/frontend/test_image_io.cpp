// Image output: the sRGB encoding and the all-or-nothing file write (frontend/image_io.hpp).
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "frontend/error.hpp"
#include "frontend/image_io.hpp"

namespace fs = std::filesystem;
using namespace vplkit;

TEST_CASE("to_srgb8 follows the sRGB transfer curve and flips rows to top-down") {
  // 1 x 2 image, bottom row first as GL reads it.
  const std::vector<float> linear = {0.0f, 0.5f, 1.0f, 1.0f,     // bottom
                                     0.0031308f, 2.0f, -1.0f, 0.0f};  // top
  const std::vector<std::uint8_t> encoded = to_srgb8(linear, 1, 2);
  const auto srgb = [](double v) { return static_cast<int>(std::lround(255.0 * (1.055 * std::pow(v, 1.0 / 2.4) - 0.055))); };
  // Top row first now.
  CHECK(encoded[0] == std::lround(255.0 * 12.92 * 0.0031308));
  CHECK(encoded[1] == 255);  // clamped
  CHECK(encoded[2] == 0);    // clamped
  CHECK(encoded[3] == 255);  // opaque
  CHECK(encoded[4] == 0);
  CHECK(encoded[5] == srgb(0.5));
  CHECK(encoded[6] == 255);
}

TEST_CASE("write_png writes a PNG, and on failure leaves no file behind") {
  const fs::path folder = fs::temp_directory_path() / ("vplkit-png-" + std::to_string(std::random_device{}()));
  const std::vector<std::uint8_t> pixels(4 * 3 * 2, 128);
  const fs::path good = folder / "nested" / "image.png";
  write_png(good, 3, 2, pixels);
  std::ifstream in(good, std::ios::binary);
  char magic[8] = {};
  in.read(magic, 8);
  CHECK(std::string(magic + 1, 3) == "PNG");
  // Nothing but the image in the folder: the temporary file was renamed.
  CHECK(std::distance(fs::directory_iterator(good.parent_path()), fs::directory_iterator()) == 1);

  // A file where a folder should be: the write must fail, name the path, and create nothing.
  const fs::path blocked = folder / "nested" / "image.png" / "inside.png";
  try {
    write_png(blocked, 3, 2, pixels);
    FAIL("no error for an unwritable path");
  } catch (const vplkit::error& failure) {
    CHECK(std::string(failure.what()).find(blocked.string()) != std::string::npos);
  }
  CHECK(std::distance(fs::directory_iterator(good.parent_path()), fs::directory_iterator()) == 1);
  CHECK_THROWS_AS(write_png(folder / "wrong-size.png", 3, 3, pixels), vplkit::error);
  CHECK(!fs::exists(folder / "wrong-size.png"));
  fs::remove_all(folder);
}
