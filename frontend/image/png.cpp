#include "frontend/image/png.hpp"

#include <spng.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>

#include "frontend/core/error.hpp"

namespace vplkit {

namespace {

struct context_deleter {
  void operator()(spng_ctx* context) const { spng_ctx_free(context); }
};
using spng_context = std::unique_ptr<spng_ctx, context_deleter>;

std::uint32_t big_endian(std::string_view bytes, std::size_t at) {
  const auto byte = [&](std::size_t k) { return static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[at + k])); };
  return (byte(0) << 24) | (byte(1) << 16) | (byte(2) << 8) | byte(3);
}

// The bytes the image data inflates to: every row of every (Adam7) pass with its filter byte.
std::uint64_t raw_image_bytes(std::uint32_t width, std::uint32_t height, unsigned bits_per_pixel, bool interlaced) {
  const auto rows_of = [&](std::uint64_t w, std::uint64_t h) { return w == 0 || h == 0 ? 0 : h * (1 + (w * bits_per_pixel + 7) / 8); };
  if (!interlaced) return rows_of(width, height);
  static constexpr int passes[7][4] = {{0, 0, 8, 8}, {4, 0, 8, 8}, {0, 4, 4, 8}, {2, 0, 4, 4}, {0, 2, 2, 4}, {1, 0, 2, 2}, {0, 1, 1, 2}};
  std::uint64_t total = 0;
  for (const auto& pass : passes) {
    const auto extent = [](std::uint64_t size, int start, int step) -> std::uint64_t {
      return size > static_cast<std::uint64_t>(start) ? (size - static_cast<std::uint64_t>(start) + static_cast<std::uint64_t>(step) - 1) / static_cast<std::uint64_t>(step) : 0;
    };
    total += rows_of(extent(width, pass[0], pass[2]), extent(height, pass[1], pass[3]));
  }
  return total;
}

unsigned channels_of(unsigned colour_type) {
  switch (colour_type) {
    case 0: return 1;  // grey
    case 2: return 3;  // RGB
    case 3: return 1;  // palette index
    case 4: return 2;  // grey + alpha
    default: return 4; // RGBA (and anything invalid: spng refuses it)
  }
}

}  // namespace

rgba8_image decode_png_rgba8(std::string_view bytes, const std::string& name, const image_read_limits& limits) {
  static constexpr unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (bytes.size() < sizeof signature || std::memcmp(bytes.data(), signature, sizeof signature) != 0)
    throw error(name + ": not a PNG file (no PNG signature)");
  // The size from the IHDR chunk, which must come first, checked before anything is allocated.
  if (bytes.size() < 33 || bytes.substr(12, 4) != "IHDR") throw error(name + ": not a readable PNG (no IHDR chunk after the signature)");
  const std::uint32_t claimed_width = big_endian(bytes, 16), claimed_height = big_endian(bytes, 20);
  if (claimed_width == 0 || claimed_height == 0 || claimed_width > 0x7fffffffu || claimed_height > 0x7fffffffu)
    throw error(name + ": not a readable PNG (its header claims " + std::to_string(claimed_width) + "x" + std::to_string(claimed_height) + " pixels)");
  if (claimed_width > static_cast<std::uint32_t>(limits.max_side) || claimed_height > static_cast<std::uint32_t>(limits.max_side) ||
      static_cast<std::uint64_t>(claimed_width) * claimed_height > limits.max_pixels)
    throw error(name + ": the image claims " + std::to_string(claimed_width) + "x" + std::to_string(claimed_height) +
                " pixels, more than vplkit reads (sides up to " + std::to_string(limits.max_side) + ", " + std::to_string(limits.max_pixels) +
                " pixels in all)");
  const unsigned bit_depth = static_cast<unsigned char>(bytes[24]), colour_type = static_cast<unsigned char>(bytes[25]);
  const bool interlaced = bytes[28] != 0;
  // Every chunk up to IEND inside the file, and the image data no larger than any encoder makes it.
  std::uint64_t image_data = 0;
  for (std::size_t at = 8;;) {
    if (bytes.size() - at < 12) throw error(name + ": not a readable PNG (it ends inside the chunk at byte " + std::to_string(at) + ", before IEND)");
    const std::uint32_t chunk_length = big_endian(bytes, at);
    const std::string_view type = bytes.substr(at + 4, 4);
    if (chunk_length > bytes.size() - at - 12)
      throw error(name + ": not a readable PNG (its chunk at byte " + std::to_string(at) + " claims " + std::to_string(chunk_length) +
                  " bytes of data; the file has " + std::to_string(bytes.size() - at - 12) + " after its header)");
    if (type == "IDAT") image_data += chunk_length;
    at += 12 + std::size_t{chunk_length};
    if (type == "IEND") break;
  }
  const std::uint64_t raw = raw_image_bytes(claimed_width, claimed_height, channels_of(colour_type) * std::max(bit_depth, 1u), interlaced);
  const std::uint64_t most = raw + raw / 4 + 4096;
  if (image_data > most)
    throw error(name + ": not a readable PNG (its compressed image data is " + std::to_string(image_data) + " bytes, more than a " +
                std::to_string(claimed_width) + "x" + std::to_string(claimed_height) + " image can need: " + std::to_string(raw) +
                " bytes uncompressed; an inflate bomb?)");

  const spng_context context(spng_ctx_new(0));
  if (!context) throw error(name + ": out of memory for the PNG decoder");
  spng_ctx* png = context.get();
  const auto check = [&](int code) {
    if (code != 0) throw error(name + ": not a readable PNG (" + spng_strerror(code) + ")");
  };
  check(spng_set_image_limits(png, static_cast<std::uint32_t>(limits.max_side), static_cast<std::uint32_t>(limits.max_side)));
  check(spng_set_chunk_limits(png, limits.max_chunk_bytes, limits.max_chunk_cache_bytes));
  check(spng_set_png_buffer(png, bytes.data(), bytes.size()));
  spng_ihdr header{};
  check(spng_get_ihdr(png, &header));
  rgba8_image out;
  out.width = static_cast<int>(header.width);
  out.height = static_cast<int>(header.height);
  const std::size_t pixel_count = static_cast<std::size_t>(header.width) * header.height;
  out.pixels.resize(pixel_count * 4);
  if (header.color_type == SPNG_COLOR_TYPE_INDEXED) {
    // The indices as the file has them, each checked against the palette, then looked up here.
    spng_plte palette{};
    check(spng_get_plte(png, &palette));
    spng_trns transparency{};
    const bool has_alpha = spng_get_trns(png, &transparency) == 0;
    std::size_t length = 0;
    check(spng_decoded_image_size(png, SPNG_FMT_PNG, &length));
    std::vector<std::uint8_t> packed(length);
    check(spng_decode_image(png, packed.data(), packed.size(), SPNG_FMT_PNG, 0));
    const std::size_t row_bytes = length / header.height;
    const unsigned depth = header.bit_depth;
    for (std::uint32_t y = 0; y < header.height; ++y)
      for (std::uint32_t x = 0; x < header.width; ++x) {
        const std::size_t bit = static_cast<std::size_t>(x) * depth;
        const unsigned byte = packed[y * row_bytes + bit / 8];
        const unsigned index = (byte >> (8 - depth - bit % 8)) & ((1u << depth) - 1u);
        if (index >= palette.n_entries)
          throw error(name + ": not a readable PNG (pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") uses palette entry " +
                      std::to_string(index) + ", but the palette has " + std::to_string(palette.n_entries) + ")");
        std::uint8_t* to = &out.pixels[(static_cast<std::size_t>(y) * header.width + x) * 4];
        to[0] = palette.entries[index].red;
        to[1] = palette.entries[index].green;
        to[2] = palette.entries[index].blue;
        to[3] = has_alpha && index < transparency.n_type3_entries ? transparency.type3_alpha[index] : 255;
      }
  } else {
    check(spng_decode_image(png, out.pixels.data(), out.pixels.size(), SPNG_FMT_RGBA8, SPNG_DECODE_TRNS));
  }
  std::uint8_t intent = 0;
  std::uint32_t gamma = 0;
  if (spng_get_srgb(png, &intent) != 0 && spng_get_gama_int(png, &gamma) == 0 && gamma == 100000) out.srgb = false;
  return out;
}

std::vector<std::uint8_t> encode_png_rgba8(int width, int height, const std::vector<std::uint8_t>& rgba8) {
  if (width < 1 || height < 1 || rgba8.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4)
    throw error("PNG encoding: a " + std::to_string(width) + "x" + std::to_string(height) + " image needs " +
                std::to_string(static_cast<std::size_t>(std::max(width, 0)) * static_cast<std::size_t>(std::max(height, 0)) * 4) +
                " bytes of RGBA8, got " + std::to_string(rgba8.size()));
  const spng_context context(spng_ctx_new(SPNG_CTX_ENCODER));
  if (!context) throw error("PNG encoding: out of memory for the encoder");
  spng_ctx* png = context.get();
  const auto check = [](int code) {
    if (code != 0) throw error(std::string("PNG encoding failed (") + spng_strerror(code) + ")");
  };
  check(spng_set_option(png, SPNG_ENCODE_TO_BUFFER, 1));
  spng_ihdr header{};
  header.width = static_cast<std::uint32_t>(width);
  header.height = static_cast<std::uint32_t>(height);
  header.bit_depth = 8;
  header.color_type = SPNG_COLOR_TYPE_TRUECOLOR_ALPHA;
  check(spng_set_ihdr(png, &header));
  check(spng_set_srgb(png, 0));  // perceptual intent: the bytes are sRGB
  check(spng_encode_image(png, rgba8.data(), rgba8.size(), SPNG_FMT_PNG, SPNG_ENCODE_FINALIZE));
  std::size_t length = 0;
  int code = 0;
  void* buffer = spng_get_png_buffer(png, &length, &code);
  if (!buffer) check(code != 0 ? code : SPNG_EINTERNAL);
  const std::unique_ptr<void, void (*)(void*)> owned(buffer, std::free);
  const auto* begin = static_cast<const std::uint8_t*>(buffer);
  return std::vector<std::uint8_t>(begin, begin + length);
}

}  // namespace vplkit
