// Image files: PNG (8-bit sRGB, the display images; frontend/image/png.hpp over libspng) and PFM
// (linear RGB floats, the images that are measured), encoded to bytes and decoded from bytes with
// every claim of a file checked before anything is allocated for it. Every encoder refuses a
// non-finite pixel: vplkit writes finite images only. Writing whole files is core/files' job (output_file,
// write_all_or_nothing); write_png is the single-file shortcut.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "frontend/image/image.hpp"

namespace vplkit {

/// RGBA8 rows top-down (to_srgb8's output) encoded as a PNG file's bytes (libspng, with an sRGB
/// chunk). Throws vplkit::error when the size does not match the pixels.
std::vector<std::uint8_t> encode_png(int width, int height, const std::vector<std::uint8_t>& rgba8);

/// Writes an RGBA8 PNG whole or not at all. Throws vplkit::error naming the path.
void write_png(const std::filesystem::path& path, int width, int height, const std::vector<std::uint8_t>& rgba8);

/// PFM (portable float map, RGB, little-endian, rows bottom-up like vplkit::image): the file's
/// bytes; alpha is dropped. Throws vplkit::error naming the first non-finite pixel.
std::vector<std::uint8_t> encode_pfm(const image& linear);

/// Throws vplkit::error naming the first pixel (from the top left) whose RGB is NaN or infinite.
void require_finite_pixels(const image& linear);

enum class image_file_format { pfm, png };

/// Decodes a PFM (RGB, little-endian, exactly width x height x 12 bytes of finite floats after
/// the header) or a PNG (decode_png_rgba8's checks; sRGB converted to linear) into an image with
/// alpha 1. Throws vplkit::error starting with `name` and saying what is wrong
/// (header, size over the limits, truncated or trailing data, the first non-finite pixel).
image decode_image(const std::string& bytes, image_file_format format, const std::string& name, const image_read_limits& limits = {});

/// Reads a .pfm or a .png file (the extension picks the format) with decode_image. Throws
/// vplkit::error naming the file.
image read_image_file(const std::filesystem::path& path, const image_read_limits& limits = {});

}  // namespace vplkit
