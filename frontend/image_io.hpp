// Image output. Files are written whole or not at all: the bytes go to a temporary file next to
// the target, which is renamed over it only after a successful write, so a failure never leaves
// a partial image behind.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "frontend/files.hpp"

namespace vplkit {

/// Linear float RGBA (rows bottom-up, as GL reads them) to 8-bit sRGB RGBA, rows top-down,
/// alpha forced opaque. Values are scaled by `exposure` and clamped to [0, 1] before encoding.
std::vector<std::uint8_t> to_srgb8(const std::vector<float>& linear_rgba, int width, int height, float exposure = 1.0f);

/// RGBA8 rows top-down encoded as a PNG file's bytes. Throws vplkit::error when the size does not
/// match the pixels.
std::vector<std::uint8_t> encode_png(int width, int height, const std::vector<std::uint8_t>& rgba8);

/// Writes an RGBA8 PNG. Throws vplkit::error naming the path when it cannot be written; the
/// parent folder must exist or be creatable.
void write_png(const std::filesystem::path& path, int width, int height, const std::vector<std::uint8_t>& rgba8);

}  // namespace vplkit
