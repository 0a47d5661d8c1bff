// Image files (frontend/image/image_files.hpp): PNG and PFM encoded and decoded with the rows in
// the order each format stores them, the all-or-nothing write, and errors naming the file.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "frontend/core/error.hpp"
#include "frontend/core/files.hpp"
#include "frontend/image/image_files.hpp"
#include "frontend/image/metrics.hpp"

namespace fs = std::filesystem;
using namespace vplkit;

namespace {

// A horizontal ramp whose rows differ too (green grows upwards), so a flipped row order shows.
image gradient(int width, int height, float offset = 0.0f) {
  image ramp(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float v = 0.1f + 0.8f * static_cast<float>(x) / static_cast<float>(width - 1);
      ramp.at(x, y) = glm::vec4(v + offset, 0.1f + 0.8f * static_cast<float>(y) / static_cast<float>(height - 1) + offset, 0.25f + offset, 1.0f);
    }
  return ramp;
}

}  // namespace

TEST_CASE("PFM stores rows bottom-up like vplkit::image; PNG stores them top-down") {
  image two_rows(1, 2);
  two_rows.at(0, 0) = glm::vec4(1.0f, 2.0f, 3.0f, 1.0f);  // bottom
  two_rows.at(0, 1) = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);  // top
  const std::vector<std::uint8_t> pfm = encode_pfm(two_rows);
  const std::string header = "PF\n1 2\n-1.0\n";
  REQUIRE(pfm.size() == header.size() + 2 * 12);
  float first[3];
  std::memcpy(first, pfm.data() + header.size(), sizeof first);
  CHECK(first[0] == 1.0f);  // the file's first row is the bottom row
  CHECK(first[2] == 3.0f);
  const std::vector<std::uint8_t> srgb = to_srgb8(two_rows);
  CHECK(srgb[0] == 0);    // the PNG raster's first row is the top row
  CHECK(srgb[4] == 255);  // then the bottom one
  const std::vector<std::uint8_t> png = encode_png(1, 2, srgb);
  const image decoded = decode_image(std::string(png.begin(), png.end()), image_file_format::png, "rows.png");
  CHECK(decoded.at(0, 0).r == 1.0f);  // back at the bottom
  CHECK(decoded.at(0, 1).r == 0.0f);
}

TEST_CASE("PFM round trip, PNG reading, false colour, and errors naming the file") {
  const fs::path folder = fs::temp_directory_path() / ("vplkit-metrics-" + std::to_string(std::random_device{}()));
  const image a = gradient(17, 9);
  fs::create_directories(folder);
  write_bytes_atomically(folder / "a.pfm", encode_pfm(a));
  const image back = read_image_file(folder / "a.pfm");
  REQUIRE(back.width == 17);
  REQUIRE(back.height == 9);
  CHECK(back.texels == a.texels);
  // A PNG of the same image reads back within 8-bit sRGB quantisation, rows in place.
  write_png(folder / "a.png", 17, 9, to_srgb8(a));
  CHECK(compare_images(read_image_file(folder / "a.png"), a).rmse < 0.005);
  const std::vector<std::uint8_t> colours = false_colour_error(gradient(17, 9, 0.1f), a, 0.1f);
  CHECK(colours[0] == 255);  // the full scale is red
  CHECK(colours[1] == 0);
  CHECK(false_colour_error(a, a, 1.0f)[2] == 255);  // no difference: blue
  // Errors.
  CHECK_THROWS_WITH_AS(read_image_file(folder / "none.pfm"), doctest::Contains("none.pfm: no such PFM image"), vplkit::error);
  std::ofstream(folder / "bad.pfm") << "P6\n1 1\n255\n";
  CHECK_THROWS_WITH_AS(read_image_file(folder / "bad.pfm"), doctest::Contains("not an RGB PFM file"), vplkit::error);
  std::ofstream(folder / "short.pfm") << "PF\n4 4\n-1.0\n1234";
  CHECK_THROWS_WITH_AS(read_image_file(folder / "short.pfm"), doctest::Contains("ends before its 4x4 pixels"), vplkit::error);
  std::ofstream(folder / "text.png") << "not a png";
  CHECK_THROWS_WITH_AS(read_image_file(folder / "text.png"), doctest::Contains("text.png: not a PNG file (no PNG signature)"), vplkit::error);
  // A PNG signature with a broken body reaches the PNG decoder (libspng), and only that one.
  std::ofstream(folder / "broken.png", std::ios::binary) << "\x89PNG\r\n\x1a\nbroken";
  CHECK_THROWS_WITH_AS(read_image_file(folder / "broken.png"), doctest::Contains("broken.png: not a readable PNG"), vplkit::error);
  CHECK_THROWS_WITH_AS(read_image_file(folder / "a.jpg"), doctest::Contains("unsupported image format '.jpg'"), vplkit::error);
  std::ofstream(folder / "a.exr") << "x";
  CHECK_THROWS_WITH_AS(read_image_file(folder / "a.exr"), doctest::Contains("unsupported image format '.exr'"), vplkit::error);
  CHECK_THROWS_WITH_AS(compare_images(gradient(4, 4), gradient(5, 4)), doctest::Contains("different sizes (4x4 and 5x4)"), vplkit::error);
  fs::remove_all(folder);
}

TEST_CASE("PFM decoding: exact size, finite pixels, header limits checked before allocating") {
  const auto pfm = [](const std::string& header, std::vector<float> values, const std::string& tail = "") {
    std::string bytes = header;
    bytes.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(float));
    return bytes + tail;
  };
  const image ok = decode_image(pfm("PF\n2 1\n-1.0\n", {1, 2, 3, 4, 5, 6}), image_file_format::pfm, "ok.pfm");
  CHECK(ok.at(1, 0) == glm::vec4(4, 5, 6, 1));
  CHECK_THROWS_WITH_AS(decode_image(pfm("PF\n1 1\n-1.0\n", {1, 2, 3}, "xy"), image_file_format::pfm, "t.pfm"),
                       "t.pfm: 2 bytes follow the 1x1 pixels of the PFM file", vplkit::error);
  CHECK_THROWS_WITH_AS(decode_image(pfm("PF\n1 2\n-1.0\n", {1, 2, 3, 4, 5, std::nanf("")}), image_file_format::pfm, "t.pfm"),
                       "t.pfm: pixel (0, 0) (from the top left) is NaN; vplkit compares finite images", vplkit::error);
  CHECK_THROWS_WITH_AS(decode_image(pfm("PF\n20000 20000\n-1.0\n", {0, 0, 0}), image_file_format::pfm, "t.pfm"),
                       doctest::Contains("t.pfm: the image claims 20000x20000 pixels, more than vplkit reads"), vplkit::error);
  image_read_limits tiny;
  tiny.max_pixels = 1;
  CHECK_THROWS_WITH_AS(decode_image(pfm("PF\n2 1\n-1.0\n", {1, 2, 3, 4, 5, 6}), image_file_format::pfm, "t.pfm", tiny),
                       doctest::Contains("the image claims 2x1 pixels"), vplkit::error);
  CHECK_THROWS_WITH_AS(decode_image(pfm("PF\n1 1\n1.0\n", {1, 2, 3}), image_file_format::pfm, "t.pfm"), doctest::Contains("big-endian"), vplkit::error);
  CHECK_THROWS_WITH_AS(decode_image(pfm("PF\n1 1\nnan\n", {1, 2, 3}), image_file_format::pfm, "t.pfm"), doctest::Contains("scale 'nan'"), vplkit::error);
  CHECK_THROWS_WITH_AS(decode_image(pfm("Pf\n1 1\n-1\n", {1}), image_file_format::pfm, "t.pfm"), doctest::Contains("greyscale"), vplkit::error);
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

TEST_CASE("PNG decoding: every chunk's length is checked against the file before the decoder allocates") {
  const std::vector<std::uint8_t> encoded = encode_png(3, 2, std::vector<std::uint8_t>(3 * 2 * 4, 200));
  const std::string png(encoded.begin(), encoded.end());
  CHECK(decode_image(png, image_file_format::png, "ok.png").width == 3);
  CHECK(decode_image(png + "trailing bytes", image_file_format::png, "ok.png").width == 3);  // after IEND: ignored
  // The first chunk after IHDR (at byte 33) claiming 2^31 - 1 bytes: stb_image grew its IDAT
  // buffer to that length before finding the data missing; no decoder is given the chance.
  std::string hostile = png;
  for (int i = 0; i < 4; ++i) hostile[33 + static_cast<std::size_t>(i)] = static_cast<char>(i == 0 ? 0x7f : 0xff);
  CHECK_THROWS_WITH_AS(decode_image(hostile, image_file_format::png, "t.png"),
                       doctest::Contains("t.png: not a readable PNG (its chunk at byte 33 claims 2147483647 bytes of data"), vplkit::error);
  CHECK_THROWS_WITH_AS(decode_image(png.substr(0, png.size() - 12), image_file_format::png, "t.png"),
                       doctest::Contains("t.png: not a readable PNG (it ends inside the chunk at byte"), vplkit::error);
}
