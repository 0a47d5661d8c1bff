// GLSL twin of include/vplkit/voxel_visibility.hpp: the march of a conservative voxel occupancy
// grid from a receiver to a pixel light or a coarse light (a 3D DDA over every cell the segment
// passes through). The grid is the packed RGBA32UI texture of the C++ twin (128 cells along z per
// texel), read
// through `uvec4 voxel_fetch(ivec2 texel)`, which the including shader defines (e.g. texelFetch
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

ivec2 voxel_texel(ivec3 cell, ivec3 cells) { return ivec2(cell.x, cell.y + (cell.z >> 7) * cells.y); }

bool voxel_bit(uvec4 texel, int z) { return ((texel[(z >> 5) & 3] >> uint(z & 31)) & 1u) != 0u; }

float voxel_march_cells(ivec3 cells, vec3 u0, vec3 u1) {
  vec3 d = u1 - u0;
  vec3 size = vec3(cells);
  const float far_away = 1e30;
  float t_enter = 0.0;
  float t_exit = 1.0;
  vec3 inverse_d = vec3(far_away);
  for (int i = 0; i < 3; ++i) {
    if (abs(d[i]) > 1e-12) {
      inverse_d[i] = 1.0 / d[i];
      float ta = (0.0 - u0[i]) * inverse_d[i];
      float tb = (size[i] - u0[i]) * inverse_d[i];
      t_enter = max(t_enter, min(ta, tb));
      t_exit = min(t_exit, max(ta, tb));
    } else if (u0[i] < 0.0 || u0[i] > size[i]) {
      return 1.0;
    }
  }
  if (t_enter > t_exit) return 1.0;
  ivec3 cell = clamp(ivec3(floor(u0 + d * t_enter)), ivec3(0), cells - 1);
  ivec3 cell_step = ivec3(0);
  vec3 t_max = vec3(far_away);
  vec3 t_delta = vec3(far_away);
  for (int i = 0; i < 3; ++i) {
    if (abs(d[i]) > 1e-12) {
      cell_step[i] = d[i] > 0.0 ? 1 : -1;
      float boundary = float(cell[i] + (d[i] > 0.0 ? 1 : 0));
      t_max[i] = (boundary - u0[i]) * inverse_d[i];
      t_delta[i] = abs(inverse_d[i]);
    }
  }
  int steps = cells.x + cells.y + cells.z;
  for (int n = 0; n <= steps; ++n) {
    if (voxel_bit(voxel_fetch(voxel_texel(cell, cells)), cell.z)) return 0.0;
    int axis = 0;
    if (t_max.y < t_max[axis]) axis = 1;
    if (t_max.z < t_max[axis]) axis = 2;
    if (t_max[axis] > t_exit) break;
    cell[axis] += cell_step[axis];
    if (cell[axis] < 0 || cell[axis] >= cells[axis]) break;
    t_max[axis] += t_delta[axis];
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
  return voxel_march_cells(shape.cells, (from - shape.origin) * inverse_cell, (to - shape.origin) * inverse_cell);
}

float voxel_light_visible(voxel_grid_shape shape, voxel_march_settings settings, mat4 to_cells, vec3 x, vec3 n, vec3 xp, vec3 np) {
  vec3 to_light = xp - x;
  if (!(dot(n, to_light) > 0.0) || !(dot(np, to_light) < 0.0)) return 1.0;
  return voxel_march_cells(shape.cells, transform_point(to_cells, x + n * (settings.start_offset * shape.cell_size)),
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
