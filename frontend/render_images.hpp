// The images `vplkit render` writes for the RSM techniques: the final image, the indirect
// irradiance alone (paper 000, Fig. 5.1 a/b) and the amplified luminance difference between
// the radial pattern without and with visibility (Fig. 5.1c, 5.5).
#pragma once

#include <cstdint>
#include <vector>

namespace vplkit {

/// Rec. 709 luminance of linear RGB.
float luminance(float r, float g, float b);

/// The exposure that maps the 99th percentile of the luminance of `rgba` (linear) to 0.8: a
/// deterministic display scale for images whose level depends on the scene (indirect light).
/// Returns 1 for an all-black image.
float percentile_exposure(const std::vector<float>& rgba);

/// |L(without) - L(with)| * scale, as grey, in linear RGBA (rows as given). Brighter = more
/// light removed (or added) by the visibility approximation.
std::vector<float> luminance_difference(const std::vector<float>& without_visibility, const std::vector<float>& with_visibility,
                                        float scale);

}  // namespace vplkit
