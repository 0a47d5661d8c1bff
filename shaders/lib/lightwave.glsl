// GLSL twin of include/vplkit/lightwave.hpp: the Light Wave layout, lobe, Eq. 4.5, the flux
// layout and its VPLs' light, and the integrated-shadow stepping of [LW]. The image comparison (Alg. 1) and the ranking
// (Eq. 5.3) are host-side evaluations of whole images and have no shader twin.
#ifndef VPLKIT_LIGHTWAVE_GLSL
#define VPLKIT_LIGHTWAVE_GLSL

#include "lib/direct_light.glsl"
#include "lib/irradiance.glsl"
#include "lib/polynomial_math.glsl"
#include "lib/shading.glsl"

int lightwave_ray_count(int angle_deg) { return (90 / angle_deg) * (360 / angle_deg) + 1; }

int lightwave_vpl_count(int angle_deg, int per_ray) { return per_ray * lightwave_ray_count(angle_deg); }

float lightwave_attenuation(int hemisphere) {
  float attenuation = 0.05;
  for (int h = 0; h < hemisphere; ++h) attenuation *= 2.0;
  return attenuation;
}

float lightwave_lobe(float cos_angle) { return clamp((cos_angle + 0.5) / 1.5, 0.0, 1.0); }

struct lightwave_layout_settings {
  vec3 light_position;
  vec3 light_direction;
  int angle_deg;
  int per_ray;
  float max_distance;
};

struct lightwave_vpl {
  vec3 position;
  vec3 normal;
  float attenuation;
};

vec3 lightwave_direction(vec3 w, vec2 polar, vec2 azimuth) {
  vec3 helper = abs(w.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
  vec3 u = normalize(cross(helper, w));
  vec3 v = cross(w, u);
  return w * polar.x + (u * azimuth.x + v * azimuth.y) * polar.y;
}

lightwave_vpl lightwave_layout_vpl(int index, lightwave_layout_settings settings) {
  int rays = lightwave_ray_count(settings.angle_deg);
  int azimuths = 360 / settings.angle_deg;
  int hemisphere = index / rays;
  int ray = index - hemisphere * rays;
  int polar_step = ray == 0 ? 0 : (ray - 1) / azimuths + 1;
  int azimuth_step = ray == 0 ? 0 : (ray - 1) - (polar_step - 1) * azimuths;
  vec2 polar = direction_from_turns(float(polar_step * settings.angle_deg) / 360.0);
  vec2 azimuth = direction_from_turns(float(azimuth_step * settings.angle_deg) / 360.0);
  vec3 direction = lightwave_direction(settings.light_direction, polar, azimuth);
  float fraction = 0.5;
  for (int h = 0; h < hemisphere; ++h) fraction *= 0.5;
  return lightwave_vpl(settings.light_position + direction * (settings.max_distance * (1.0 - fraction)), direction,
                       lightwave_attenuation(hemisphere));
}

// ---- A point light's VPLs: the stacked hemispheres on both sides (see the C++ twin) ----

int lightwave_sphere_ray_count(int angle_deg) { return 2 * lightwave_ray_count(angle_deg) - 360 / angle_deg; }

int lightwave_sphere_vpl_count(int angle_deg, int per_ray) { return per_ray * lightwave_sphere_ray_count(angle_deg); }

int lightwave_sphere_sample_count(int angle_deg, int per_ray) { return 2 * lightwave_vpl_count(angle_deg, per_ray); }

lightwave_vpl lightwave_sphere_layout_vpl(int index, lightwave_layout_settings settings) {
  int rays = lightwave_ray_count(settings.angle_deg);
  int first = settings.per_ray * rays;
  if (index < first) return lightwave_layout_vpl(index, settings);
  int lower_rays = rays - 360 / settings.angle_deg;
  int hemisphere = (index - first) / lower_rays;
  int ray = (index - first) - hemisphere * lower_rays;
  lightwave_layout_settings opposite = settings;
  opposite.light_direction = -settings.light_direction;
  return lightwave_layout_vpl(hemisphere * rays + ray, opposite);
}

// ---- VPLs that carry the light's flux (see the C++ twin) ----

struct lightwave_cone_settings {
  vec3 light_direction;
  int angle_deg;
  int per_ray;
  float half_angle_deg;
};

vec2 lightwave_stratum_point(int sample_index, int per_ray) {
  float u = (float(sample_index) + 0.5) / float(per_ray);
  float lattice = 0.5 + float(sample_index) * 0.618033988749894848;
  return vec2(u, lattice - floor(lattice));
}

vec4 lightwave_cone_sample(int index, lightwave_cone_settings settings) {
  int rays = lightwave_ray_count(settings.angle_deg);
  int rings = 90 / settings.angle_deg;
  int azimuths = 360 / settings.angle_deg;
  int sample_index = index / rays;
  int ray = index - sample_index * rays;
  int ring = ray == 0 ? 0 : (ray - 1) / azimuths + 1;
  int sector = ray == 0 ? 0 : (ray - 1) - (ring - 1) * azimuths;
  float band_turns = settings.half_angle_deg / (360.0 * (float(rings) + 0.5));
  float lower = direction_from_turns(ray == 0 ? 0.0 : (float(ring) - 0.5) * band_turns).x;
  float upper = direction_from_turns((float(ring) + 0.5) * band_turns).x;
  vec2 stratum = lightwave_stratum_point(sample_index, settings.per_ray);
  float u = stratum.x;
  float v = stratum.y;
  float cos_polar = lower + (upper - lower) * u;
  float sin_polar = sqrt(max(0.0, 1.0 - cos_polar * cos_polar));
  float azimuth_turns = ray == 0 ? v : (float(sector) + v - 0.5) / float(azimuths);
  vec3 direction = lightwave_direction(settings.light_direction, vec2(cos_polar, sin_polar), direction_from_turns(azimuth_turns));
  float solid_angle = 6.28318530717958647692 * (lower - upper) / float(ray == 0 ? settings.per_ray : azimuths * settings.per_ray);
  return vec4(direction, solid_angle);
}

vec3 lightwave_ray_flux(spot_light light, vec3 direction, float solid_angle, vec3 albedo, vec3 surface_normal) {
  float cone = spot_light_cone(light, dot(light.direction, direction));
  float facing = dot(surface_normal, direction) < 0.0 ? 1.0 : 0.0;
  return albedo * light.intensity * (facing * cone * solid_angle);
}

vec4 lightwave_sphere_sample(int index, lightwave_cone_settings settings) {
  int count = lightwave_vpl_count(settings.angle_deg, settings.per_ray);
  lightwave_cone_settings hemisphere = settings;
  hemisphere.half_angle_deg = 90.0;
  if (index >= count) {
    hemisphere.light_direction = -settings.light_direction;
    index -= count;
  }
  return lightwave_cone_sample(index, hemisphere);
}

vec3 lightwave_ray_flux(point_light light, vec3 direction, float solid_angle, vec3 albedo, vec3 surface_normal) {
  float facing = dot(surface_normal, direction) < 0.0 ? 1.0 : 0.0;
  return albedo * light.intensity * (facing * solid_angle);
}

int lightwave_parallel_side(int angle_deg) {
  int side = 1;
  while (side * side < lightwave_ray_count(angle_deg)) ++side;
  return side;
}

int lightwave_parallel_sample_count(int angle_deg, int per_ray) { return per_ray * lightwave_parallel_side(angle_deg) * lightwave_parallel_side(angle_deg); }

vec3 lightwave_parallel_sample(int index, int angle_deg, int per_ray) {
  int side = lightwave_parallel_side(angle_deg);
  int cells = side * side;
  int sample_index = index / cells;
  int cell = index - sample_index * cells;
  int row = cell / side;
  int column = cell - row * side;
  vec2 stratum = lightwave_stratum_point(sample_index, per_ray);
  float u = stratum.x;
  float v = stratum.y;
  float cell_side = 2.0 / float(side);
  return vec3(-1.0 + (float(column) + u) * cell_side, -1.0 + (float(row) + v) * cell_side, cell_side * cell_side / float(per_ray));
}

vec3 lightwave_ray_flux(directional_light light, vec3 direction, float area, vec3 albedo, vec3 surface_normal) {
  float facing = dot(surface_normal, direction) < 0.0 ? 1.0 : 0.0;
  return albedo * light.irradiance * (facing * area);
}

float lightwave_patch_radius(float solid_angle, float distance_to_patch, float cos_incidence) {
  return sqrt(solid_angle * distance_to_patch * distance_to_patch / (max(abs(cos_incidence), 0.0625) * 3.14159265358979323846));
}

struct lightwave_flux_vpl {
  vec3 position;
  vec3 normal;
  vec3 flux;
  float radius;
};

vec3 lightwave_bounce_irradiance(vec3 x, vec3 n, lightwave_flux_vpl vpl, float min_distance) {
  irradiance_settings clamp_settings = irradiance_settings(max(vpl.radius, min_distance));
  return pixel_light_irradiance(x, n, vpl.position, vpl.normal, vpl.flux, clamp_settings) * 0.318309886183790671538;
}

bool lightwave_flux_vpl_faces(vec3 x, vec3 n, vec3 position, vec3 normal) {
  vec3 light_to_receiver = x - position;
  return dot(normal, light_to_receiver) > 0.0 && -dot(n, light_to_receiver) > 0.0;
}

float lightwave_bounce_weight(vec3 x, vec3 n, lightwave_flux_vpl vpl, float min_distance) {
  vec3 e = lightwave_bounce_irradiance(x, n, vpl, min_distance);
  return e.x + e.y + e.z;
}

#ifdef VPLKIT_LIGHTWAVE_FETCH_FLUX
// Defined by the including shader: flux VPL number `index`.
lightwave_flux_vpl lightwave_fetch_flux_vpl(int index);

vec3 lightwave_bounce_sum(vec3 x, vec3 n, int count, vec3 sum, float min_distance) {
  for (int index = 0; index < count; ++index) sum += lightwave_bounce_irradiance(x, n, lightwave_fetch_flux_vpl(index), min_distance);
  return sum;
}

// The receivers lightwave_bounce_sums sums at once (C++: lightwave_sum_receivers, from which the
// pipeline defines it).
#ifndef VPLKIT_LIGHTWAVE_SUM_RECEIVERS
#define VPLKIT_LIGHTWAVE_SUM_RECEIVERS 4
#endif

// lightwave_bounce_sum for VPLKIT_LIGHTWAVE_SUM_RECEIVERS receivers at once, each VPL fetched once
// for all of them: each sum the same additions in the same order.
void lightwave_bounce_sums(vec3 x[VPLKIT_LIGHTWAVE_SUM_RECEIVERS], vec3 n[VPLKIT_LIGHTWAVE_SUM_RECEIVERS], int count,
                           inout vec3 sums[VPLKIT_LIGHTWAVE_SUM_RECEIVERS], float min_distance) {
  for (int index = 0; index < count; ++index) {
    lightwave_flux_vpl vpl = lightwave_fetch_flux_vpl(index);
    for (int k = 0; k < VPLKIT_LIGHTWAVE_SUM_RECEIVERS; ++k) sums[k] += lightwave_bounce_irradiance(x[k], n[k], vpl, min_distance);
  }
}

vec3 lightwave_vertex_bounce(vec3 x, vec3 n, vec3 albedo, int count, irradiance_settings settings) {
  return diffuse_radiance(albedo, vec3(0.0), 0.0, lightwave_bounce_sum(x, n, count, vec3(0.0), settings.min_distance));
}
#endif

struct lightwave_shading_settings {
  float specular_strength;
  int specular_exponent;
};

vec3 lightwave_vpl_contribution(vec3 x, vec3 n, vec3 albedo, vec3 eye, lightwave_vpl vpl, lightwave_shading_settings settings) {
  // A VPL on the vertex itself has no direction to light it from (and normalize(0) is NaN).
  vec3 offset = vpl.position - x;
  if (!(dot(offset, offset) > 0.0)) return vec3(0.0);
  vec3 to_vpl = normalize(offset);
  float object_term = max(0.0, dot(n, to_vpl));
  float light_term = lightwave_lobe(dot(vpl.normal, -to_vpl));
  float strength = max(0.0, 1.0 - vpl.attenuation);
  vec3 reflected = -to_vpl - 2.0 * dot(n, -to_vpl) * n;
  vec3 to_eye = eye - x;
  float mirror = dot(to_eye, to_eye) > 0.0 ? max(0.0, dot(reflected, normalize(to_eye))) : 0.0;
  // pow, not a loop: see the C++ twin (llvmpipe caps nested loop iterations).
  float specular = object_term > 0.0 ? settings.specular_strength * pow(mirror, float(settings.specular_exponent)) : 0.0;
  return albedo * (object_term * light_term * strength) + vec3(specular);
}

float lightwave_vpl_weight(vec3 x, vec3 n, lightwave_vpl vpl) {
  vec3 offset = vpl.position - x;
  if (!(dot(offset, offset) > 0.0)) return 0.0;
  vec3 to_vpl = normalize(offset);
  float object_term = max(0.0, dot(n, to_vpl));
  float light_term = lightwave_lobe(dot(vpl.normal, -to_vpl));
  float strength = max(0.0, 1.0 - vpl.attenuation);
  return object_term * light_term * strength;
}

vec4 lightwave_map_coordinate(vec4 clip) {
  if (!(clip.w > 0.0)) return vec4(0.0);
  vec3 coordinate = clip.xyz / clip.w * 0.5 + 0.5;
  bool inside = coordinate.x >= 0.0 && coordinate.y >= 0.0 && coordinate.z >= 0.0 && coordinate.x <= 1.0 && coordinate.y <= 1.0 &&
                coordinate.z <= 1.0;
  return vec4(coordinate, inside ? 1.0 : 0.0);
}

float lightwave_map_fade(vec4 coordinate, float margin) {
  float border = min(min(coordinate.x, 1.0 - coordinate.x), min(coordinate.y, 1.0 - coordinate.y));
  float t = clamp(border / margin, 0.0, 1.0);
  return coordinate.w * (t * t * (3.0 - 2.0 * t));
}

float lightwave_group_confidence(vec3 x, vec3 group_position, float group_radius) {
  vec3 offset = group_position - x;
  float diameter = 4.0 * group_radius;
  return 1.0 / (1.0 + diameter * diameter / max(dot(offset, offset), 1e-12));
}

#ifdef VPLKIT_LIGHTWAVE_FETCH
// Defined by the including shader: VPL number `index`.
lightwave_vpl lightwave_fetch_vpl(int index);

vec3 lightwave_vertex_indirect(vec3 x, vec3 n, vec3 albedo, vec3 eye, int count, lightwave_shading_settings settings) {
  vec3 sum = vec3(0.0);
  for (int index = 0; index < count; ++index) sum += lightwave_vpl_contribution(x, n, albedo, eye, lightwave_fetch_vpl(index), settings);
  return count > 0 ? sum / float(count) : sum;
}
#endif

int lightwave_integrated_shadow_count(int steps, int maps) { return (steps + 2) * (maps * (maps - 1) / 2); }

vec4 lightwave_integrated_step(vec3 coordinate_a, vec3 coordinate_b, int lookup, int steps) {
  float t = float(lookup) / float(steps + 1);
  vec3 coordinate = coordinate_a + (coordinate_b - coordinate_a) * t;
  return vec4(coordinate, 2 * lookup >= steps + 1 ? 1.0 : 0.0);
}

vec3 lightwave_faked_indirect(vec3 direct, float shadow, float multiplier) {
  return direct * (0.5 * shadow) + direct * (multiplier - 0.5);
}

#endif
