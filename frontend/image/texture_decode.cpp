#include "frontend/image/texture_decode.hpp"

#include <spng.h>
#include <turbojpeg.h>

#include <limits>
#include <memory>

#include "frontend/core/error.hpp"

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

texture_pixels decode_texture(std::string_view bytes, const std::string& name, const texture_limits& limits) {
  switch (texture_format_of(bytes)) {
    case texture_file_format::png: return decode_png_texture(bytes, name, limits);
    case texture_file_format::jpeg: return decode_jpeg_texture(bytes, name, limits);
    case texture_file_format::unknown: break;
  }
  throw error(name + ": not a PNG or JPEG image (the first bytes carry neither signature; vplkit reads textures in these two formats)");
}

texture_pixels decode_png_texture(std::string_view bytes, const std::string& name, const texture_limits& limits) {
  if (!starts_with_bytes(bytes, png_signature, sizeof png_signature)) throw error(name + ": not a PNG image (no PNG signature)");
  // The size IHDR claims (it must be the first chunk), checked here so that the message says it;
  // libspng's own image limits below are the same.
  if (bytes.size() >= 24 && bytes.substr(12, 4) == "IHDR") {
    const auto big_endian = [&](std::size_t at) {
      std::uint64_t value = 0;
      for (std::size_t i = 0; i < 4; ++i) value = (value << 8) | static_cast<unsigned char>(bytes[at + i]);
      return value;
    };
    check_claimed_size(big_endian(16), big_endian(20), name, "PNG", limits);
  }
  const std::unique_ptr<spng_ctx, void (*)(spng_ctx*)> context(spng_ctx_new(0), spng_ctx_free);
  if (!context) throw error(name + ": libspng could not create a decoder");
  const auto check = [&](int code, const char* step) {
    if (code != 0) throw error(name + ": PNG " + step + ": " + spng_strerror(code));
  };
  const auto side_limit = static_cast<std::uint32_t>(limits.max_side);
  check(spng_set_image_limits(context.get(), side_limit, side_limit), "limits");
  // A chunk can be no longer than the file; ancillary chunks (text, ICC profiles) are not used and
  // get 1 MiB between them.
  check(spng_set_chunk_limits(context.get(), bytes.size(), std::size_t{1} << 20), "limits");
  check(spng_set_png_buffer(context.get(), bytes.data(), bytes.size()), "buffer");
  spng_ihdr header{};
  check(spng_get_ihdr(context.get(), &header), "header");
  check_claimed_size(header.width, header.height, name, "PNG", limits);
  std::size_t size = 0;
  check(spng_decoded_image_size(context.get(), SPNG_FMT_RGBA8, &size), "size");
  texture_pixels out;
  out.width = static_cast<int>(header.width);
  out.height = static_cast<int>(header.height);
  if (size != static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height) * 4) throw error(name + ": PNG: unexpected decoded size");
  out.rgba8.resize(size);
  check(spng_decode_image(context.get(), out.rgba8.data(), size, SPNG_FMT_RGBA8, SPNG_DECODE_TRNS), "data");
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
