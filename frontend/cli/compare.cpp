// vplkit compare: the metrics of an image against a reference (PFM linear or PNG sRGB), over all
// pixels and over a mask, and a false-colour error image. Given the reference's per-pixel variance
// (--reference-variance) or a second, independent reference (--second-reference, another seed),
// also what the reference's own noise does to the relative errors (frontend/image/reference_noise.hpp).
#include <cmath>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>

#include "frontend/cli/commands.hpp"
#include "frontend/cli/output.hpp"
#include "frontend/core/error.hpp"
#include "frontend/core/files.hpp"
#include "frontend/image/image_files.hpp"
#include "frontend/image/metrics.hpp"
#include "frontend/image/reference_noise.hpp"

namespace vplkit::cli {

namespace {

namespace fs = std::filesystem;

struct compare_state {
  std::string image, reference, mask, error_image, variance, second;
  float error_scale = 0.0f;
};

std::string size_of(const image& i) { return std::to_string(i.width) + "x" + std::to_string(i.height); }

// A relative number as the table shows it: the number, or "undefined" and why (a black reference
// has no level to be relative to; 0 there would read as a perfect match).
std::string relative_cell(const relative_error& error, double value) {
  if (!error.defined) return "undefined: " + error.why_undefined;
  std::ostringstream text;
  text << std::setprecision(6) << value;
  return text.str();
}

// The share of the reference's lit pixels (luminance > 0; within the mask when one is given) where
// the image's luminance is below half the reference's: the missing light that a mean hides (shadow
// acne, a seam, a light leak's opposite). The direct-light target is <= 1 %.
struct darker_than_half {
  std::size_t lit = 0;
  std::size_t darker = 0;
};

darker_than_half darker_than_half_of(const image& candidate, const image& reference, const image* mask) {
  darker_than_half count;
  for (std::size_t i = 0; i < reference.texels.size(); ++i) {
    if (mask && !(luminance(glm::dvec3(mask->texels[i])) > 0.5)) continue;
    const double expected = luminance(glm::dvec3(reference.texels[i]));
    if (!(expected > 0.0)) continue;
    ++count.lit;
    if (luminance(glm::dvec3(candidate.texels[i])) < 0.5 * expected) ++count.darker;
  }
  return count;
}

int run_compare(const session& io, const compare_state& s) {
  std::optional<output_set> files;
  if (!s.error_image.empty()) {
    files.emplace(s.error_image, "", ".png", "--error-image");
    for (const std::string& input : {s.image, s.reference, s.mask, s.variance, s.second})
      if (!input.empty() && same_file(s.error_image, input)) throw usage_error("--error-image " + s.error_image + " is the input " + input + "; name a new file");
  }
  if (!s.variance.empty() && !s.second.empty()) throw usage_error("--reference-variance and --second-reference both give the reference's noise: give one");
  if (io.dry_run) return 0;
  const image candidate = read_image_file(s.image);
  const image reference = read_image_file(s.reference);
  std::optional<image> mask;
  if (!s.mask.empty()) mask = read_image_file(s.mask);
  if (!candidate.same_size(reference))
    throw error("the image " + s.image + " is " + size_of(candidate) + " but the reference " + s.reference + " is " + size_of(reference));
  if (mask && !mask->same_size(reference))
    throw error("the mask " + s.mask + " is " + size_of(*mask) + " but the reference " + s.reference + " is " + size_of(reference));
  const image_metrics m = compare_images(candidate, reference, mask ? &*mask : nullptr);
  if (files) files->add_png(files->main(), candidate.width, candidate.height, false_colour_error(candidate, reference, s.error_scale));
  io.out << std::setprecision(6) << "| metric | value |\n|---|---:|\n| RMSE | " << m.rmse << " |\n| relative MSE | " << m.relative_mse << " |\n| PSNR (dB) | ";
  if (m.psnr_defined) io.out << m.psnr;
  else io.out << "undefined: " << m.why_psnr_undefined;
  io.out << " |\n| SSIM (luminance) | " << m.ssim << " |\n| similarity (Alg. 1, %) | " << m.similarity << " |\n";
  io.out << "| relative RMSE (RMSE / reference mean) | " << relative_cell(m.relative, m.relative.rmse)
         << " |\n| relative bias ((mean - reference mean) / reference mean) | " << relative_cell(m.relative, m.relative.bias) << " |\n";
  const darker_than_half darker = darker_than_half_of(candidate, reference, mask ? &*mask : nullptr);
  io.out << "| lit pixels darker than half the reference (%" << (mask ? ", in the mask" : "") << ") | ";
  if (darker.lit == 0) io.out << "undefined: the reference has no lit pixel" << (mask ? " in the mask" : "");
  else io.out << 100.0 * static_cast<double>(darker.darker) / static_cast<double>(darker.lit) << " (" << darker.darker << " of " << darker.lit << ")";
  io.out << " |\n";
  if (m.leak_rmse) io.out << "| masked RMSE (" << m.leak_pixels << " pixels, e.g. a leak region) | " << *m.leak_rmse << " |\n";
  if (m.masked)
    io.out << "| masked relative RMSE (" << m.masked->pixels << " pixels) | " << relative_cell(*m.masked, m.masked->rmse) << " |\n| masked relative bias | "
           << relative_cell(*m.masked, m.masked->bias) << " |\n";
  if (!s.variance.empty() || !s.second.empty()) {
    const std::string& given = s.variance.empty() ? s.second : s.variance;
    const image other = read_image_file(given);
    if (!other.same_size(reference)) throw error("the " + std::string(s.variance.empty() ? "second reference " : "variance ") + given + " is " + size_of(other) +
                                                 " but the reference " + s.reference + " is " + size_of(reference));
    const image variance = s.variance.empty() ? variance_of_two(reference, other) : other;
    const reference_noise noise = reference_noise_of(candidate, reference, variance, mask ? &*mask : nullptr);
    if (!noise.defined) {
      io.out << "| the reference's noise | undefined: " << noise.why_undefined << " |\n";
    } else {
      io.out << "| the reference's noise (the relative RMSE of a perfect image) | " << noise.noise << " |\n| relative RMSE, the reference's noise taken out | "
             << noise.rmse_corrected << " |\n| relative RMSE's standard error from the reference | " << noise.rmse_se
             << " |\n| relative bias's standard error from the reference | " << noise.bias_se << " |\n| the reference's noise / relative RMSE (%) | "
             << 100.0 * noise.share << " |\n";
      if (!s.second.empty()) {
        // Similarity and SSIM against the two references: their spread is the estimate of
        // those measures' standard error (one degree of freedom).
        const image_metrics again = compare_images(candidate, other, mask ? &*mask : nullptr);
        io.out << "| SSIM's standard error from the reference | " << std::fabs(m.ssim - again.ssim) / std::sqrt(2.0)
               << " |\n| similarity's standard error from the reference | " << std::fabs(m.similarity - again.similarity) / std::sqrt(2.0) << " |\n";
      }
      if (noise.share > 0.1)
        std::cerr << "compare: warning: the reference's own noise is " << std::setprecision(3) << 100.0 * noise.share
                  << " % of the relative RMSE (more than 10 %): the error is partly the reference's; raise --reference-samples of `vplkit reference` "
                     "(4x the samples halves the noise), and read the noise-corrected relative RMSE\n";
    }
  }
  if (files) files->write(io.out);
  return 0;
}

}  // namespace

command add_compare_command(CLI::App& app) {
  auto state = std::make_shared<compare_state>();
  CLI::App* compare = app.add_subcommand("compare", "compare an image with a reference (.pfm linear or .png sRGB)");
  compare->add_option("image", state->image, "the image to judge")->required();
  compare->add_option("reference", state->reference, "the reference")->required();
  compare->add_option("--mask", state->mask, "pixels (luminance > 0.5) for the light-leak error and the masked relative errors, e.g. the "
                                             "-receivers.pfm of vplkit reference --method rsm-brute-force");
  compare->add_option("--reference-variance", state->variance,
                      "the reference's per-pixel variance (.pfm, per channel): report the reference's noise, the noise-corrected relative RMSE and "
                      "the standard errors");
  compare->add_option("--second-reference", state->second,
                      "a second reference of the same image, independent of the first (e.g. vplkit reference --reference-seed 2): its difference "
                      "to the first gives the variance, as --reference-variance");
  compare->add_option("--error-image", state->error_image, "write the false-colour error image (.png)");
  compare->add_option("--error-scale", state->error_scale, "luminance difference shown as full red (0: the largest)")
      ->check(number_in(0.0, std::numeric_limits<float>::max(), false, "linear luminance"))->capture_default_str();
  return {compare, [state](const session& io) { return run_compare(io, *state); }, restorer(state)};
}

}  // namespace vplkit::cli
