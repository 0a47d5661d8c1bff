// Fuzz target: the comparison metrics (frontend/image/metrics.hpp). The first byte picks the
// width (1..16) and whether a mask follows; the rest are the little-endian floats of the image,
// the reference and the mask, as far as they go. Any finite pixels, FLT_MAX included, must give
// finite metrics (PSNR is +inf exactly when the images are equal); non-finite pixels must end in
// vplkit::error.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "frontend/core/error.hpp"
#include "frontend/image/metrics.hpp"

namespace {

void require(bool condition, const char* what) {
  if (!condition) {
    std::fprintf(stderr, "fuzz_compare: %s\n", what);
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const int width = 1 + (data[0] & 15);
  const bool with_mask = (data[0] & 16) != 0;
  std::vector<float> floats((size - 1) / 4);
  if (!floats.empty()) std::memcpy(floats.data(), data + 1, floats.size() * 4);
  const int images = with_mask ? 3 : 2;
  const std::size_t per_image = floats.size() / static_cast<std::size_t>(images);
  const int height = static_cast<int>(per_image / (3 * static_cast<std::size_t>(width)));
  if (height < 1) return 0;
  std::vector<vplkit::image> parts(static_cast<std::size_t>(images));
  std::size_t next = 0;
  for (vplkit::image& part : parts) {
    part = vplkit::image(width, height);
    for (glm::vec4& p : part.texels) {
      p = glm::vec4(floats[next], floats[next + 1], floats[next + 2], 1.0f);
      next += 3;
    }
  }
  const vplkit::image* mask = with_mask ? &parts[2] : nullptr;
  try {
    const vplkit::image_metrics m = vplkit::compare_images(parts[0], parts[1], mask);
    for (const double value : {m.rmse, m.relative_mse, m.ssim, m.similarity, m.relative.rmse, m.relative.bias})
      require(std::isfinite(value), "a metric is not finite");
    require(std::isfinite(m.psnr) || (std::isinf(m.psnr) && m.psnr > 0.0 && m.rmse == 0.0), "PSNR is not finite for different images");
    require(m.psnr_defined == m.why_psnr_undefined.empty() && (m.psnr_defined || m.rmse > 0.0), "PSNR undefined without a reason, or for equal images");
    if (m.leak_rmse) require(std::isfinite(*m.leak_rmse), "the masked RMSE is not finite");
    if (m.masked) require(std::isfinite(m.masked->rmse) && std::isfinite(m.masked->bias), "a masked relative error is not finite");
    // An undefined relative number always says why; a black reference never gets a defined one.
    require(m.relative.defined == m.relative.why_undefined.empty(), "a relative error undefined without a reason");
    if (m.masked) require(m.masked->defined == m.masked->why_undefined.empty(), "a masked relative error undefined without a reason");
    bool black = true;
    for (const glm::vec4& p : parts[1].texels) black = black && p.r == 0.0f && p.g == 0.0f && p.b == 0.0f;
    if (black) require(!m.relative.defined && !m.psnr_defined == (m.rmse > 0.0), "a black reference gave a relative number");
    for (const float scale : {0.0f, 1.0f, 1e-30f, 3e38f}) {
      const std::vector<std::uint8_t> colours = vplkit::false_colour_error(parts[0], parts[1], scale);
      require(colours.size() == parts[0].texels.size() * 4, "the error image has the wrong size");
    }
  } catch (const vplkit::error&) {
    bool finite = true;
    for (const vplkit::image& part : parts)
      for (const glm::vec4& p : part.texels) finite = finite && std::isfinite(p.r) && std::isfinite(p.g) && std::isfinite(p.b);
    require(!finite, "finite images of the same size were refused");
  }
  return 0;
}
