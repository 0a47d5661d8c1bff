// Light Wave ([LW], Larson 2012): virtual point lights floating in space on hemispheres
// stacked around the primary light, their per-vertex contribution with a lobe widened to 240
// degrees, the counting of the integrated indirect shadows, and the thesis's image comparison.
//
// Layout (chapter 4.1, Eq. 4.1, 4.2, 5.1). Rays leave the light every `angle` degrees around its
// axis and every `angle` degrees away from it, down to 90 degrees, plus the axis itself:
// rays = (90 / angle) * (360 / angle) + 1 (one axis ray: no duplicates at the pole). On each ray
// lie `per_ray` VPLs, one per hemisphere h = 0 .. per_ray - 1, at the distance
// max_distance * (1 - 2^-(h+1)) (Eq. 4.1 with i = h + 1), with the attenuation 0.05 * 2^h
// (Eq. 4.2: 5%, 10%, 20%, 40%, 80%). The paper indexes the two formulas inconsistently; this
// reading reproduces both of its number sequences (docs/errata.md, LW-1). A VPL's normal is its ray's
// direction: the light's direction rotated by the polar angle about an axis perpendicular to it,
// then by the azimuth about the light's direction. (The thesis's printed update overwrites
// normal.x before it computes normal.y; this is the rotation it means.)
// Index order: hemisphere-major, index = h * rays + ray; ray 0 is the axis, ray 1 + (e - 1) *
// azimuths + a has the polar angle e * angle and the azimuth a * angle.
//
// Contribution (Eq. 4.5), per vertex, summed over all VPLs and divided by their number:
//   obj   = max(0, <n, normalize(vpl - x)>)
//   light = clamp((<n_vpl, normalize(x - vpl)> + 0.5) / 1.5, 0, 1)        (the 240-degree lobe)
//   indirect += albedo * obj * light * max(0, 1 - attenuation) + specular
// with no distance falloff (the thesis has none). The factor 1 - attenuation goes negative from
// the sixth hemisphere on (160%); it is clamped at 0 (docs/errata.md, LW-2). The specular term, which the
// thesis describes but does not print, is specular_strength * max(0, <reflect(l, n), v>)^exponent
// with l = normalize(x - vpl), v = normalize(eye - x): a Phong lobe of the VPL seen in the mirror
// direction, 0 for surfaces facing away from the VPL.
//
// Indirect shadows (section 4.3). Accurate: shadow maps from a few VPLs; a fragment's factor is
// the mean of their lookups in the thesis. vplkit weights each lookup by that VPL's diffuse
// weight at the fragment (lightwave_vpl_weight) over the probability with which it was chosen,
// so the factor estimates the share of the VPL light that reaches the fragment, and lookups
// behind or outside a map do not vote (lightwave_map_coordinate). Integrated: lookups stepped
// between the coordinates of a fragment in every pair of maps (lightwave_integrated_step),
// between valid endpoints only.
//
// GLSL twin: shaders/lib/lightwave.glsl.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>

#include <vplkit/direct_light.hpp>
#include <vplkit/irradiance.hpp>
#include <vplkit/polynomial_math.hpp>
#include <vplkit/settings.hpp>
#include <vplkit/shading.hpp>

namespace vplkit {

/// Whether rays every `angle_deg` degrees close up both around the axis and down to 90 degrees
/// from it (1, 2, 3, 5, 6, 9, 10, 15, 18, 30, 45 or 90).
constexpr bool lightwave_ray_angle_divides(int angle_deg) { return angle_deg >= 1 && 90 % angle_deg == 0 && 360 % angle_deg == 0; }

/// Rays of the layout: (90 / angle) * (360 / angle) + 1.
constexpr int lightwave_ray_count(int angle_deg) { return (90 / angle_deg) * (360 / angle_deg) + 1; }

/// Eq. 5.1: VPLs = per_ray * ((90 / angle) * (360 / angle) + 1). 5 degrees x 5 -> 6485.
constexpr int lightwave_vpl_count(int angle_deg, int per_ray) { return per_ray * lightwave_ray_count(angle_deg); }

/// Eq. 4.2: the attenuation of hemisphere h (0 = innermost): 0.05 * 2^h.
template <typename T = float>
constexpr T lightwave_attenuation(int hemisphere) {
  T attenuation = T(0.05);
  for (int h = 0; h < hemisphere; ++h) attenuation *= T(2);
  return attenuation;
}

/// The 240-degree lobe of a VPL (section 3.3): maps cos in [-0.5, 1] onto [0, 1].
template <typename T>
T lightwave_lobe(T cos_angle) {
  return glm::clamp((cos_angle + T(0.5)) / T(1.5), T(0), T(1));
}

/// Where the VPLs go. GLSL twin: struct lightwave_layout_settings.
template <typename T = float>
struct lightwave_layout_settings {
  glm::vec<3, T> light_position = glm::vec<3, T>(0);
  glm::vec<3, T> light_direction = glm::vec<3, T>(0, -1, 0);  ///< unit
  int angle_deg = 5;      ///< between rays, around and away from the axis (the thesis: 5)
  int per_ray = 5;        ///< VPLs per ray = stacked hemispheres (the thesis: 5)
  T max_distance = T(1);  ///< the hemispheres approach it: h-th at max_distance (1 - 2^-(h+1))
};

template <typename T>
struct settings_description<lightwave_layout_settings<T>> {
  using S = lightwave_layout_settings<T>;
  static constexpr const char* name = "lightwave_layout_settings";
  static constexpr bool glsl_twin = true;
  static constexpr auto fields() {
    return std::make_tuple(schema::field(&S::light_position, "light_position", schema::any_finite(), "scene units", "the spot light's position"),
                           schema::field(&S::light_direction, "light_direction", schema::closed_range(-1, 1), "", "the spot light's axis, unit"),
                           schema::field(&S::angle_deg, "angle_deg", schema::closed_range(1, 90), "degrees", "between VPL rays, around and away from the axis (divides 90 and 360)"),
                           schema::field(&S::per_ray, "per_ray", schema::closed_range(1, 32), "", "VPLs per ray: stacked hemispheres"),
                           schema::field(&S::max_distance, "max_distance", schema::at_least(0.0), "scene units", "the distance the hemispheres approach"));
  }
  static setting_problem rules(const S& settings) {
    if (!lightwave_ray_angle_divides(settings.angle_deg))
      return setting_problem("Light Wave ray angle must divide 90 and 360 (1, 2, 3, 5, 6, 9, 10, 15, 18, 30, 45 or 90 degrees)");
    if (!(std::abs(glm::length(settings.light_direction) - T(1)) < T(1e-3))) return setting_problem("lightwave_layout_settings::light_direction must be a unit vector");
    return {};
  }
};

/// The problem with a ray angle and a VPL count per ray, if any.
template <typename T = float>
setting_problem validate_lightwave_layout(int angle_deg, int per_ray) {
  lightwave_layout_settings<T> layout;
  layout.angle_deg = angle_deg;
  layout.per_ray = per_ray;
  return validate(layout);
}

/// One VPL. GLSL twin: struct lightwave_vpl.
template <typename T>
struct lightwave_vpl {
  glm::vec<3, T> position;
  glm::vec<3, T> normal;  ///< unit: the direction of its ray
  T attenuation;          ///< Eq. 4.2
};

/// The direction at (cos, sin) `polar` off the unit axis w and (cos, sin) `azimuth` around it, in
/// the orthonormal basis (u, v, w) that every Light Wave layout builds around the light's direction.
template <typename T>
glm::vec<3, T> lightwave_direction(const glm::vec<3, T>& w, const glm::vec<2, T>& polar, const glm::vec<2, T>& azimuth) {
  const glm::vec<3, T> helper = glm::abs(w.y) < T(0.9) ? glm::vec<3, T>(0, 1, 0) : glm::vec<3, T>(1, 0, 0);
  const glm::vec<3, T> u = glm::normalize(glm::cross(helper, w));
  const glm::vec<3, T> v = glm::cross(w, u);
  return w * polar.x + (u * azimuth.x + v * azimuth.y) * polar.y;
}

/// VPL number `index` (0 .. lightwave_vpl_count - 1) of the layout.
template <typename T>
lightwave_vpl<T> lightwave_layout_vpl(int index, const lightwave_layout_settings<T>& settings) {
  const int rays = lightwave_ray_count(settings.angle_deg);
  const int azimuths = 360 / settings.angle_deg;
  const int hemisphere = index / rays;
  const int ray = index - hemisphere * rays;
  const int polar_step = ray == 0 ? 0 : (ray - 1) / azimuths + 1;
  const int azimuth_step = ray == 0 ? 0 : (ray - 1) - (polar_step - 1) * azimuths;
  const glm::vec<2, T> polar = direction_from_turns(T(polar_step * settings.angle_deg) / T(360));
  const glm::vec<2, T> azimuth = direction_from_turns(T(azimuth_step * settings.angle_deg) / T(360));
  const glm::vec<3, T> direction = lightwave_direction(settings.light_direction, polar, azimuth);
  T fraction = T(0.5);  // 2^-(h+1)
  for (int h = 0; h < hemisphere; ++h) fraction *= T(0.5);
  return {settings.light_position + direction * (settings.max_distance * (T(1) - fraction)), direction,
          lightwave_attenuation<T>(hemisphere)};
}

/// Writes all lightwave_vpl_count VPLs to `out` (an output iterator), in index order.
template <typename T, typename OutputIterator>
OutputIterator lightwave_layout(const lightwave_layout_settings<T>& settings, OutputIterator out) {
  const int count = lightwave_vpl_count(settings.angle_deg, settings.per_ray);
  for (int index = 0; index < count; ++index) *out++ = lightwave_layout_vpl(index, settings);
  return out;
}

// ---- A point light's VPLs: the stacked hemispheres on both sides of the light ----
//
// A point light sends light into the whole sphere, and [LW]'s hemispheres face one way. The
// sphere layout is the hemisphere layout twice: around an axis `light_direction` (any unit
// vector; its choice only turns the pattern) and around its opposite. The thesis layout's last
// ring lies at 90 degrees, on the equator both hemispheres share, so the second hemisphere leaves
// that ring out (no VPL twice); the flux layout's patches of half-angle 90 tile each hemisphere,
// so both keep every ray and the patches tile the sphere (solid angles summing to 4 pi).

/// Rays of the thesis layout over the sphere: both hemispheres, the equator's ring once.
constexpr int lightwave_sphere_ray_count(int angle_deg) { return 2 * lightwave_ray_count(angle_deg) - 360 / angle_deg; }

/// VPLs of the thesis layout over the sphere: per_ray on each of lightwave_sphere_ray_count rays.
constexpr int lightwave_sphere_vpl_count(int angle_deg, int per_ray) { return per_ray * lightwave_sphere_ray_count(angle_deg); }

/// Samples of the flux layout over the sphere: a hemisphere's cone layout (half-angle 90) twice.
constexpr int lightwave_sphere_sample_count(int angle_deg, int per_ray) { return 2 * lightwave_vpl_count(angle_deg, per_ray); }

/// VPL `index` (0 .. lightwave_sphere_vpl_count - 1) of the thesis layout over the sphere: first
/// the hemisphere layout's VPLs around light_direction in their order (lightwave_layout_vpl), then
/// those around -light_direction without its equator ring, hemisphere-major.
template <typename T>
lightwave_vpl<T> lightwave_sphere_layout_vpl(int index, const lightwave_layout_settings<T>& settings) {
  const int rays = lightwave_ray_count(settings.angle_deg);
  const int first = settings.per_ray * rays;
  if (index < first) return lightwave_layout_vpl(index, settings);
  // The equator ring is the last one (ray indices rays - 360 / angle .. rays - 1).
  const int lower_rays = rays - 360 / settings.angle_deg;
  const int hemisphere = (index - first) / lower_rays;
  const int ray = (index - first) - hemisphere * lower_rays;
  lightwave_layout_settings<T> opposite = settings;
  opposite.light_direction = -settings.light_direction;
  return lightwave_layout_vpl(hemisphere * rays + ray, opposite);
}

// ---- VPLs that carry the light's flux (vplkit's default energy; docs/errata.md, LW-8) ----
//
// The thesis's VPLs float in space with a strength that ignores the light (Eq. 4.5 has no flux
// and no distance), so their indirect light has no physical level. Here every ray of the layout
// stands for a patch of the spot's cone, and the VPL it makes sits where that ray meets the scene,
// reflecting the flux the patch carries there:
//   flux = albedo * I * cone(direction) * solid_angle          (0 where the surface faces away)
// and lighting a vertex as a diffuse surface patch does (Eq. 3.2 of [RSMV], the RSM's pixel light):
//   E(x, n) = flux / pi * max(0, <n_vpl, x - p>) * max(0, <n, p - x>) / max(|x - p|, r)^4
// with r the radius of the disk the patch covers (lightwave_patch_radius), which bounds the 1/r^2
// singularity where a point light would overstate a patch. The rays cover the cone, not the
// hemisphere: `angle_deg` gives the thesis's counts (Eq. 5.1), the rings are spread evenly up to
// the cone's half-angle, and the `per_ray` VPLs of a ray are stratified samples of the ray's
// patch (a rank-1 lattice over the patch, equal solid angles), not stacked hemispheres.

/// The cone the flux layout covers. GLSL twin: struct lightwave_cone_settings.
template <typename T = float>
struct lightwave_cone_settings {
  glm::vec<3, T> light_direction = glm::vec<3, T>(0, -1, 0);  ///< unit
  int angle_deg = 5;      ///< as lightwave_layout_settings: (90 / angle) rings of (360 / angle) rays, plus the axis
  int per_ray = 5;        ///< samples of each ray's patch
  T half_angle_deg = T(50);  ///< the cone's half-angle the rings reach, in (0, 90]
};

// Described like the layout it shares angle_deg and per_ray with, so that it has a std140 layout
// (vplkit/std140.hpp) and reaches a shader in a uniform block on every target, Vulkan included.
template <typename T>
struct settings_description<lightwave_cone_settings<T>> {
  using S = lightwave_cone_settings<T>;
  static constexpr const char* name = "lightwave_cone_settings";
  static constexpr bool glsl_twin = true;
  static constexpr auto fields() {
    return std::make_tuple(schema::field(&S::light_direction, "light_direction", schema::closed_range(-1, 1), "", "the spot light's axis, unit"),
                           schema::field(&S::angle_deg, "angle_deg", schema::closed_range(1, 90), "degrees", "between rays, around and away from the axis (divides 90 and 360)"),
                           schema::field(&S::per_ray, "per_ray", schema::closed_range(1, 32), "", "samples of each ray's patch"),
                           schema::field(&S::half_angle_deg, "half_angle_deg", schema::open_closed_range(0, 90), "degrees", "the cone's half-angle the rings reach"));
  }
  static setting_problem rules(const S& settings) {
    if (!lightwave_ray_angle_divides(settings.angle_deg))
      return setting_problem("Light Wave ray angle must divide 90 and 360 (1, 2, 3, 5, 6, 9, 10, 15, 18, 30, 45 or 90 degrees)");
    if (!(std::abs(glm::length(settings.light_direction) - T(1)) < T(1e-3))) return setting_problem("lightwave_cone_settings::light_direction must be a unit vector");
    return {};
  }
};

/// Where sample s of a patch (or of a sun's cell) lies in the patch's unit square: (u, v) =
/// ((s + 1/2) / per_ray, frac(1/2 + s g)), g the golden ratio's conjugate: u stratified, v a rank-1
/// lattice, so the per_ray samples of one patch spread over both coordinates.
template <typename T>
glm::vec<2, T> lightwave_stratum_point(int sample_index, int per_ray) {
  const T u = (T(sample_index) + T(0.5)) / T(per_ray);
  const T lattice = T(0.5) + T(sample_index) * T(0.618033988749894848);
  return {u, lattice - std::floor(lattice)};
}

/// Sample `index` (0 .. lightwave_vpl_count - 1; index = sample_index * rays + ray, ray 0 the axis) of
/// the flux layout: (unit direction, solid angle). The axis ray's patch is the cap of polar
/// angles [0, d/2], ring e's (e = 1 .. 90 / angle) the band [(e - 1/2) d, (e + 1/2) d] cut into
/// 360 / angle equal sectors, d = half_angle / (90 / angle + 1/2), so that the patches tile the
/// cone exactly; each patch is split into per_ray equal solid angles. Sample s of a patch lies at
/// (u, v) = ((s + 1/2) / per_ray, frac(1/2 + s g)), g the golden ratio's conjugate, with u
/// uniform in the cosine of the polar angle (equal solid angle) and v across the sector's azimuths.
template <typename T>
glm::vec<4, T> lightwave_cone_sample(int index, const lightwave_cone_settings<T>& settings) {
  const int rays = lightwave_ray_count(settings.angle_deg);
  const int rings = 90 / settings.angle_deg;
  const int azimuths = 360 / settings.angle_deg;
  const int sample_index = index / rays;
  const int ray = index - sample_index * rays;
  const int ring = ray == 0 ? 0 : (ray - 1) / azimuths + 1;
  const int sector = ray == 0 ? 0 : (ray - 1) - (ring - 1) * azimuths;
  const T band_turns = settings.half_angle_deg / (T(360) * (T(rings) + T(0.5)));  // d in turns
  const T lower = direction_from_turns(ray == 0 ? T(0) : (T(ring) - T(0.5)) * band_turns).x;  // cos of the patch's polar bounds
  const T upper = direction_from_turns((T(ring) + T(0.5)) * band_turns).x;
  const glm::vec<2, T> stratum = lightwave_stratum_point<T>(sample_index, settings.per_ray);
  const T u = stratum.x;
  const T v = stratum.y;
  const T cos_polar = lower + (upper - lower) * u;
  const T sin_polar = std::sqrt(glm::max(T(0), T(1) - cos_polar * cos_polar));
  const T azimuth_turns = ray == 0 ? v : (T(sector) + v - T(0.5)) / T(azimuths);
  const glm::vec<3, T> direction =
      lightwave_direction(settings.light_direction, glm::vec<2, T>(cos_polar, sin_polar), direction_from_turns(azimuth_turns));
  const T solid_angle = T(6.28318530717958647692) * (lower - upper) / T(ray == 0 ? settings.per_ray : azimuths * settings.per_ray);
  return {direction, solid_angle};
}

/// The flux a ray's patch brings to the surface it meets and that surface reflects: albedo * I *
/// cone(direction) * solid_angle, 0 when the surface faces away from the light (its back is lit).
template <typename T>
glm::vec<3, T> lightwave_ray_flux(const spot_light<T>& light, const glm::vec<3, T>& direction, T solid_angle, const glm::vec<3, T>& albedo,
                                  const glm::vec<3, T>& surface_normal) {
  const T cone = spot_light_cone(light, glm::dot(light.direction, direction));
  const T facing = glm::dot(surface_normal, direction) < T(0) ? T(1) : T(0);
  return albedo * light.intensity * (facing * cone * solid_angle);
}

/// Sample `index` (0 .. lightwave_sphere_sample_count - 1) of a point light's flux layout:
/// (unit direction, solid angle). Below lightwave_vpl_count: lightwave_cone_sample around
/// settings.light_direction with the half-angle 90; from there on the same around its opposite.
/// settings.half_angle_deg is not read (a sphere has no cone).
template <typename T>
glm::vec<4, T> lightwave_sphere_sample(int index, const lightwave_cone_settings<T>& settings) {
  const int count = lightwave_vpl_count(settings.angle_deg, settings.per_ray);
  lightwave_cone_settings<T> hemisphere = settings;
  hemisphere.half_angle_deg = T(90);
  if (index >= count) {
    hemisphere.light_direction = -settings.light_direction;
    index -= count;
  }
  return lightwave_cone_sample(index, hemisphere);
}

/// The flux a point light's patch brings to the surface it meets and that surface reflects:
/// albedo * I * solid_angle, 0 when the surface faces away from the light.
template <typename T>
glm::vec<3, T> lightwave_ray_flux(const point_light<T>& light, const glm::vec<3, T>& direction, T solid_angle, const glm::vec<3, T>& albedo,
                                  const glm::vec<3, T>& surface_normal) {
  const T facing = glm::dot(surface_normal, direction) < T(0) ? T(1) : T(0);
  return albedo * light.intensity * (facing * solid_angle);
}

// ---- A sun's VPLs: parallel rays on a grid across its orthographic map (docs/errata.md, LW-11) ----
//
// A directional light has no position to spread rays from: its flux layout is a square grid of
// cells across the window of an orthographic map that holds the scene (half-side `half_extent`,
// looking along the sun's direction), each cell split into `per_ray` samples by the cone
// layout's rank-1 lattice, so that every sample stands for an equal part of the window's area.
// The grid has as many cells as the cone layout has rays (lightwave_ray_count, rounded up to a
// square), so that `angle_deg` sets the same VPL count for every kind of light.

/// The side of the sun's grid: the least s with s * s >= lightwave_ray_count(angle_deg).
constexpr int lightwave_parallel_side(int angle_deg) {
  int side = 1;
  while (side * side < lightwave_ray_count(angle_deg)) ++side;
  return side;
}

/// Samples of the sun's flux layout: per_ray on each of the grid's cells.
constexpr int lightwave_parallel_sample_count(int angle_deg, int per_ray) {
  return per_ray * lightwave_parallel_side(angle_deg) * lightwave_parallel_side(angle_deg);
}

/// Sample `index` (0 .. lightwave_parallel_sample_count - 1; index = sample_index * cells + cell,
/// cell = row * side + column) of the sun's flux layout: (x, y) in [-1, 1] across the map's
/// window and the sample's share of the window's area (whose side is 2: the shares sum to 4; the
/// area in scene units is share * half_extent^2). Sample s of a cell lies at ((s + 1/2) / per_ray,
/// frac(1/2 + s g)) of the cell, g the golden ratio's conjugate (the cone layout's lattice).
template <typename T>
glm::vec<3, T> lightwave_parallel_sample(int index, int angle_deg, int per_ray) {
  const int side = lightwave_parallel_side(angle_deg);
  const int cells = side * side;
  const int sample_index = index / cells;
  const int cell = index - sample_index * cells;
  const int row = cell / side;
  const int column = cell - row * side;
  const glm::vec<2, T> stratum = lightwave_stratum_point<T>(sample_index, per_ray);
  const T u = stratum.x;
  const T v = stratum.y;
  const T cell_side = T(2) / T(side);
  return {T(-1) + (T(column) + u) * cell_side, T(-1) + (T(row) + v) * cell_side, cell_side * cell_side / T(per_ray)};
}

/// The flux a sun's sample brings to the surface it meets and that surface reflects: albedo *
/// irradiance * area (the sample's cross-section, perpendicular to the light), 0 when the surface
/// faces away from the light. `direction` is the light's (the twins of the other kinds take the
/// ray's).
template <typename T>
glm::vec<3, T> lightwave_ray_flux(const directional_light<T>& light, const glm::vec<3, T>& direction, T area, const glm::vec<3, T>& albedo,
                                  const glm::vec<3, T>& surface_normal) {
  const T facing = glm::dot(surface_normal, direction) < T(0) ? T(1) : T(0);
  return albedo * light.irradiance * (facing * area);
}

/// The radius of the disk with the area a patch of `solid_angle` covers on a surface at
/// `distance` met at `cos_incidence` (the ray against the surface's normal): sqrt(solid_angle
/// distance^2 / (|cos| pi)), with |cos| at least 1/16 (a grazing patch is long, not wide).
template <typename T>
T lightwave_patch_radius(T solid_angle, T distance, T cos_incidence) {
  return std::sqrt(solid_angle * distance * distance / (glm::max(std::abs(cos_incidence), T(0.0625)) * T(3.14159265358979323846)));
}

/// A VPL of the flux layout. GLSL twin: struct lightwave_flux_vpl.
template <typename T>
struct lightwave_flux_vpl {
  glm::vec<3, T> position;  ///< on the surface its ray met
  glm::vec<3, T> normal;    ///< that surface's unit normal
  glm::vec<3, T> flux;      ///< lightwave_ray_flux
  T radius;                 ///< lightwave_patch_radius: the distance clamp of its light
};

/// The irradiance a flux VPL gives (x, n): Eq. 3.2 / pi with the distance clamped at
/// max(vpl.radius, min_distance).
template <typename T>
glm::vec<3, T> lightwave_bounce_irradiance(const glm::vec<3, T>& x, const glm::vec<3, T>& n, const lightwave_flux_vpl<T>& vpl, T min_distance) {
  irradiance_settings<T> clamp;
  clamp.min_distance = glm::max(vpl.radius, min_distance);
  return pixel_light_irradiance(x, n, vpl.position, vpl.normal, vpl.flux, clamp) * inv_pi<T>;
}

/// Whether a flux VPL at (position, normal) lights (x, n) at all: x in front of its surface and
/// facing it, the two factors of Eq. 3.2 that can vanish (lightwave_bounce_irradiance > 0 for a
/// VPL of positive flux).
template <typename T>
bool lightwave_flux_vpl_faces(const glm::vec<3, T>& x, const glm::vec<3, T>& n, const glm::vec<3, T>& position, const glm::vec<3, T>& normal) {
  const glm::vec<3, T> light_to_receiver = x - position;
  return glm::dot(normal, light_to_receiver) > T(0) && -glm::dot(n, light_to_receiver) > T(0);
}

/// A flux VPL's weight at (x, n) for the indirect shadows: the sum of the channels of its irradiance.
template <typename T>
T lightwave_bounce_weight(const glm::vec<3, T>& x, const glm::vec<3, T>& n, const lightwave_flux_vpl<T>& vpl, T min_distance) {
  const glm::vec<3, T> e = lightwave_bounce_irradiance(x, n, vpl, min_distance);
  return e.x + e.y + e.z;
}

/// `sum` plus the irradiance at (x, n) of `count` flux VPLs from `fetch(int index) ->
/// lightwave_flux_vpl<T>`, added in index order. A renderer that cannot hold every VPL at once
/// adds them a part at a time, each part continuing from the last one's sum: the same additions in
/// the same order, so the same result to the bit. GLSL twin: lightwave_bounce_sum, with the VPLs
/// from the including shader's `lightwave_flux_vpl lightwave_fetch_flux_vpl(int index)` (define
/// VPLKIT_LIGHTWAVE_FETCH_FLUX first).
template <typename T, typename Fetch>
glm::vec<3, T> lightwave_bounce_sum(const glm::vec<3, T>& x, const glm::vec<3, T>& n, Fetch&& fetch, int count, glm::vec<3, T> sum, T min_distance) {
  for (int index = 0; index < count; ++index) sum += lightwave_bounce_irradiance(x, n, fetch(index), min_distance);
  return sum;
}

/// The receivers lightwave_bounce_sums sums at once: lightwave_capture.frag's receivers per
/// fragment. GLSL twin: VPLKIT_LIGHTWAVE_SUM_RECEIVERS (its default; the pipeline defines it from
/// this). A software rasteriser reads a uniform block per fragment lane, which costs more than the
/// arithmetic of Eq. 3.2 (three vec4 reads cost about three times the terms on llvmpipe); four
/// receivers share each read: the boxes' sums about half as dear on llvmpipe with 2 cores. More
/// would leave a small scene's few fragments to fewer cores (and a GPU, which broadcasts such
/// reads, with fewer threads).
inline constexpr int lightwave_sum_receivers = 4;

/// lightwave_bounce_sum for lightwave_sum_receivers receivers at once: sums[k] plus the irradiance
/// at (x[k], n[k]) of `count` flux VPLs from `fetch`, each VPL fetched once for all of them. Each
/// receiver's sum is the same additions in the same order as lightwave_bounce_sum's, so the same
/// result to the bit. GLSL twin: lightwave_bounce_sums (VPLKIT_LIGHTWAVE_FETCH_FLUX as there).
template <typename T, typename Fetch>
std::array<glm::vec<3, T>, lightwave_sum_receivers> lightwave_bounce_sums(const std::array<glm::vec<3, T>, lightwave_sum_receivers>& x,
                                                                        const std::array<glm::vec<3, T>, lightwave_sum_receivers>& n, Fetch&& fetch,
                                                                        int count, std::array<glm::vec<3, T>, lightwave_sum_receivers> sums,
                                                                        T min_distance) {
  for (int index = 0; index < count; ++index) {
    const lightwave_flux_vpl<T> vpl = fetch(index);
    for (int k = 0; k < lightwave_sum_receivers; ++k) sums[k] += lightwave_bounce_irradiance(x[k], n[k], vpl, min_distance);
  }
  return sums;
}

/// The radiance one bounce sends to the camera from vertex (x, n) with albedo: albedo / pi times
/// the irradiance of `count` flux VPLs from `fetch` summed (lightwave_bounce_sum from 0, then
/// diffuse_radiance). GLSL twin: lightwave_vertex_bounce (VPLKIT_LIGHTWAVE_FETCH_FLUX as there).
template <typename T, typename Fetch>
glm::vec<3, T> lightwave_vertex_bounce(const glm::vec<3, T>& x, const glm::vec<3, T>& n, const glm::vec<3, T>& albedo, Fetch&& fetch, int count,
                                       const irradiance_settings<T>& settings) {
  return diffuse_radiance(albedo, glm::vec<3, T>(0), T(0), lightwave_bounce_sum(x, n, fetch, count, glm::vec<3, T>(0), settings.min_distance));
}

/// The shading parameters of Eq. 4.5. GLSL twin: struct lightwave_shading_settings.
template <typename T = float>
struct lightwave_shading_settings {
  T specular_strength = T(0.05);  ///< weight of the specular term (the thesis does not print one)
  int specular_exponent = 16;     ///< Phong exponent of the specular term (>= 1)
};

template <typename T>
struct settings_description<lightwave_shading_settings<T>> {
  using S = lightwave_shading_settings<T>;
  static constexpr const char* name = "lightwave_shading_settings";
  static constexpr bool glsl_twin = true;
  static constexpr auto fields() {
    return std::make_tuple(schema::field(&S::specular_strength, "specular_strength", schema::at_least(0.0), "", "weight of Eq. 4.5's specular term"),
                           schema::field(&S::specular_exponent, "specular_exponent", schema::closed_range(1, 256), "", "Phong exponent of the specular term"));
  }
  static setting_problem rules(const S& settings) { return schema::no_rules(settings); }
};

/// One VPL's term of Eq. 4.5 at vertex (x, n) with albedo, seen from `eye`.
template <typename T, glm::qualifier Q>
glm::vec<3, T, Q> lightwave_vpl_contribution(const glm::vec<3, T, Q>& x, const glm::vec<3, T, Q>& n, const glm::vec<3, T, Q>& albedo,
                                             const glm::vec<3, T, Q>& eye, const lightwave_vpl<T>& vpl,
                                             const lightwave_shading_settings<T>& settings) {
  // A VPL on the vertex itself has no direction to light it from (and normalize(0) is NaN).
  const glm::vec<3, T, Q> offset = vpl.position - x;
  if (!(glm::dot(offset, offset) > T(0))) return glm::vec<3, T, Q>(0);
  const glm::vec<3, T, Q> to_vpl = glm::normalize(offset);
  const T object_term = glm::max(T(0), glm::dot(n, to_vpl));
  const T light_term = lightwave_lobe(glm::dot(vpl.normal, -to_vpl));
  const T strength = glm::max(T(0), T(1) - vpl.attenuation);
  // Phong: the reflection of the incoming direction -to_vpl about n, against the view direction.
  const glm::vec<3, T, Q> reflected = -to_vpl - T(2) * glm::dot(n, -to_vpl) * n;
  const glm::vec<3, T, Q> to_eye = eye - x;
  const T mirror = glm::dot(to_eye, to_eye) > T(0) ? glm::max(T(0), glm::dot(reflected, glm::normalize(to_eye))) : T(0);
  // pow, not a loop of multiplies: this runs inside the loop over thousands of VPLs, and
  // llvmpipe caps the iterations of nested loops (65535 in total), past which the inner loop
  // silently stops (measured: 6485 VPLs x 16 multiplies gave 46% less light than the CPU).
  const T specular = object_term > T(0) ? settings.specular_strength * std::pow(mirror, T(settings.specular_exponent)) : T(0);
  return albedo * (object_term * light_term * strength) + glm::vec<3, T, Q>(specular);
}

/// The diffuse weight of one VPL at (x, n): Eq. 4.5 without the albedo and the specular term,
/// obj * light * max(0, 1 - attenuation). The accurate indirect shadows weight each VPL's shadow
/// lookup by it, so a VPL that is blocked removes the share of the light it brings.
template <typename T, glm::qualifier Q>
T lightwave_vpl_weight(const glm::vec<3, T, Q>& x, const glm::vec<3, T, Q>& n, const lightwave_vpl<T>& vpl) {
  const glm::vec<3, T, Q> offset = vpl.position - x;
  if (!(glm::dot(offset, offset) > T(0))) return T(0);
  const glm::vec<3, T, Q> to_vpl = glm::normalize(offset);
  const T object_term = glm::max(T(0), glm::dot(n, to_vpl));
  const T light_term = lightwave_lobe(glm::dot(vpl.normal, -to_vpl));
  const T strength = glm::max(T(0), T(1) - vpl.attenuation);
  return object_term * light_term * strength;
}

/// A point's place in a shadow map from its clip-space position there: (x, y, depth) in [0, 1]
/// and w = 1 when the point is in front of the map's camera and inside its frustum, else 0.
/// A point behind the camera (clip w <= 0) has no projection: dividing by a negative w mirrors it
/// into the map, where it finds an occluder that does not exist (the streaks of the integrated
/// shadows on open floor). Such a point, or one outside the map, does not vote.
template <typename T>
glm::vec<4, T> lightwave_map_coordinate(const glm::vec<4, T>& clip) {
  if (!(clip.w > T(0))) return glm::vec<4, T>(0);
  const glm::vec<3, T> coordinate = glm::vec<3, T>(clip) / clip.w * T(0.5) + T(0.5);
  const bool inside = coordinate.x >= T(0) && coordinate.y >= T(0) && coordinate.z >= T(0) && coordinate.x <= T(1) &&
                      coordinate.y <= T(1) && coordinate.z <= T(1);
  return glm::vec<4, T>(coordinate, inside ? T(1) : T(0));
}

/// How much a lookup in a map counts at its coordinate (lightwave_map_coordinate): 0 outside the
/// map, rising smoothly (smoothstep) to 1 within `margin` of the map's side from its border. The
/// accurate shadows blend a lookup towards "lit" by 1 - this, so that a map's frustum does not
/// draw its rectangle into a shadow that reaches past it.
template <typename T>
T lightwave_map_fade(const glm::vec<4, T>& coordinate, T margin) {
  const T border = glm::min(glm::min(coordinate.x, T(1) - coordinate.x), glm::min(coordinate.y, T(1) - coordinate.y));
  const T t = glm::clamp(border / margin, T(0), T(1));
  return coordinate.w * (t * t * (T(3) - T(2) * t));
}

/// How far the accurate shadows trust one map for a group of VPLs at x: the map is rendered from
/// one point of the group, whose visibility stands for the whole group's only while the group
/// looks small. 1 / (1 + theta^2), theta = 4 radius / |x - position| the group's angular
/// diameter (small-angle, radians), `group_radius` being its RMS radius (a disc's extent is about
/// twice its RMS radius): 1 for a group seen as a point, 1/2 at theta = 1. (With the diameter
/// taken as 2 RMS radii, one map for all of a room's VPLs still shadowed a corner it lights the
/// more: further from the one-bounce reference than no map, docs/lightwave-shadows.md.)
template <typename T>
T lightwave_group_confidence(const glm::vec<3, T>& x, const glm::vec<3, T>& group_position, T group_radius) {
  const glm::vec<3, T> offset = group_position - x;
  const T diameter = T(4) * group_radius;
  return T(1) / (T(1) + diameter * diameter / glm::max(glm::dot(offset, offset), T(1e-12)));
}

/// Eq. 4.5 summed over `count` VPLs from `fetch(int index) -> lightwave_vpl<T>`, divided by count.
/// GLSL twin: lightwave_vertex_indirect, with the VPLs from the including shader's
/// `lightwave_vpl lightwave_fetch_vpl(int index)` (define VPLKIT_LIGHTWAVE_FETCH first).
template <typename T, glm::qualifier Q, typename Fetch>
glm::vec<3, T, Q> lightwave_vertex_indirect(const glm::vec<3, T, Q>& x, const glm::vec<3, T, Q>& n, const glm::vec<3, T, Q>& albedo,
                                            const glm::vec<3, T, Q>& eye, Fetch&& fetch, int count,
                                            const lightwave_shading_settings<T>& settings) {
  glm::vec<3, T, Q> sum(0);
  for (int index = 0; index < count; ++index) sum += lightwave_vpl_contribution(x, n, albedo, eye, fetch(index), settings);
  return count > 0 ? sum / T(count) : sum;
}

/// Eq. 4.8 generalised: shadow lookups of the integrated technique with `steps` in-between
/// points on each of the C(maps, 2) pairs of maps: (steps + 2) * maps * (maps - 1) / 2.
constexpr int lightwave_integrated_shadow_count(int steps, int maps) { return (steps + 2) * (maps * (maps - 1) / 2); }

/// Lookup number `lookup` (0 .. steps + 1) on the line from a fragment's coordinate in map a to
/// its coordinate in map b (section 4.3): 0 is a's own coordinate, steps + 1 is b's, and the
/// in-between point s = 1 .. steps lies at t = s / (steps + 1) and is looked up in the nearer map
/// (a for t < 1/2, b from 1/2 on: "the first half in map a, the second in map b").
/// Returns (coordinate, 0 for map a or 1 for map b). GLSL twin: the same name.
template <typename T>
glm::vec<4, T> lightwave_integrated_step(const glm::vec<3, T>& coordinate_a, const glm::vec<3, T>& coordinate_b, int lookup, int steps) {
  const T t = T(lookup) / T(steps + 1);
  const glm::vec<3, T> coordinate = coordinate_a + (coordinate_b - coordinate_a) * t;
  return {coordinate, T(2 * lookup >= steps + 1 ? 1 : 0)};
}

/// Eq. 5.2, the "faked indirect" colour: direct * 0.5 * shadow + direct * (m - 0.5).
template <typename T, glm::qualifier Q>
glm::vec<3, T, Q> lightwave_faked_indirect(const glm::vec<3, T, Q>& direct, T shadow, T multiplier) {
  return direct * (T(0.5) * shadow) + direct * (multiplier - T(0.5));
}

/// Alg. 1, as docs/errata.md (LW-4) fixes it: the percentage of similarity of two images given as `count`
/// 8-bit channel values each: 100 * mean over channels of (min + 1) / (max + 1). (The printed
/// pseudo-code divides the larger by the smaller, which contradicts its own example: 200 against
/// 100 is "about 50% different" only as 101 / 201.) Identical images give 100.
inline double lightwave_similarity(const std::uint8_t* a, const std::uint8_t* b, std::size_t count) {
  if (count == 0) return 100.0;
  double similar = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    const double low = std::fmin(a[i], b[i]), high = std::fmax(a[i], b[i]);
    similar += (low + 1.0) / (high + 1.0);
  }
  return 100.0 * similar / static_cast<double>(count);
}

/// Eq. 5.3: rank = fps_gain / (100 - similarity_percent), Table 5.10's ranking value
/// (e.g. (161 - 55) / (100 - 98.563) = 73.76). Identical images (100%) rank infinitely high.
inline double lightwave_rank(double fps_gain, double similarity_percent) {
  return fps_gain / (100.0 - similarity_percent);
}

}  // namespace vplkit
