// The PNG codec (frontend/image/png.hpp over libspng): every colour type, bit depth and the Adam7
// interlacing decoded to the RGBA8 the pixels say, palette indices checked against the palette,
// inflate bombs refused before a byte is inflated, the sRGB/linear information, and the round
// trip of the encoder. The PNGs are built here byte by byte (zlib for their deflate streams), so
// that each case is exactly the file it describes.
#include <doctest/doctest.h>

#include <zlib.h>

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "frontend/core/error.hpp"
#include "frontend/image/png.hpp"

using namespace vplkit;

namespace {

void put32(std::string& out, std::uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8) out += static_cast<char>((value >> shift) & 0xff);
}

std::string chunk(const std::string& type, const std::string& data) {
  std::string out;
  put32(out, static_cast<std::uint32_t>(data.size()));
  out += type + data;
  const std::string crc_input = type + data;
  put32(out, static_cast<std::uint32_t>(crc32(0, reinterpret_cast<const Bytef*>(crc_input.data()), static_cast<uInt>(crc_input.size()))));
  return out;
}

std::string deflate(const std::string& raw) {
  uLongf size = compressBound(static_cast<uLong>(raw.size()));
  std::string out(size, '\0');
  REQUIRE(compress2(reinterpret_cast<Bytef*>(out.data()), &size, reinterpret_cast<const Bytef*>(raw.data()), static_cast<uLong>(raw.size()), 9) == Z_OK);
  out.resize(size);
  return out;
}

// A PNG with the given header fields, extra chunks before IDAT, and raw (filtered) image data.
std::string png(std::uint32_t width, std::uint32_t height, int bit_depth, int colour_type, const std::string& raw, const std::string& before_data = "",
                bool interlaced = false) {
  std::string header;
  put32(header, width);
  put32(header, height);
  header += static_cast<char>(bit_depth);
  header += static_cast<char>(colour_type);
  header += '\0';
  header += '\0';
  header += static_cast<char>(interlaced ? 1 : 0);
  return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", header) + before_data + chunk("IDAT", deflate(raw)) + chunk("IEND", "");
}

std::string bytes(std::initializer_list<int> values) {
  std::string out;
  for (int v : values) out += static_cast<char>(v);
  return out;
}

std::vector<std::uint8_t> rgba(std::initializer_list<int> values) {
  std::vector<std::uint8_t> out;
  for (int v : values) out.push_back(static_cast<std::uint8_t>(v));
  return out;
}

}  // namespace

TEST_CASE("PNG: grey, grey + alpha, RGB, RGBA, 16-bit and colour keys decode to the RGBA8 the pixels say") {
  // Each row starts with its filter byte (0: none).
  CHECK(decode_png_rgba8(png(2, 1, 8, 0, bytes({0, 10, 200})), "grey.png").pixels == rgba({10, 10, 10, 255, 200, 200, 200, 255}));
  CHECK(decode_png_rgba8(png(1, 1, 8, 4, bytes({0, 10, 77})), "grey-alpha.png").pixels == rgba({10, 10, 10, 77}));
  CHECK(decode_png_rgba8(png(1, 2, 8, 2, bytes({0, 1, 2, 3, 0, 4, 5, 6})), "rgb.png").pixels == rgba({1, 2, 3, 255, 4, 5, 6, 255}));
  CHECK(decode_png_rgba8(png(1, 1, 8, 6, bytes({0, 1, 2, 3, 4})), "rgba.png").pixels == rgba({1, 2, 3, 4}));
  // 16 bits: the high byte (big-endian in the file).
  CHECK(decode_png_rgba8(png(1, 1, 16, 2, bytes({0, 0x12, 0x34, 0x56, 0x78, 0x9a, 0xbc})), "rgb16.png").pixels == rgba({0x12, 0x56, 0x9a, 255}));
  // 1-bit grey: 0 and 1 are black and white.
  CHECK(decode_png_rgba8(png(3, 1, 1, 0, bytes({0, 0xa0})), "grey1.png").pixels == rgba({255, 255, 255, 255, 0, 0, 0, 255, 255, 255, 255, 255}));
  // A tRNS colour key makes that colour transparent.
  const std::string key = chunk("tRNS", bytes({0, 1, 0, 2, 0, 3}));
  CHECK(decode_png_rgba8(png(2, 1, 8, 2, bytes({0, 1, 2, 3, 1, 2, 4}), key), "key.png").pixels == rgba({1, 2, 3, 0, 1, 2, 4, 255}));
}

TEST_CASE("PNG: palettes of 1, 2, 4 and 8 bits with their alpha; an index beyond the palette is refused") {
  const std::string palette = chunk("PLTE", bytes({255, 0, 0, 0, 255, 0, 0, 0, 255}));
  const std::string alpha = chunk("tRNS", bytes({128}));  // entry 0 half transparent, the others opaque
  const std::vector<std::uint8_t> expected = rgba({0, 0, 255, 255, 255, 0, 0, 128, 0, 255, 0, 255});
  CHECK(decode_png_rgba8(png(3, 1, 8, 3, bytes({0, 2, 0, 1}), palette + alpha), "p8.png").pixels == expected);
  CHECK(decode_png_rgba8(png(3, 1, 4, 3, bytes({0, 0x20, 0x10}), palette + alpha), "p4.png").pixels == expected);
  CHECK(decode_png_rgba8(png(3, 1, 2, 3, bytes({0, 0x84}), palette + alpha), "p2.png").pixels == expected);
  const std::string two_colours = chunk("PLTE", bytes({255, 0, 0, 0, 255, 0}));  // a 1-bit image has at most 2
  CHECK(decode_png_rgba8(png(2, 1, 1, 3, bytes({0, 0x40}), two_colours), "p1.png").pixels == rgba({255, 0, 0, 255, 0, 255, 0, 255}));
  // Index 5 of a 3-entry palette: spng would read an entry the file never gave (stb read
  // uninitialised memory there, and compare gave a different RMSE on each run).
  CHECK_THROWS_WITH_AS(decode_png_rgba8(png(2, 1, 8, 3, bytes({0, 1, 5}), palette), "oob.png"),
                       "oob.png: not a readable PNG (pixel (1, 0) uses palette entry 5, but the palette has 3)", vplkit::error);
  CHECK_THROWS_WITH_AS(decode_png_rgba8(png(2, 1, 4, 3, bytes({0, 0x0f}), palette), "oob4.png"), doctest::Contains("palette entry 15"), vplkit::error);
  CHECK_THROWS_WITH_AS(decode_png_rgba8(png(1, 1, 8, 3, bytes({0, 0})), "none.png"), doctest::Contains("none.png: not a readable PNG"), vplkit::error);
}

TEST_CASE("PNG: an Adam7-interlaced image decodes to the same pixels as the plain one") {
  const int size = 9;
  const auto colour = [](int x, int y) { return bytes({x * 20, y * 20, (x * y) % 256}); };
  std::string plain;
  for (int y = 0; y < size; ++y) {
    plain += '\0';
    for (int x = 0; x < size; ++x) plain += colour(x, y);
  }
  std::string interlaced;
  static constexpr int passes[7][4] = {{0, 0, 8, 8}, {4, 0, 8, 8}, {0, 4, 4, 8}, {2, 0, 4, 4}, {0, 2, 2, 4}, {1, 0, 2, 2}, {0, 1, 1, 2}};
  for (const auto& pass : passes)
    for (int y = pass[1]; y < size; y += pass[3]) {
      if (pass[0] >= size) break;
      interlaced += '\0';
      for (int x = pass[0]; x < size; x += pass[2]) interlaced += colour(x, y);
    }
  const rgba8_image a = decode_png_rgba8(png(size, size, 8, 2, plain), "plain.png");
  const rgba8_image b = decode_png_rgba8(png(size, size, 8, 2, interlaced, "", true), "adam7.png");
  CHECK(a.pixels == b.pixels);
  CHECK(b.pixels[4 * (3 * size + 5) + 1] == 60);  // pixel (5, 3): green 3 x 20
}

TEST_CASE("PNG: an inflate bomb is refused before a byte is inflated") {
  // A 1x1 RGB image whose IDAT inflates to 64 MiB: 4 bytes are all the image can use.
  std::string raw = bytes({0, 16, 32, 48});
  raw.append(std::size_t{64} << 20, '\0');
  const std::string bomb = png(1, 1, 8, 2, raw);
  CHECK(bomb.size() < (std::size_t{1} << 20));
  const auto start = std::chrono::steady_clock::now();
  CHECK_THROWS_WITH_AS(decode_png_rgba8(bomb, "bomb.png"), doctest::Contains("bomb.png: not a readable PNG (its compressed image data is"), vplkit::error);
  CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(1));
  // The bound leaves room for any encoder: stored (uncompressed) blocks decode.
  std::string stored_raw;
  for (int y = 0; y < 64; ++y) stored_raw += '\0' + std::string(64 * 3, static_cast<char>(y));
  uLongf size = compressBound(static_cast<uLong>(stored_raw.size()));
  std::string stored(size, '\0');
  REQUIRE(compress2(reinterpret_cast<Bytef*>(stored.data()), &size, reinterpret_cast<const Bytef*>(stored_raw.data()), static_cast<uLong>(stored_raw.size()),
                    0) == Z_OK);  // level 0: stored blocks, larger than the raw data
  stored.resize(size);
  CHECK(stored.size() > stored_raw.size());
  std::string header;
  put32(header, 64);
  put32(header, 64);
  header += bytes({8, 2, 0, 0, 0});
  const std::string file = std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", header) + chunk("IDAT", stored) + chunk("IEND", "");
  CHECK(decode_png_rgba8(file, "stored.png").pixels[4 * 64 * 10] == 10);
}

TEST_CASE("PNG: the size in IHDR is checked against the limits before anything is allocated") {
  image_read_limits small;
  small.max_side = 64;
  small.max_pixels = 1024;
  CHECK_THROWS_WITH_AS(decode_png_rgba8(png(65, 1, 8, 0, "\0" + std::string(65, 'a')), "wide.png", small),
                       doctest::Contains("wide.png: the image claims 65x1 pixels, more than vplkit reads (sides up to 64, 1024 pixels in all)"),
                       vplkit::error);
  CHECK_THROWS_WITH_AS(decode_png_rgba8(png(40, 40, 1, 0, std::string(40 * 6, '\0')), "many.png", small), doctest::Contains("claims 40x40"),
                       vplkit::error);
  CHECK_THROWS_WITH_AS(decode_png_rgba8("GIF89a", "fake.png"), "fake.png: not a PNG file (no PNG signature)", vplkit::error);
}

TEST_CASE("PNG: sRGB information, and the encoder's round trip") {
  const std::vector<std::uint8_t> pixels = rgba({1, 2, 3, 255, 250, 128, 0, 255, 9, 9, 9, 255, 0, 0, 0, 255, 77, 66, 55, 255, 255, 255, 255, 255});
  const std::vector<std::uint8_t> encoded = encode_png_rgba8(3, 2, pixels);
  const rgba8_image back = decode_png_rgba8(std::string(encoded.begin(), encoded.end()), "round.png");
  CHECK(back.width == 3);
  CHECK(back.height == 2);
  CHECK(back.pixels == pixels);  // rows top-down in both
  CHECK(back.srgb);              // the encoder writes an sRGB chunk
  CHECK(decode_png_rgba8(png(1, 1, 8, 0, bytes({0, 9})), "plain.png").srgb);  // nothing said: sRGB
  std::string linear_gamma;
  put32(linear_gamma, 100000);
  CHECK_FALSE(decode_png_rgba8(png(1, 1, 8, 0, bytes({0, 9}), chunk("gAMA", linear_gamma)), "linear.png").srgb);
  std::string display_gamma;
  put32(display_gamma, 45455);
  CHECK(decode_png_rgba8(png(1, 1, 8, 0, bytes({0, 9}), chunk("gAMA", display_gamma)), "gamma.png").srgb);
  CHECK_THROWS_WITH_AS(encode_png_rgba8(3, 3, pixels), doctest::Contains("a 3x3 image needs 36 bytes of RGBA8, got 24"), vplkit::error);
}

TEST_CASE("PNG: ancillary chunks are bounded, decompressed text too") {
  // A zTXt chunk whose text inflates to 64 MiB, far beyond the chunk limits (4 MiB each, 16 MiB
  // in all): refused, not inflated.
  const std::string text = std::string("Comment") + '\0' + '\0' + deflate(std::string(std::size_t{64} << 20, 'x'));
  CHECK_THROWS_WITH_AS(decode_png_rgba8(png(1, 1, 8, 0, bytes({0, 9}), chunk("zTXt", text)), "ztxt.png"),
                       "ztxt.png: not a readable PNG (reached chunk/cache limits)", vplkit::error);
  // Within the limits the same kind of chunk is read and the image decodes.
  const std::string small_text = std::string("Comment") + '\0' + '\0' + deflate(std::string(1000, 'x'));
  CHECK(decode_png_rgba8(png(1, 1, 8, 0, bytes({0, 9}), chunk("zTXt", small_text)), "ztxt.png").pixels == rgba({9, 9, 9, 255}));
  // The limits are the caller's: a 1000-byte tEXt against 16 bytes.
  image_read_limits tight;
  tight.max_chunk_bytes = 16;
  tight.max_chunk_cache_bytes = 64;
  const std::string big_text = chunk("tEXt", std::string("Comment") + '\0' + std::string(1000, 'y'));
  CHECK(decode_png_rgba8(png(1, 1, 8, 0, bytes({0, 9}), big_text), "text.png").pixels == rgba({9, 9, 9, 255}));
  CHECK_THROWS_WITH_AS(decode_png_rgba8(png(1, 1, 8, 0, bytes({0, 9}), big_text), "text.png", tight), "text.png: not a readable PNG (reached chunk/cache limits)",
                       vplkit::error);
}
