// Texture decoding (frontend/image/texture_decode.hpp): PNG through libspng and JPEG through
// TurboJPEG give the stored colours, the format is told by the signature, and sizes over the
// limits, truncated data and other formats are refused with the texture's name.
#include <doctest/doctest.h>

#include <turbojpeg.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "frontend/core/error.hpp"
#include "frontend/image/image_files.hpp"
#include "frontend/image/texture_decode.hpp"

using namespace vplkit;

namespace {

// A w x h RGBA8 image: red in the left half, blue in the right, alpha 200.
std::vector<std::uint8_t> red_blue_halves(int w, int h) {
  std::vector<std::uint8_t> rgba(static_cast<std::size_t>(w * h * 4));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = &rgba[static_cast<std::size_t>((y * w + x) * 4)];
      const bool left = x < w / 2;
      p[0] = left ? 220 : 20, p[1] = 20, p[2] = left ? 20 : 220, p[3] = 200;
    }
  return rgba;
}

std::string as_bytes(const std::vector<std::uint8_t>& data) { return std::string(data.begin(), data.end()); }

std::string jpeg_of(int w, int h, const std::vector<std::uint8_t>& rgba) {
  tjhandle encoder = tjInitCompress();
  REQUIRE(encoder != nullptr);
  unsigned char* out = nullptr;
  unsigned long size = 0;
  REQUIRE(tjCompress2(encoder, rgba.data(), w, 0, h, TJPF_RGBA, &out, &size, TJSAMP_444, 95, 0) == 0);
  std::string bytes(reinterpret_cast<const char*>(out), size);
  tjFree(out);
  tjDestroy(encoder);
  return bytes;
}

std::string decode_error(const std::string& bytes, const texture_limits& limits = {}) {
  try {
    decode_texture(bytes, "scene.gltf: image 3 'floor'", limits);
  } catch (const error& failure) {
    return failure.what();
  }
  return "";
}

}  // namespace

TEST_CASE("texture decoding: a PNG gives its stored RGBA8, rows top-down") {
  const std::vector<std::uint8_t> rgba = red_blue_halves(8, 4);
  const std::string png = as_bytes(encode_png(8, 4, rgba));
  CHECK(texture_format_of(png) == texture_file_format::png);
  const texture_pixels decoded = decode_texture(png, "halves.png");
  CHECK(decoded.width == 8);
  CHECK(decoded.height == 4);
  CHECK(decoded.rgba8 == rgba);
}

TEST_CASE("texture decoding: a JPEG gives its colours within the codec's error, opaque") {
  const std::vector<std::uint8_t> rgba = red_blue_halves(32, 16);
  const std::string jpeg = jpeg_of(32, 16, rgba);
  CHECK(texture_format_of(jpeg) == texture_file_format::jpeg);
  const texture_pixels decoded = decode_texture(jpeg, "halves.jpg");
  REQUIRE(decoded.rgba8.size() == rgba.size());
  // Away from the edge between the halves (8x8 blocks, quality 95): within 12 codes.
  for (int y = 0; y < 16; ++y)
    for (const int x : {2, 5, 26, 29}) {
      const std::size_t i = static_cast<std::size_t>((y * 32 + x) * 4);
      CAPTURE(x);
      for (int c = 0; c < 3; ++c) CHECK(std::abs(int{decoded.rgba8[i + static_cast<std::size_t>(c)]} - int{rgba[i + static_cast<std::size_t>(c)]}) <= 12);
      CHECK(decoded.rgba8[i + 3] == 255);
    }
}

TEST_CASE("texture decoding: sizes over the limits, truncated data and other formats are refused, naming the texture") {
  const std::string png = as_bytes(encode_png(64, 32, red_blue_halves(64, 32)));
  texture_limits small;
  small.max_side = 32;
  const std::string side = decode_error(png, small);
  CHECK(side.find("scene.gltf: image 3 'floor'") == 0);
  CHECK(side.find("64x32") != std::string::npos);
  small.max_side = 64;
  small.max_pixels = 1000;
  CHECK(decode_error(png, small).find("1000 pixels in all") != std::string::npos);  // png.cpp's message
  const std::string jpeg = jpeg_of(64, 32, red_blue_halves(64, 32));
  CHECK(decode_error(jpeg, small).find("JPEG claims 64x32") != std::string::npos);
  // Truncated: the header is read, the data is not all there.
  CHECK(decode_error(png.substr(0, png.size() / 2)).find("scene.gltf: image 3 'floor': not a readable PNG") == 0);
  CHECK(decode_error(jpeg.substr(0, jpeg.size() / 2)).find("scene.gltf: image 3 'floor': JPEG") == 0);
  CHECK(decode_error("GIF89a....").find("not a PNG or JPEG") != std::string::npos);
  CHECK(decode_error("").find("not a PNG or JPEG") != std::string::npos);
}
