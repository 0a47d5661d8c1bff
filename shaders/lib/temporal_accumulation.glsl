// GLSL twin of include/vplkit/temporal_accumulation.hpp: the history of the RSM gather's indirect
// irradiance clamped to the current 3 x 3 neighbourhood (mean +- clamp_width standard deviations)
// and blended with the current frame; the reprojected history's depth test.
#ifndef VPLKIT_TEMPORAL_ACCUMULATION_GLSL
#define VPLKIT_TEMPORAL_ACCUMULATION_GLSL

struct temporal_settings {
  float blend;
  float clamp_width;
  float depth_tolerance;
};

struct neighbourhood_moments {
  vec3 sum;
  vec3 squares;
  float count;
};

void neighbourhood_add(inout neighbourhood_moments moments, vec3 value) {
  moments.sum += value;
  moments.squares += value * value;
  moments.count += 1.0;
}

vec3 temporal_resolve(vec3 current, vec3 history, bool history_valid, neighbourhood_moments moments, temporal_settings settings) {
  if (!history_valid || !(moments.count > 0.0)) return current;
  vec3 mean = moments.sum / moments.count;
  vec3 variance = max(moments.squares / moments.count - mean * mean, vec3(0.0));
  vec3 width = settings.clamp_width * sqrt(variance);
  vec3 clamped = clamp(history, mean - width, mean + width);
  return clamped + (current - clamped) * settings.blend;
}

bool temporal_history_matches(float expected_depth, float history_depth, temporal_settings settings) {
  return expected_depth < 0.0 && history_depth < 0.0 && abs(history_depth - expected_depth) <= settings.depth_tolerance * -expected_depth;
}

#endif
