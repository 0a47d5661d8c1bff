#include "frontend/techniques/final_gather/final_gather_cpu_mirror.hpp"

#include <vplkit/final_gather.hpp>
#include <vplkit/shading.hpp>

#include "frontend/core/parallel.hpp"

namespace vplkit {

final_gather_images cpu_final_gather_shade(const final_gather_buffers& buffers, const final_gather_scene& source,
                                           const final_gather_settings& settings, int threads) {
  const final_gather_variant variant = find_final_gather_technique(settings.technique).variant;
  final_gather_images out;
  for (image* image : {&out.radiance, &out.indirect}) {
    image->width = settings.width;
    image->height = settings.height;
    image->texels.assign(static_cast<std::size_t>(settings.width) * static_cast<std::size_t>(settings.height), glm::vec4(0, 0, 0, 1));
  }
  const int m = settings.resolution, k = settings.environment_resolution;
  const auto fetch = [&](int face, int i, int j) { return buffers.small_cube.at(glm::ivec2(face * m + i, j)); };
  const auto row = [&](int y) {
    for (int x = 0; x < settings.width; ++x) {
      const glm::ivec2 pixel(x, y);
      const glm::vec4 position_kind = buffers.gbuffer[0].at(pixel);
      if (position_kind.w < 0.5f) continue;
      const glm::vec3 p(position_kind), n(buffers.gbuffer[1].at(pixel)), albedo(buffers.gbuffer[2].at(pixel));
      glm::vec3 indirect(0.0f);
      if (position_kind.w > 1.5f) {
        if (variant == final_gather_variant::environment_map) {
          const glm::ivec3 texel = cube_texel_of(n, k);
          indirect = glm::vec3(buffers.environment_map.at(glm::ivec2(texel.x * k + texel.y, texel.z)));
        } else if (variant == final_gather_variant::point) {
          indirect = final_gather_irradiance<gather_form_factor::point>(p, n, source.reference_point, m, fetch);
        } else {
          indirect = final_gather_irradiance<gather_form_factor::polygon>(p, n, source.reference_point, m, fetch);
        }
      }
      // The lights' shadowed direct irradiance, summed on the GPU (final_gather_direct.frag).
      const glm::vec3 direct(buffers.direct.at(pixel));
      out.radiance.at(pixel) = glm::vec4(diffuse_radiance(albedo, direct, 1.0f, indirect), 1.0f);
      out.indirect.at(pixel) = glm::vec4(indirect, 1.0f);
    }
  };
  parallel_for(settings.height, threads, row);
  return out;
}

}  // namespace vplkit
