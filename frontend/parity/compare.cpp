// vplkit::parity's comparison (vplkit/parity/parity.hpp): GPU against CPU outputs texel by
// texel within a tolerance, and the report that names the texels out of it with their inputs.
#include <vplkit/parity/parity.hpp>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iomanip>
#include <sstream>

#include "frontend/core/error.hpp"
#include "frontend/parity/internal.hpp"

namespace vplkit::parity {
using detail::check_grid;

std::int64_t ulp_distance(float a, float b) {
  auto ordered = [](float value) {
    std::int32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    // Map the sign-magnitude float order onto two's-complement order (-0 and +0 both to 0).
    return bits < 0 ? static_cast<std::int64_t>(std::int32_t{INT32_MIN}) - bits : static_cast<std::int64_t>(bits);
  };
  return std::llabs(ordered(a) - ordered(b));
}

namespace {

std::string describe_inputs(const kernel_inputs& inputs, std::size_t index) {
  std::ostringstream out;
  out << std::setprecision(9);
  for (std::size_t i = 0; i < inputs.floats.size(); ++i) {
    const glm::vec4& v = inputs.floats[i][index];
    out << " fin" << i << "=(" << v.x << ", " << v.y << ", " << v.z << ", " << v.w << ")";
  }
  for (std::size_t i = 0; i < inputs.uints.size(); ++i) {
    const glm::uvec4& v = inputs.uints[i][index];
    out << " uin" << i << "=(" << v.x << ", " << v.y << ", " << v.z << ", " << v.w << ")";
  }
  return out.str();
}

std::string texel_name(const kernel_inputs& inputs, std::size_t index, int channel) {
  const char* channels = "xyzw";
  return "texel (" + std::to_string(index % static_cast<std::size_t>(inputs.width)) + ", " +
         std::to_string(index / static_cast<std::size_t>(inputs.width)) + ")." + channels[channel];
}

std::string number_text(double value) {
  std::ostringstream text;
  text << std::setprecision(9) << value;
  return text.str();
}

// What every comparison needs before it counts anything. Each misuse here made compare() pass,
// or read out of bounds, rather than fail: a NaN, negative or above-1 allowed fraction (cast to a
// huge or arbitrary count of allowed mismatches), 0 or negative channels (nothing compared), 5 or
// more channels (past w), an empty grid, outputs or inputs shorter than the grid.
void check_comparison(const std::string& kernel, std::size_t gpu, std::size_t cpu, const kernel_inputs& inputs, int channels,
                      double allowed_mismatch_fraction) {
  const std::string what = "parity compare " + kernel + ": ";
  if (channels < 1 || channels > 4)
    throw error(what + "channels is " + std::to_string(channels) + "; it must be 1 to 4 (x, xy, xyz or xyzw)");
  if (!(allowed_mismatch_fraction >= 0.0 && allowed_mismatch_fraction <= 1.0))
    throw error(what + "allowed_mismatch_fraction is " + number_text(allowed_mismatch_fraction) + "; it must be in [0, 1]");
  check_grid(what, inputs);
  if (gpu != inputs.size() || cpu != inputs.size())
    throw error(what + "the outputs have gpu " + std::to_string(gpu) + " and cpu " + std::to_string(cpu) + " values for a " +
                std::to_string(inputs.width) + "x" + std::to_string(inputs.height) + " grid (" + std::to_string(inputs.size()) + " texels)");
}

// A tolerance that is NaN, infinite or negative passes everything, nothing, or depends on the
// comparison's direction; it is refused with the field that holds it.
void check_tolerance(const std::string& kernel, const tolerance& bounds, const kernel_inputs& inputs) {
  const std::string what = "parity compare " + kernel + ": the tolerance's ";
  const std::string rule = "; bounds must be finite and non-negative";
  if (!(std::isfinite(bounds.max_abs) && bounds.max_abs >= 0.0f)) throw error(what + "max_abs is " + number_text(bounds.max_abs) + rule);
  if (!(std::isfinite(bounds.max_rel) && bounds.max_rel >= 0.0f)) throw error(what + "max_rel is " + number_text(bounds.max_rel) + rule);
  if (bounds.max_ulp < 0) throw error(what + "max_ulp is " + std::to_string(bounds.max_ulp) + rule);
  if (bounds.abs_scale.empty()) return;
  if (bounds.abs_scale.size() != inputs.size())
    throw error(what + "abs_scale has " + std::to_string(bounds.abs_scale.size()) + " values for " + std::to_string(inputs.size()) + " texels");
  for (std::size_t index = 0; index < bounds.abs_scale.size(); ++index)
    for (int c = 0; c < 4; ++c)
      if (const float scale = bounds.abs_scale[index][c]; !(std::isfinite(scale) && scale >= 0.0f))
        throw error(what + "abs_scale of " + texel_name(inputs, index, c) + " is " + number_text(scale) + rule);
}

std::size_t allowed(std::size_t values, double fraction) {
  return static_cast<std::size_t>(std::floor(fraction * static_cast<double>(values)));
}

}  // namespace

comparison compare(const std::string& kernel, const std::vector<glm::vec4>& gpu, const std::vector<glm::vec4>& cpu,
                   const kernel_inputs& inputs, const tolerance& bounds, int channels) {
  check_comparison(kernel, gpu.size(), cpu.size(), inputs, channels, bounds.allowed_mismatch_fraction);
  check_tolerance(kernel, bounds, inputs);
  comparison result;
  result.kernel = kernel;
  result.bounds = bounds;
  const bool scaled = !bounds.abs_scale.empty();
  double worst_score = -1.0;
  std::size_t listed = 0;
  std::ostringstream list;
  list << std::setprecision(9);
  for (std::size_t index = 0; index < gpu.size(); ++index) {
    for (int c = 0; c < channels; ++c) {
      const float g = gpu[index][c], r = cpu[index][c];
      ++result.values;
      const bool finite = std::isfinite(g) && std::isfinite(r);
      const double abs_error = finite ? std::fabs(static_cast<double>(g) - static_cast<double>(r)) : INFINITY;
      const double magnitude = std::max(std::fabs(static_cast<double>(g)), std::fabs(static_cast<double>(r)));
      const double rel_error = finite ? (magnitude > 0.0 ? abs_error / magnitude : 0.0) : INFINITY;
      const std::int64_t ulps = finite ? ulp_distance(g, r) : INT64_MAX;
      const double abs_bound = static_cast<double>(bounds.max_abs) * (scaled ? static_cast<double>(bounds.abs_scale[index][c]) : 1.0);
      if (finite) {
        result.max_abs = std::max(result.max_abs, abs_error);
        result.max_rel = std::max(result.max_rel, rel_error);
        result.max_ulp = std::max(result.max_ulp, ulps);
        if (abs_bound > 0.0) result.max_abs_over_bound = std::max(result.max_abs_over_bound, abs_error / abs_bound);
      }
      const bool within = finite && (abs_error <= abs_bound || rel_error <= bounds.max_rel || ulps <= bounds.max_ulp);
      // The worst texel: non-finite first, then by the error measure relative to its bound.
      const double score = !finite ? INFINITY
                                   : std::min({abs_bound > 0 ? abs_error / abs_bound : abs_error * 1e30,
                                               bounds.max_rel > 0 ? rel_error / bounds.max_rel : rel_error * 1e30,
                                               bounds.max_ulp > 0 ? static_cast<double>(ulps) / static_cast<double>(bounds.max_ulp)
                                                                  : static_cast<double>(ulps) * 1e30});
      const auto detail = [&] {
        std::ostringstream text;
        text << std::setprecision(9) << texel_name(inputs, index, c) << ": gpu=" << g << " cpu=" << r << " (abs " << abs_error;
        if (scaled) text << " of " << abs_bound << " allowed";
        text << ", rel " << rel_error << ", ulp " << ulps << ");" << describe_inputs(inputs, index);
        return text.str();
      };
      if (score > worst_score) {
        worst_score = score;
        result.worst = detail();
      }
      if (!within) {
        ++result.mismatches;
        if (listed++ < 8) list << "\n    " << detail();
      }
    }
  }
  result.allowed_mismatches = allowed(result.values, bounds.allowed_mismatch_fraction);
  result.mismatch_list = list.str();
  return result;
}

comparison compare_exact(const std::string& kernel, const std::vector<glm::uvec4>& gpu, const std::vector<glm::uvec4>& cpu,
                         const kernel_inputs& inputs, double allowed_mismatch_fraction, int channels) {
  check_comparison(kernel, gpu.size(), cpu.size(), inputs, channels, allowed_mismatch_fraction);
  comparison result;
  result.kernel = kernel;
  result.bounds = {0.0f, 0.0f, 0, allowed_mismatch_fraction, "integers: exact"};
  std::size_t listed = 0;
  std::ostringstream list;
  for (std::size_t index = 0; index < gpu.size(); ++index) {
    for (int c = 0; c < channels; ++c) {
      ++result.values;
      if (gpu[index][c] == cpu[index][c]) continue;
      ++result.mismatches;
      const std::string detail = texel_name(inputs, index, c) + ": gpu=" + std::to_string(gpu[index][c]) +
                                 " cpu=" + std::to_string(cpu[index][c]) + ";" + describe_inputs(inputs, index);
      if (result.worst.empty()) result.worst = detail;
      if (listed++ < 8) list << "\n    " << detail;
    }
  }
  result.allowed_mismatches = allowed(result.values, allowed_mismatch_fraction);
  result.mismatch_list = list.str();
  return result;
}

std::string comparison::summary() const {
  std::ostringstream out;
  out << std::setprecision(3) << "parity " << kernel << ": " << values << " values, " << mismatches
      << " outside tolerance (allowed " << allowed_mismatches << "), max abs " << max_abs << ", max rel " << max_rel
      << ", max ulp " << max_ulp;
  if (!bounds.abs_scale.empty()) out << ", max abs / its bound " << max_abs_over_bound;
  out << "\n  worst " << worst;
  if (!passed())
    out << "\n  tolerance: abs <= " << bounds.max_abs << (bounds.abs_scale.empty() ? "" : " x the texel's abs_scale") << " or rel <= "
        << bounds.max_rel << " or ulp <= " << bounds.max_ulp << ", allowed fraction " << bounds.allowed_mismatch_fraction
        << (bounds.reason.empty() ? "" : " (" + bounds.reason + ")");
  return out.str();
}

}  // namespace vplkit::parity
