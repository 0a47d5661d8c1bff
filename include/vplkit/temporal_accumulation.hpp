// Temporal accumulation of the RSM gather over a sequence of frames (vplkit render --poses): the
// gather's pattern turns from frame to frame (a new seed per frame), and each receiver's raw
// indirect irradiance is blended with its own from the frame before, found by reprojecting the
// receiver into the previous camera (an exponential moving average with weight `blend` on the new
// frame). The history is clamped to the current frame's neighbourhood first, the box
// mean +- clamp_width * standard deviation of the 3 x 3 receivers around it (variance clipping,
// Salvi 2016), so that light that moved (a light jump, a shadow edge) replaces the history within
// a few frames instead of fading in over 1 / blend. A history is used only where the reprojected
// receiver was seen in the previous frame at the depth the current one expects there (relative
// tolerance), so disocclusions start from the current frame alone. [RSMV] renders single frames;
// this is vplkit's (docs/errata.md, RSMV-11; measured in docs/rsm-study.md, "Flicker").
//
// GLSL twin: shaders/lib/temporal_accumulation.glsl.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

#include <vplkit/settings.hpp>

namespace vplkit {

/// Settings of the temporal accumulation. GLSL twin: struct temporal_settings.
template <typename T = float>
struct temporal_settings {
  T blend = T(0.2);            ///< weight of the current frame, in (0, 1]; 1 keeps no history
  T clamp_width = T(1);        ///< the history box: mean +- this many standard deviations of the 3 x 3 neighbourhood
  T depth_tolerance = T(0.02); ///< relative camera-depth difference at which a reprojected history is still accepted
};

/// Its description (vplkit/settings.hpp): validate() and the uniform upload come from it.
template <typename T>
struct settings_description<temporal_settings<T>> {
  using S = temporal_settings<T>;
  static constexpr const char* name = "temporal_settings";
  static constexpr bool glsl_twin = true;
  static constexpr auto fields() {
    return std::make_tuple(schema::field(&S::blend, "blend", schema::open_closed_range(0, 1), "", "weight of each new frame's gather against the history; 1: none"),
                           schema::field(&S::clamp_width, "clamp_width", schema::closed_range(0, 16), "standard deviations",
                                 "the history box: the 3 x 3 neighbourhood's mean +- this"),
                           schema::field(&S::depth_tolerance, "depth_tolerance", schema::closed_range(0, 1), "of the depth",
                                 "relative camera-depth difference at which a reprojected history is still accepted"));
  }
  static setting_problem rules(const S& settings) { return schema::no_rules(settings); }
};

/// The sums over a neighbourhood of receivers: count, per-channel sum and sum of squares.
template <typename T>
struct neighbourhood_moments {
  glm::vec<3, T> sum{T(0)};
  glm::vec<3, T> squares{T(0)};
  T count = T(0);
};

template <typename T>
void neighbourhood_add(neighbourhood_moments<T>& moments, const glm::vec<3, T>& value) {
  moments.sum += value;
  moments.squares += value * value;
  moments.count += T(1);
}

/// The history clamped to mean +- clamp_width * standard deviation of the moments (per channel),
/// then blended with the current value: mix(clamped, current, blend). Without a history (or an
/// empty neighbourhood) the current value alone.
template <typename T>
glm::vec<3, T> temporal_resolve(const glm::vec<3, T>& current, const glm::vec<3, T>& history, bool history_valid,
                                const neighbourhood_moments<T>& moments, const temporal_settings<T>& settings) {
  if (!history_valid || !(moments.count > T(0))) return current;
  const glm::vec<3, T> mean = moments.sum / moments.count;
  const glm::vec<3, T> variance = glm::max(moments.squares / moments.count - mean * mean, glm::vec<3, T>(T(0)));
  const glm::vec<3, T> width = settings.clamp_width * glm::sqrt(variance);
  const glm::vec<3, T> clamped = glm::clamp(history, mean - width, mean + width);
  return clamped + (current - clamped) * settings.blend;
}

/// Whether a history texel whose stored camera depth is `history_depth` belongs to the receiver
/// that the previous camera sees at `expected_depth` (both eye-space z, negative in front).
template <typename T>
bool temporal_history_matches(T expected_depth, T history_depth, const temporal_settings<T>& settings) {
  return expected_depth < T(0) && history_depth < T(0) && std::abs(history_depth - expected_depth) <= settings.depth_tolerance * -expected_depth;
}

}  // namespace vplkit
