// The direct-light pipeline: a shadow map rendered from the spot light, then one shading pass
// of the camera view with spot_light_irradiance (shaders/lib/direct_light.glsl) times the
// shadow-map visibility. It is the walking skeleton the indirect techniques build on.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <vplkit/irradiance.hpp>

#include "frontend/gpu_timer.hpp"
#include "frontend/mesh_buffers.hpp"
#include "frontend/program.hpp"
#include "frontend/render_target.hpp"
#include "frontend/scene.hpp"

namespace vplkit {

struct direct_settings {
  int width = 512;               ///< final image width in pixels
  int height = 512;              ///< final image height in pixels
  int shadow_map_size = 1024;    ///< square shadow map resolution
  texel_format target_format = texel_format::rgba16f;  ///< radiance target (rgba16f or rgba32f)
  irradiance_settings<float> irradiance;                ///< distance clamp of the light term
};

/// Returns nullptr when the settings are usable, else a message naming the bad one.
const char* validate(const direct_settings& settings);

/// One rendered frame: linear radiance (RGBA, rows bottom-up) and the GPU time of each pass.
struct frame {
  int width = 0;
  int height = 0;
  std::vector<float> radiance;
  std::vector<pass_time> pass_times;
};

/// View-projection of the spot light's shadow map: a square frustum that holds the outer cone.
glm::mat4 light_view_projection(const spot_light<float>& light);
/// View-projection of the camera for an image of the given aspect ratio.
glm::mat4 camera_view_projection(const camera& view, float aspect);

class direct_renderer {
 public:
  /// Loads the programs and uploads the scene. Throws vplkit::error on bad settings, missing
  /// shaders or compile errors.
  direct_renderer(const shader_library& shaders, const scene& source, const direct_settings& settings);
  frame render();
  /// The radiance texture of the last frame.
  const texture_2d& output() const { return target_.colour(0); }

 private:
  scene scene_;
  direct_settings settings_;
  mesh_buffers mesh_;
  program shadow_program_;
  program shade_program_;
  framebuffer shadow_map_;
  framebuffer target_;
  gpu_timer timer_;
};

}  // namespace vplkit
