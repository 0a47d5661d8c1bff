// Embeds one vplkit kernel, as a user would: irradiance from one pixel light (Eq. 3.2).
#include <cmath>
#include <cstdio>

#include <vplkit/irradiance.hpp>
#include <vplkit/version.hpp>

int main() {
  const glm::vec3 receiver(0.0f, 0.0f, 1.0f), receiver_normal(0.0f, 0.0f, -1.0f);
  const glm::vec3 light(0.0f), light_normal(0.0f, 0.0f, 1.0f), flux(2.0f);
  const glm::vec3 e = vplkit::pixel_light_irradiance(receiver, receiver_normal, light, light_normal, flux);
  // Face to face at distance 1: E = flux.
  std::printf("vplkit %s: E = %g (expected 2)\n", vplkit::version_string, static_cast<double>(e.x));
  return std::fabs(e.x - 2.0f) < 1e-6f ? 0 : 1;
}
