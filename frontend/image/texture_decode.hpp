// Texture images of users' scenes (glTF base-colour textures, OBJ/MTL map_Kd): PNG through
// vplkit's one PNG decoder (frontend/image/png.hpp, libspng) and JPEG through libjpeg-turbo's
// TurboJPEG API, decoded to 8-bit RGBA exactly as the file stores it (colour still sRGB-encoded,
// alpha linear, rows top-down, the first row the image's top). The size a file claims is read
// from its header and checked against texture_limits before a pixel buffer is allocated or the
// decoder runs. Errors name the texture (`name`, e.g. "scene.gltf: image 2 'wood.png'") and what
// is wrong. The format is told by the bytes' signature, never by a file name: a JPEG named .png
// decodes as JPEG, a GIF is refused.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace vplkit {

/// What one texture file may claim before anything is allocated for it.
struct texture_limits {
  int max_side = 16384;                           ///< GL_MAX_TEXTURE_SIZE of most GPUs
  std::size_t max_pixels = std::size_t{1} << 26;  ///< 64 Mi pixels: 256 MiB of RGBA8, 341 MiB with mipmaps
  /// All of one scene's decoded textures with their mip chains together (texture_budget,
  /// frontend/scene/material.hpp): 1 GiB, checked from each header before it is decoded.
  std::uint64_t max_scene_bytes = std::uint64_t{1} << 30;
};

/// The width and height a PNG's IHDR or a JPEG's frame header claims, read without decoding.
struct texture_size {
  std::uint64_t width = 0;
  std::uint64_t height = 0;
};

/// A decoded texture: 8-bit RGBA, RGB as stored (sRGB-encoded), alpha linear, rows top-down.
struct texture_pixels {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba8;
};

enum class texture_file_format { png, jpeg, unknown };

/// The format the bytes' signature names (PNG: 89 50 4E 47 0D 0A 1A 0A; JPEG: FF D8 FF).
texture_file_format texture_format_of(std::string_view bytes);

/// The size the header of a PNG or JPEG claims, without decoding the pixels; {0, 0} when there is
/// no readable header (decode_texture then says what is wrong).
texture_size claimed_texture_size(std::string_view bytes);

/// Decodes a PNG or a JPEG, chosen by the signature. Throws vplkit::error starting with `name`
/// for another format, a size over the limits, or a file the decoder refuses.
texture_pixels decode_texture(std::string_view bytes, const std::string& name, const texture_limits& limits = {});

/// PNG through decode_png_rgba8 (any bit depth and colour type; tRNS applied; gAMA and iCCP not
/// applied: glTF textures are sRGB by definition), with texture_limits as its size limits.
texture_pixels decode_png_texture(std::string_view bytes, const std::string& name, const texture_limits& limits = {});

/// JPEG through TurboJPEG (baseline and progressive, greyscale or YCbCr; CMYK is refused). The
/// header's size is checked before decoding; progressive scans are limited (TJFLAG_LIMITSCANS)
/// and a warning such as truncated data is an error (TJFLAG_STOPONWARNING).
texture_pixels decode_jpeg_texture(std::string_view bytes, const std::string& name, const texture_limits& limits = {});

}  // namespace vplkit
