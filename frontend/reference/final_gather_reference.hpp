// The exact reference of [FG]'s indirect irradiance in the final-gathering room: the walls
// cut into small patches, each gathered with the polygon-to-point form factor (exact for a
// planar polygon), in double precision. It judges both form factors of the technique.
#pragma once

#include <glm/glm.hpp>

#include "frontend/techniques/final_gather/final_gather_pipeline.hpp"

namespace vplkit {

/// The exact indirect irradiance at (x, n) in the final-gathering room without self-shadowing
/// (the paper's assumption), summed over the RGB channels: each wall cut into `cuts` x `cuts`
/// patches of its radiance lit by every light of the scene (unshadowed), gathered with the polygon form factor (exact for a
/// planar patch) in double precision.
double final_gather_reference(const final_gather_scene& scene, const glm::dvec3& x, const glm::dvec3& n, int cuts = 24);

}  // namespace vplkit
