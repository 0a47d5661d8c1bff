// The files a command writes: one place for output naming (a default under output/, siblings
// such as <out>-indirect.png next to the main file), extension checks, and all-or-nothing
// writing (core/files: every file is encoded and written to a temporary first, then, under a lock
// on the folder, the previous files are moved aside and the new ones renamed in; a failure puts
// the previous set back). Every image is checked for finite pixels before it is written.
#pragma once

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "frontend/core/files.hpp"
#include "frontend/gl/pass_timer.hpp"
#include "frontend/image/image.hpp"

namespace vplkit::cli {

class output_set {
 public:
  /// The main file: `given` (the value of `option`, e.g. --out) or, when empty, `default_path`.
  /// Throws usage_error when its extension is not `extension` (".png" or ".pfm"); `what_else`
  /// says in that message which files go next to it.
  output_set(const std::string& given, const std::string& default_path, const std::string& extension, const std::string& option,
             const std::string& what_else = {});
  const std::filesystem::path& main() const { return main_; }
  /// main() with `suffix` added to its stem and the extension replaced: ("-indirect", ".pfm").
  std::filesystem::path sibling(const std::string& suffix, const std::string& extension) const;

  /// An 8-bit sRGB PNG of exposure * `linear`. Throws vplkit::error naming the path and the first
  /// non-finite pixel, if any.
  void add_png(const std::filesystem::path& path, const image& linear, float exposure = 1.0f);
  /// An RGBA8 PNG, rows top-down (e.g. false_colour_error).
  void add_png(const std::filesystem::path& path, int width, int height, std::vector<std::uint8_t> rgba8);
  /// A linear PFM (write() refuses a non-finite pixel, naming it and the path).
  void add_pfm(const std::filesystem::path& path, image linear);
  /// Text as it is (e.g. a glTF scene).
  void add_text(const std::filesystem::path& path, std::string text);

  /// Writes every file added, all or nothing, and prints "wrote <absolute path>" for each.
  void write(std::ostream& out) const;

 private:
  std::filesystem::path main_;
  std::vector<output_file> files_;
};

/// A frame's time per light (render --stats): the pipelines name a pass drawn for one light
/// "... light K ..." ("RSM light 1 face 3"), K its index in the scene's lights. Passes naming no
/// light (the G-buffer, the post filter) are shared by all lights.
struct light_time {
  std::size_t light = 0;
  std::size_t passes = 0;
  double milliseconds = 0.0;
};
struct light_times {
  std::vector<light_time> lights;  ///< by light index, only the lights some pass names
  std::size_t shared_passes = 0;
  double shared_milliseconds = 0.0;
};
/// The passes grouped by the light their name names: the word "light" followed by a number, as
/// whole words ("spotlight 2" and "light 2b" name none).
light_times group_by_light(const std::vector<pass_time>& passes);
/// "| light | passes | ms | % |" rows per light and one for the shared passes, the % of the
/// frame's total; "" when no pass names a light (a one-light pipeline's table says it all).
std::string format_light_table(const light_times& times);
/// The same as JSON: [{"light": K, "passes": n, "ms": t}, ...], "shared_ms": t.
std::string light_times_json(const light_times& times);

}  // namespace vplkit::cli
