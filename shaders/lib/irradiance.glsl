// GLSL twin of include/vplkit/irradiance.hpp: Eq. 3.2 of [RSMV] with the distance clamp.
#ifndef VPLKIT_IRRADIANCE_GLSL
#define VPLKIT_IRRADIANCE_GLSL

struct irradiance_settings {
  float min_distance;  // see the C++ struct; must be > 0
};

vec3 pixel_light_irradiance(vec3 x, vec3 n, vec3 xp, vec3 np, vec3 flux,
                            irradiance_settings settings) {
  vec3 light_to_receiver = x - xp;
  float min_distance = settings.min_distance;
  float distance_squared =
      max(dot(light_to_receiver, light_to_receiver), min_distance * min_distance);
  float emit = max(0.0, dot(np, light_to_receiver));
  float receive = max(0.0, -dot(n, light_to_receiver));
  return flux * ((emit / distance_squared) * (receive / distance_squared));
}

#endif
