#include "frontend/techniques/rsm/rsm_cpu_mirror.hpp"

#include "frontend/core/error.hpp"
#include "frontend/core/parallel.hpp"

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include <vplkit/cube_map.hpp>
#include <vplkit/rsm_coarse_visibility.hpp>
#include <vplkit/direct_light.hpp>
#include <vplkit/shading.hpp>
#include <vplkit/transform.hpp>

namespace vplkit {
namespace {

// What the gather reads: the decoded RSM and, with coverage, the coarse lights read back.
struct gather_inputs {
  const std::vector<rsm_texel<float>>& rsm;
  int rsm_width;
  const std::vector<coarse_light<float>>& coarse;
  int blocks;
  const voxel_grid* voxels;  ///< rsm-voxel's grid (null otherwise)
  const cube_face_rsms* cube;  ///< a point light's six RSMs for the coarse lights' visibility (null: unoccluded)
};

template <rsm_pattern Pattern, rsm_visibility Visibility>
glm::vec3 gather_variant(const gather_receiver<float>& receiver, const gather_inputs& in, const rsm_frame_constants& constants) {
  const auto fetch = [&](glm::ivec2 texel) {
    return in.rsm[static_cast<std::size_t>(texel.y) * static_cast<std::size_t>(in.rsm_width) + static_cast<std::size_t>(texel.x)];
  };
  const auto coarse_fetch = [&](glm::ivec2 block) {
    return in.coarse[static_cast<std::size_t>(block.y) * static_cast<std::size_t>(in.blocks) + static_cast<std::size_t>(block.x)];
  };
  if constexpr (Visibility == rsm_visibility::voxel) {
    // gather.frag's rsm_voxel_visibility and rsm_voxel_coarse_visibility: the grid's march, by the same matrix.
    voxel_rsm_visibility<float, voxel_grid_fetch> visibility{voxel_grid_fetch{in.voxels}, in.voxels->shape, constants.voxel_march,
                                                             voxel_cells_from(in.voxels->shape, constants.light_view_inverse)};
    if (in.coarse.empty()) return gather_rsm_with<Pattern>(receiver, fetch, constants.gather, visibility);
    return gather_rsm_with<Pattern>(receiver, fetch, coarse_fetch, constants.gather, visibility);
  } else {
    if (in.coarse.empty()) return gather_rsm<Pattern, Visibility>(receiver, fetch, constants.gather);
    if (!in.cube) return gather_rsm<Pattern, Visibility>(receiver, fetch, coarse_fetch, constants.gather);
    // gather.frag's rsm_face_depth: the packed texel's first word, the eye-space depth's bits.
    const auto face_depth = [&](int face, glm::ivec2 texel) {
      const packed_rsm& rsm = in.cube->faces[static_cast<std::size_t>(face)];
      return float_from_bits(rsm.texels[static_cast<std::size_t>(texel.y) * static_cast<std::size_t>(rsm.width) + static_cast<std::size_t>(texel.x)].x);
    };
    const auto coarse_visibility = [&](const glm::vec3& x, const glm::vec3& x_c) {
      return coarse_light_cube_visibility(x, x_c, in.cube->frames, constants.unprojection, constants.gather.rsm_size, face_depth);
    };
    return gather_rsm<Pattern, Visibility>(receiver, fetch, coarse_fetch, coarse_visibility, constants.gather);
  }
}

glm::vec3 gather_dispatch(const gather_receiver<float>& receiver, const gather_inputs& in, const rsm_frame_constants& constants) {
  const rsm_technique& technique = constants.technique;
  if (technique.pattern == rsm_pattern::disk) return gather_variant<rsm_pattern::disk, rsm_visibility::none>(receiver, in, constants);
  switch (technique.visibility) {
    case rsm_visibility::none: return gather_variant<rsm_pattern::radial, rsm_visibility::none>(receiver, in, constants);
    case rsm_visibility::alg2: return gather_variant<rsm_pattern::radial, rsm_visibility::alg2>(receiver, in, constants);
    case rsm_visibility::alg3: return gather_variant<rsm_pattern::radial, rsm_visibility::alg3>(receiver, in, constants);
    case rsm_visibility::alg6: return gather_variant<rsm_pattern::radial, rsm_visibility::alg6>(receiver, in, constants);
    case rsm_visibility::alg6_ray: return gather_variant<rsm_pattern::radial, rsm_visibility::alg6_ray>(receiver, in, constants);
    case rsm_visibility::voxel: return gather_variant<rsm_pattern::radial, rsm_visibility::voxel>(receiver, in, constants);
  }
  return glm::vec3(0.0f);
}

struct filter_taps {
  const image& values;
  const rsm_pass_buffers& buffers;
  const rsm_frame_constants& constants;
  bilateral_tap<float> operator()(glm::ivec2 texel) const {
    const glm::vec4 value = values.at(texel);
    return {glm::vec3(value), value.w, glm::vec3(buffers.gbuffer[2].at(gbuffer_texel_of(texel, constants)))};
  }
};

}  // namespace

glm::ivec2 gbuffer_texel_of(glm::ivec2 texel, const rsm_frame_constants& constants) {
  return glm::min(texel * constants.indirect_divisor, constants.image_size - 1);
}

std::optional<gather_receiver<float>> gather_receiver_at(glm::ivec2 texel, const rsm_pass_buffers& buffers, const rsm_frame_constants& constants) {
  const glm::ivec2 sample = gbuffer_texel_of(texel, constants);
  const glm::vec4 position_depth = buffers.gbuffer[0].at(sample);
  if (!(position_depth.w < 0.0f)) return std::nullopt;
  return make_gather_receiver(glm::vec3(position_depth), glm::vec3(buffers.gbuffer[2].at(sample)), constants.light.view,
                              constants.light.view_projection, constants.gather.rsm_size, glm::uvec2(texel));
}

// Decoded once per texel instead of once per sample: the same arithmetic, so the same values.
std::vector<rsm_texel<float>> unpack_rsm(const rsm_pass_buffers& buffers, const rsm_frame_constants& constants) {
  const packed_rsm& rsm = buffers.rsm;
  std::vector<rsm_texel<float>> texels(rsm.texels.size());
  for (int y = 0; y < rsm.height; ++y)
    for (int x = 0; x < rsm.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(rsm.width) + static_cast<std::size_t>(x);
      texels[i] = unpack_rsm_texel(rsm.texels[i], glm::ivec2(x, y), constants.unprojection);
    }
  return texels;
}

std::array<image, 3> cpu_coarse_pass(const rsm_pass_buffers& buffers, const rsm_frame_constants& constants, int threads) {
  const int blocks = constants.gather.coverage_blocks;
  std::array<image, 3> out{image(blocks, blocks), image(blocks, blocks), image(blocks, blocks)};
  const std::vector<rsm_texel<float>> rsm = unpack_rsm(buffers, constants);
  const auto fetch = [&](glm::ivec2 texel) {
    return rsm[static_cast<std::size_t>(texel.y) * static_cast<std::size_t>(buffers.rsm.width) + static_cast<std::size_t>(texel.x)];
  };
  parallel_for(blocks, threads, [&](int y) {
    for (int x = 0; x < blocks; ++x) {
      const coarse_light<float> light = reduce_rsm_block<float>(glm::ivec2(x, y), blocks, constants.gather.rsm_size, fetch);
      out[0].at(x, y) = glm::vec4(light.position, light.extent);
      out[1].at(x, y) = glm::vec4(light.normal, 0.0f);
      out[2].at(x, y) = glm::vec4(light.flux, 0.0f);
    }
  });
  return out;
}

std::vector<coarse_light<float>> coarse_lights_of(const rsm_pass_buffers& buffers) {
  std::vector<coarse_light<float>> lights(buffers.coarse[0].texels.size());
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const glm::vec4 position_extent = buffers.coarse[0].texels[i];
    lights[i] = {glm::vec3(position_extent), glm::vec3(buffers.coarse[1].texels[i]), glm::vec3(buffers.coarse[2].texels[i]), position_extent.w};
  }
  return lights;
}

std::optional<cube_face_rsms> read_cube_faces(const rsm_pipeline& pipeline, std::size_t view) {
  const std::optional<coarse_cube_views> cube = pipeline.coarse_cube(view);
  if (!cube) return std::nullopt;
  cube_face_rsms out;
  out.frames = cube->frames;
  for (std::size_t g = 0; g < 6; ++g) out.faces[g] = pipeline.read_buffers(cube->view_of_face[g]).rsm;
  return out;
}

image cpu_gather_pass(const rsm_pass_buffers& buffers, const rsm_frame_constants& constants, int threads, const cube_face_rsms* cube) {
  image out;
  out.width = constants.indirect_size.x;
  out.height = constants.indirect_size.y;
  out.texels.assign(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height), glm::vec4(0.0f));
  const std::vector<rsm_texel<float>> rsm = unpack_rsm(buffers, constants);
  const std::vector<coarse_light<float>> coarse = coarse_lights_of(buffers);
  if (constants.technique.visibility == rsm_visibility::voxel && !buffers.voxels) throw error("cpu_gather_pass: rsm-voxel's buffers hold no voxel grid");
  for (std::size_t g = 0; cube && g < 6; ++g)
    if (cube->faces[g].width != constants.gather.rsm_size.x || cube->faces[g].height != constants.gather.rsm_size.y)
      throw error("cpu_gather_pass: cube face " + std::to_string(g) + "'s RSM is not the gather's size");
  const gather_inputs in{rsm, buffers.rsm.width, coarse, buffers.coarse[0].width, buffers.voxels.get(), cube};
  parallel_tiles(out.width, out.height, threads, [&](int x, int y) {
    const glm::ivec2 texel(x, y);
    const std::optional<gather_receiver<float>> receiver = gather_receiver_at(texel, buffers, constants);
    if (!receiver) return;
    out.at(texel) = glm::vec4(gather_dispatch(*receiver, in, constants), buffers.gbuffer[0].at(gbuffer_texel_of(texel, constants)).w);
  });
  return out;
}

image cpu_temporal_pass(const image& indirect, const image& history, const rsm_pipeline::temporal_inputs& inputs, const rsm_pass_buffers& buffers,
                        const rsm_frame_constants& constants, int threads) {
  image out(indirect.width, indirect.height);
  const glm::ivec2 size = constants.indirect_size;
  parallel_for(out.height, threads, [&](int y) {
    for (int x = 0; x < out.width; ++x) {
      const glm::vec4 current = indirect.at(x, y);
      if (!(current.w < 0.0f)) continue;  // no surface here
      neighbourhood_moments<float> moments;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const glm::ivec2 neighbour(x + dx, y + dy);
          if (neighbour.x < 0 || neighbour.y < 0 || neighbour.x >= size.x || neighbour.y >= size.y) continue;
          const glm::vec4 value = indirect.at(neighbour);
          if (value.w < 0.0f) neighbourhood_add(moments, glm::vec3(value));
        }
      const glm::vec3 world(buffers.gbuffer[0].at(gbuffer_texel_of(glm::ivec2(x, y), constants)));
      const float expected = transform_point(inputs.previous_view, world).z;
      bool valid = false;
      glm::vec3 previous_value(0.0f);
      if (inputs.history_valid && expected < 0.0f) {
        const glm::vec2 previous = map_coordinate(inputs.previous_view_projection, world, size);
        if (previous.x >= 0.0f && previous.y >= 0.0f && previous.x < static_cast<float>(size.x) && previous.y < static_cast<float>(size.y)) {
          const glm::vec4 stored = history.at(glm::ivec2(glm::floor(previous)));
          valid = temporal_history_matches(expected, stored.w, constants.temporal);
          previous_value = glm::vec3(stored);
        }
      }
      out.at(x, y) = glm::vec4(temporal_resolve(glm::vec3(current), previous_value, valid, moments, constants.temporal), current.w);
    }
  });
  return out;
}

image cpu_blur_x_pass(const image& indirect, const rsm_pass_buffers& buffers,
                             const rsm_frame_constants& constants, int threads) {
  image out;
  out.width = indirect.width;
  out.height = indirect.height;
  out.texels.assign(indirect.texels.size(), glm::vec4(0.0f));
  const filter_taps taps{indirect, buffers, constants};
  parallel_for(out.height, threads, [&](int y) {
    for (int x = 0; x < out.width; ++x) {
      const bilateral_tap<float> centre = taps(glm::ivec2(x, y));
      if (!(centre.depth < 0.0f)) continue;
      out.at(glm::ivec2(x, y)) = glm::vec4(
          bilateral_filter_axis(glm::vec2(x, y) + 0.5f, centre.depth, centre.normal, taps, constants.indirect_size, 0, constants.bilateral),
          centre.depth);
    }
  });
  return out;
}

post_images cpu_post_pass(const image& filtered_input, const rsm_pass_buffers& buffers,
                          const rsm_frame_constants& constants, int threads) {
  post_images out;
  for (image* image : {&out.radiance, &out.indirect}) {
    image->width = constants.image_size.x;
    image->height = constants.image_size.y;
    image->texels.assign(static_cast<std::size_t>(image->width) * static_cast<std::size_t>(image->height), glm::vec4(0, 0, 0, 1));
  }
  const filter_taps taps{filtered_input, buffers, constants};
  const bool separable = constants.filter == post_filter::separable;
  // Pass 4b (blur_y.frag): the y axis of the 2 x 2 pixels of each indirect texel, from their
  // G-buffer depths and normals (clamped to the image, as the shader does).
  image quad_filtered;
  const bool quad = constants.technique.indirect && separable && constants.indirect_divisor == 2;
  if (quad) {
    quad_filtered = image(constants.image_size.x, constants.image_size.y);
    parallel_for(constants.indirect_size.y, threads, [&](int y) {
      for (int x = 0; x < constants.indirect_size.x; ++x) {
        const glm::ivec2 texel(x, y);
        std::array<float, 4> depth;
        std::array<glm::vec3, 4> normal;
        for (int s = 0; s < 4; ++s) {
          const glm::ivec2 pixel = glm::min(2 * texel + glm::ivec2(s & 1, s >> 1), constants.image_size - 1);
          depth[static_cast<std::size_t>(s)] = buffers.gbuffer[0].at(pixel).w;
          normal[static_cast<std::size_t>(s)] = glm::vec3(buffers.gbuffer[2].at(pixel));
        }
        const std::array<glm::vec3, 4> filtered = bilateral_filter_axis_quad(texel, depth, normal, taps, constants.indirect_size, 1, constants.bilateral);
        for (int s = 0; s < 4; ++s) {
          const glm::ivec2 pixel = 2 * texel + glm::ivec2(s & 1, s >> 1);
          if (pixel.x < constants.image_size.x && pixel.y < constants.image_size.y)
            quad_filtered.at(pixel) = glm::vec4(filtered[static_cast<std::size_t>(s)], 0.0f);
        }
      }
    });
  }
  parallel_for(constants.image_size.y, threads, [&](int y) {
    for (int x = 0; x < constants.image_size.x; ++x) {
      const glm::ivec2 pixel(x, y);
      const glm::vec4 position_depth = buffers.gbuffer[0].at(pixel);
      if (!(position_depth.w < 0.0f)) continue;
      const glm::vec4 albedo_density = buffers.gbuffer[1].at(pixel);
      const glm::vec3 n(buffers.gbuffer[2].at(pixel));
      glm::vec3 indirect(0.0f);
      if (constants.technique.indirect) {
        const glm::vec2 centre = (glm::vec2(pixel) + 0.5f) / static_cast<float>(constants.indirect_divisor);
        indirect = quad        ? glm::vec3(quad_filtered.at(pixel))
                   : separable ? bilateral_filter_axis(centre, position_depth.w, n, taps, constants.indirect_size, 1, constants.bilateral)
                               : bilateral_filter(centre, position_depth.w, n, taps, constants.indirect_size, constants.bilateral);
      }
      glm::vec3 direct(0.0f);
      if (constants.primary.kind == light_kind::spot)
        direct = spot_light_irradiance(glm::vec3(position_depth), n, constants.primary.spot, constants.gather.irradiance);
      else if (constants.primary.kind == light_kind::directional)
        direct = directional_light_irradiance(n, constants.primary.directional);
      else if (cube_face_of(glm::vec3(position_depth) - constants.primary.point.position) == constants.face)  // the face this view draws
        direct = point_light_irradiance(glm::vec3(position_depth), n, constants.primary.point, constants.gather.irradiance);
      out.radiance.at(pixel) =
          glm::vec4(diffuse_radiance(glm::vec3(albedo_density), direct, albedo_density.w, indirect), 1.0f);
      out.indirect.at(pixel) = glm::vec4(indirect, 1.0f);
    }
  });
  return out;
}

}  // namespace vplkit
