#include "frontend/cli/output.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "frontend/cli/options.hpp"
#include "frontend/core/error.hpp"
#include "frontend/core/setting.hpp"
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

namespace {

// The light index a pass name names ("RSM light 2 face 0": 2), or -1. "light" must be a word of
// its own followed by a space and digits ending the word, so that "spotlight 2", "light 2b" and
// "lighting 3" name no light.
long named_light(const std::string& name) {
  const auto word_edge = [&name](std::size_t at) { return at >= name.size() || !std::isalnum(static_cast<unsigned char>(name[at])); };
  for (std::size_t at = name.find("light"); at != std::string::npos; at = name.find("light", at + 1)) {
    if (at > 0 && !word_edge(at - 1)) continue;
    std::size_t digits = at + 6;
    if (at + 5 >= name.size() || name[at + 5] != ' ') continue;
    std::size_t end = digits;
    while (end < name.size() && end - digits < 6 && std::isdigit(static_cast<unsigned char>(name[end]))) ++end;
    if (end == digits || !word_edge(end)) continue;
    return std::stol(name.substr(digits, end - digits));
  }
  return -1;
}

// As render's pass_json writes a time: the shortest text reading back the same double, null if not finite.
std::string json_ms(double value) { return std::isfinite(value) ? format_real(value) : "null"; }

}  // namespace

light_times group_by_light(const std::vector<pass_time>& passes) {
  light_times times;
  for (const pass_time& pass : passes) {
    const long light = named_light(pass.pass);
    if (light < 0) {
      ++times.shared_passes;
      times.shared_milliseconds += pass.milliseconds;
      continue;
    }
    const std::size_t index = static_cast<std::size_t>(light);
    auto found = std::find_if(times.lights.begin(), times.lights.end(), [index](const light_time& entry) { return entry.light == index; });
    if (found == times.lights.end()) found = times.lights.insert(times.lights.end(), light_time{index, 0, 0.0});
    ++found->passes;
    found->milliseconds += pass.milliseconds;
  }
  std::sort(times.lights.begin(), times.lights.end(), [](const light_time& a, const light_time& b) { return a.light < b.light; });
  return times;
}

std::string format_light_table(const light_times& times) {
  if (times.lights.empty()) return "";
  double total = times.shared_milliseconds;
  for (const light_time& entry : times.lights) total += entry.milliseconds;
  const auto share = [total](double ms) { return total > 0.0 ? 100.0 * ms / total : 0.0; };
  std::string table = "time per light (the passes naming it; shared: the passes naming none):\n| light | passes | ms | % |\n|---|---:|---:|---:|\n";
  char row[128];
  for (const light_time& entry : times.lights) {
    std::snprintf(row, sizeof row, "| %zu | %zu | %.2f | %.1f |\n", entry.light, entry.passes, entry.milliseconds, share(entry.milliseconds));
    table += row;
  }
  std::snprintf(row, sizeof row, "| shared | %zu | %.2f | %.1f |\n", times.shared_passes, times.shared_milliseconds, share(times.shared_milliseconds));
  return table + row;
}

std::string light_times_json(const light_times& times) {
  std::string json = "[";
  for (const light_time& entry : times.lights)
    json += std::string(json.size() > 1 ? ", " : "") + "{\"light\": " + std::to_string(entry.light) + ", \"passes\": " + std::to_string(entry.passes) +
            ", \"ms\": " + json_ms(entry.milliseconds) + "}";
  return json + "], \"shared_ms\": " + json_ms(times.shared_milliseconds);
}

}  // namespace vplkit::cli
