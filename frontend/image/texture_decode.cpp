#include "frontend/image/texture_decode.hpp"

#include <turbojpeg.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <utility>

#include "frontend/core/error.hpp"
#include "frontend/image/png.hpp"

namespace vplkit {

namespace {

constexpr unsigned char png_signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

bool starts_with_bytes(std::string_view bytes, const unsigned char* prefix, std::size_t length) {
  if (bytes.size() < length) return false;
  for (std::size_t i = 0; i < length; ++i)
    if (static_cast<unsigned char>(bytes[i]) != prefix[i]) return false;
  return true;
}

// The size a header claims, against the limits: before anything is allocated for the pixels.
void check_claimed_size(std::uint64_t width, std::uint64_t height, const std::string& name, const char* format, const texture_limits& limits) {
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  if (width < 1 || height < 1) throw error(name + ": the " + std::string(format) + " claims an empty image (" + size + ")");
  if (width > static_cast<std::uint64_t>(limits.max_side) || height > static_cast<std::uint64_t>(limits.max_side))
    throw error(name + ": the " + std::string(format) + " claims " + size + " pixels; a texture side may be at most " + std::to_string(limits.max_side));
  if (width * height > limits.max_pixels)
    throw error(name + ": the " + std::string(format) + " claims " + size + " = " + std::to_string(width * height) + " pixels; a texture may have at most " +
                std::to_string(limits.max_pixels));
}

}  // namespace

texture_file_format texture_format_of(std::string_view bytes) {
  if (starts_with_bytes(bytes, png_signature, sizeof png_signature)) return texture_file_format::png;
  constexpr unsigned char jpeg_signature[3] = {0xff, 0xd8, 0xff};
  if (starts_with_bytes(bytes, jpeg_signature, sizeof jpeg_signature)) return texture_file_format::jpeg;
  return texture_file_format::unknown;
}

texture_size claimed_texture_size(std::string_view bytes) {
  switch (texture_format_of(bytes)) {
    case texture_file_format::png: {
      // The signature, IHDR's length (13) and type, then width and height, big-endian.
      if (bytes.size() < 24 || bytes.substr(12, 4) != "IHDR") return {};
      const auto be32 = [&](std::size_t at) {
        std::uint64_t value = 0;
        for (std::size_t k = 0; k < 4; ++k) value = value << 8 | static_cast<unsigned char>(bytes[at + k]);
        return value;
      };
      return {be32(16), be32(20)};
    }
    case texture_file_format::jpeg: {
      if (bytes.size() > std::numeric_limits<unsigned long>::max()) return {};
      const std::unique_ptr<void, int (*)(tjhandle)> decoder(tjInitDecompress(), tjDestroy);
      int width = 0, height = 0, subsampling = 0, colour_space = 0;
      if (!decoder || tjDecompressHeader3(decoder.get(), reinterpret_cast<const unsigned char*>(bytes.data()), static_cast<unsigned long>(bytes.size()), &width,
                                          &height, &subsampling, &colour_space) != 0)
        return {};
      return {static_cast<std::uint64_t>(std::max(width, 0)), static_cast<std::uint64_t>(std::max(height, 0))};
    }
    case texture_file_format::unknown: break;
  }
  return {};
}

texture_pixels decode_texture(std::string_view bytes, const std::string& name, const texture_limits& limits) {
  switch (texture_format_of(bytes)) {
    case texture_file_format::png: return decode_png_texture(bytes, name, limits);
    case texture_file_format::jpeg: return decode_jpeg_texture(bytes, name, limits);
    case texture_file_format::unknown: break;
  }
  throw error(name + ": not a PNG or JPEG image (the first bytes carry neither signature; vplkit reads textures in these two formats)");
}

texture_pixels decode_png_texture(std::string_view bytes, const std::string& name, const texture_limits& limits) {
  // vplkit's one PNG decoder (frontend/image/png.hpp): the size, every chunk, the compressed data
  // against the raw size (inflate bombs) and palette indices are checked there. Its sRGB/linear
  // flag is not used: a base-colour texture is sRGB by definition (glTF 2.0, 3.9.2).
  image_read_limits read_limits;
  read_limits.max_side = limits.max_side;
  read_limits.max_pixels = limits.max_pixels;
  rgba8_image decoded = decode_png_rgba8(bytes, name, read_limits);
  texture_pixels out;
  out.width = decoded.width;
  out.height = decoded.height;
  out.rgba8 = std::move(decoded.pixels);
  return out;
}

texture_pixels decode_jpeg_texture(std::string_view bytes, const std::string& name, const texture_limits& limits) {
  if (bytes.size() > std::numeric_limits<unsigned long>::max()) throw error(name + ": JPEG too large");
  const std::unique_ptr<void, int (*)(tjhandle)> decoder(tjInitDecompress(), tjDestroy);
  if (!decoder) throw error(name + ": TurboJPEG could not create a decoder");
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const auto length = static_cast<unsigned long>(bytes.size());
  int width = 0, height = 0, subsampling = 0, colour_space = 0;
  if (tjDecompressHeader3(decoder.get(), data, length, &width, &height, &subsampling, &colour_space) != 0)
    throw error(name + ": JPEG header: " + tjGetErrorStr2(decoder.get()));
  check_claimed_size(static_cast<std::uint64_t>(std::max(width, 0)), static_cast<std::uint64_t>(std::max(height, 0)), name, "JPEG", limits);
  if (colour_space == TJCS_CMYK || colour_space == TJCS_YCCK) throw error(name + ": a CMYK JPEG (vplkit reads greyscale and RGB/YCbCr JPEGs)");
  texture_pixels out;
  out.width = width;
  out.height = height;
  out.rgba8.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
  if (tjDecompress2(decoder.get(), data, length, out.rgba8.data(), width, 0, height, TJPF_RGBA, TJFLAG_LIMITSCANS | TJFLAG_STOPONWARNING) != 0)
    throw error(name + ": JPEG data: " + tjGetErrorStr2(decoder.get()));
  return out;
}

}  // namespace vplkit
