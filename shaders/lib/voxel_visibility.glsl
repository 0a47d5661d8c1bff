// GLSL twin of include/vplkit/voxel_visibility.hpp: the march of a conservative voxel occupancy
// grid from a receiver to a pixel light or a coarse light (a 3D DDA over every cell the segment
// passes through, a word of 32 cells at a time along its major axis). The grid is the packed
// RGBA32UI texture of the C++ twin (three copies side by side, 128 cells per texel along x, y and
// z respectively: voxel_texel_along), read through `uvec4 voxel_fetch(ivec2 texel)`, which the including shader defines (e.g. texelFetch
// on a usampler2D; the prototype is declared here: Mesa's linker wants every declared function
// that a compiled function calls defined).
// The gather's runs of samples that share one march (voxel_march_settings::group) are
// lib/rsm_gather.glsl's rsm_sample_group.
#ifndef VPLKIT_VOXEL_VISIBILITY_GLSL
#define VPLKIT_VOXEL_VISIBILITY_GLSL

#include "lib/transform.glsl"

uvec4 voxel_fetch(ivec2 texel);

struct voxel_march_settings {
  float start_offset;
  float end_offset;
  int group;
};

struct voxel_grid_shape {
  vec3 origin;
  float cell_size;
  ivec3 cells;
};

ivec3 voxel_axes_along(int axis, ivec3 v) { return axis == 0 ? v.yzx : (axis == 1 ? v.zxy : v); }

vec3 voxel_axes_along(int axis, vec3 v) { return axis == 0 ? v.yzx : (axis == 1 ? v.zxy : v); }

int voxel_copy_offset(int axis, ivec3 cells) { return axis == 2 ? 0 : (axis == 0 ? cells.x : cells.x + cells.y); }

ivec2 voxel_texel_along(int offset, ivec3 cell, ivec3 cells) { return ivec2(offset + cell.x, cell.y + (cell.z >> 7) * cells.y); }

const int voxel_cells_per_word = 32;

float voxel_march_words(ivec3 grid_cells, vec3 from, vec3 to) {
  vec3 extent = abs(to - from);
  int major = 2;
  if (extent.x > extent[major]) major = 0;
  if (extent.y > extent[major]) major = 1;
  int offset = voxel_copy_offset(major, grid_cells);
  ivec3 cells = voxel_axes_along(major, grid_cells);
  vec3 u0 = voxel_axes_along(major, from);
  vec3 d = voxel_axes_along(major, to) - u0;
  vec3 size = vec3(cells);
  const float far_away = 1e30;
  bvec3 moving = greaterThan(abs(d), vec3(1e-12));
  vec3 inverse_d = mix(vec3(far_away), vec3(1.0) / mix(vec3(1.0), d, moving), moving);
  vec3 ta = (vec3(0.0) - u0) * inverse_d;
  vec3 tb = (size - u0) * inverse_d;
  vec3 t_low = mix(vec3(-far_away), min(ta, tb), moving);
  vec3 t_high = mix(vec3(far_away), max(ta, tb), moving);
  vec3 parallel = vec3(1.0) - vec3(moving);
  float blocked = dot(parallel, vec3(lessThan(u0, vec3(0.0))) + vec3(greaterThan(u0, size)));
  float t_enter = max(0.0, max(t_low.x, max(t_low.y, t_low.z)));
  float t_exit = min(1.0, min(t_high.x, min(t_high.y, t_high.z)));
  if (t_enter > t_exit || blocked > 0.0) return 1.0;
  ivec3 cell = clamp(ivec3(floor(u0 + d * t_enter)), ivec3(0), cells - 1);
  int z_from = cell.z;
  cell.z = cell.z >> 5;
  vec3 side = vec3(1.0, 1.0, float(voxel_cells_per_word));
  ivec3 cell_step = ivec3(sign(d)) * ivec3(moving);
  vec3 boundary = vec3(cell + ivec3(greaterThan(d, vec3(0.0)))) * side;
  vec3 t_max = mix(vec3(far_away), (boundary - u0) * inverse_d, moving);
  vec3 t_delta = mix(vec3(far_away), abs(inverse_d) * side, moving);
  ivec3 limit = ivec3(cells.x, cells.y, (cells.z + voxel_cells_per_word - 1) >> 5);
  int steps = limit.x + limit.y + limit.z;
  for (int n = 0; n <= steps; ++n) {
    int axis = 0;
    if (t_max.y < t_max[axis]) axis = 1;
    if (t_max.z < t_max[axis]) axis = 2;
    int z_to = int(floor(u0.z + d.z * min(t_max[axis], t_exit)));
    int base = cell.z << 5;
    int low = clamp(min(z_from, z_to) - base, 0, 31);
    int high = clamp(max(z_from, z_to) - base, 0, 31);
    uint mask = (~0u << uint(low)) & (~0u >> uint(31 - high));
    if ((voxel_fetch(voxel_texel_along(offset, ivec3(cell.x, cell.y, base), cells))[cell.z & 3] & mask) != 0u) return 0.0;
    if (t_max[axis] > t_exit) break;
    cell[axis] += cell_step[axis];
    if (cell[axis] < 0 || cell[axis] >= limit[axis]) break;
    t_max[axis] += t_delta[axis];
    z_from = z_to;
  }
  return 1.0;
}

mat4 voxel_cells_from(voxel_grid_shape shape, mat4 to_world) {
  mat4 to_cells = mat4(1.0 / shape.cell_size);
  to_cells[3] = vec4(-shape.origin / shape.cell_size, 1.0);
  return to_cells * to_world;
}

float voxel_segment_visible(voxel_grid_shape shape, vec3 from, vec3 to) {
  float inverse_cell = 1.0 / shape.cell_size;
  return voxel_march_words(shape.cells, (from - shape.origin) * inverse_cell, (to - shape.origin) * inverse_cell);
}

float voxel_light_visible(voxel_grid_shape shape, voxel_march_settings settings, mat4 to_cells, vec3 x, vec3 n, vec3 xp, vec3 np) {
  vec3 to_light = xp - x;
  if (!(dot(n, to_light) > 0.0) || !(dot(np, to_light) < 0.0)) return 1.0;
  return voxel_march_words(shape.cells, transform_point(to_cells, x + n * (settings.start_offset * shape.cell_size)),
                           transform_point(to_cells, xp + np * (settings.end_offset * shape.cell_size)));
}

float voxel_light_visible(voxel_grid_shape shape, voxel_march_settings settings, vec3 x, vec3 n, vec3 xp, vec3 np) {
  return voxel_light_visible(shape, settings, voxel_cells_from(shape, mat4(1.0)), x, n, xp, np);
}

float voxel_coarse_light_visible(voxel_grid_shape shape, voxel_march_settings settings, mat4 to_cells, vec3 x, vec3 n, vec3 xc, vec3 nc) {
  float length_nc = sqrt(dot(nc, nc));
  if (!(length_nc > 0.0)) return 1.0;
  return voxel_light_visible(shape, settings, to_cells, x, n, xc, nc / length_nc);
}

#endif
