#include "frontend/cli/output.hpp"

#include "frontend/cli/options.hpp"
#include "frontend/core/error.hpp"
#include "frontend/image/image_files.hpp"

namespace vplkit::cli {

namespace fs = std::filesystem;

output_set::output_set(const std::string& given, const std::string& default_path, const std::string& extension, const std::string& option,
                       const std::string& what_else)
    : main_(given.empty() ? default_path : given) {
  if (main_.extension() != extension)
    throw usage_error(option + " must name a " + extension + " file" + (what_else.empty() ? "" : " (" + what_else + ")") + ", got " +
                      shown(main_.string()));
}

fs::path output_set::sibling(const std::string& suffix, const std::string& extension) const {
  return main_.parent_path() / (main_.stem().string() + suffix + extension);
}

void output_set::add_png(const fs::path& path, const image& linear, float exposure) {
  // to_srgb8 would show a NaN as black: a non-finite pixel is refused here as in every writer.
  try {
    require_finite_pixels(linear);
  } catch (const error& failure) {
    throw error("cannot write " + excerpt_path(path.string()) + ": " + failure.what());
  }
  add_png(path, linear.width, linear.height, to_srgb8(linear, exposure));
}

void output_set::add_png(const fs::path& path, int width, int height, std::vector<std::uint8_t> rgba8) {
  files_.push_back({path, [width, height, pixels = std::move(rgba8)] { return encode_png(width, height, pixels); }});
}

void output_set::add_pfm(const fs::path& path, image linear) {
  files_.push_back({path, [pixels = std::move(linear)] { return encode_pfm(pixels); }});
}

void output_set::add_text(const fs::path& path, std::string text) {
  files_.push_back({path, [bytes = std::move(text)] { return std::vector<std::uint8_t>(bytes.begin(), bytes.end()); }});
}

void output_set::write(std::ostream& out) const {
  write_all_or_nothing(files_);
  for (const output_file& file : files_) out << "wrote " << fs::absolute(file.path).string() << "\n";
}

}  // namespace vplkit::cli
