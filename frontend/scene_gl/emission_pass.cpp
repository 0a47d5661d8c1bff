#include "frontend/scene_gl/emission_pass.hpp"

#include <string>

#include "frontend/core/error.hpp"
#include "frontend/gl/debug_output.hpp"

namespace vplkit {

emission_pass::emission_pass(const shader_library& shaders)
    : program_(load_program(shaders, "scene.vert", "emission.frag")), framebuffer_(generate_framebuffer()) {}

void emission_pass::draw(const mesh_buffers& mesh, const glm::mat4& view_projection, const glm::vec3& eye, const texture_2d& radiance,
                         const texture_2d& depth) const {
  if (depth.width() != radiance.width() || depth.height() != radiance.height() || depth.format() != texel_format::depth32f)
    throw error("the emission pass needs a depth32f depth of the radiance's " + std::to_string(radiance.width()) + "x" +
                std::to_string(radiance.height()) + " pixels");
  // The family's own textures, attached for this pass: the emitters are tested against the depth
  // it drew (not written), their emission added to its radiance.
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, radiance.id(), 0);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth.id(), 0);
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) throw error("the emission pass's framebuffer is incomplete (glCheckFramebufferStatus " + std::to_string(status) + ")");
  const GLenum colour = GL_COLOR_ATTACHMENT0;
  glDrawBuffers(1, &colour);
  glViewport(0, 0, radiance.width(), radiance.height());
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_EQUAL);
  glDepthMask(GL_FALSE);
  glDisable(GL_CULL_FACE);  // the back of an emitter is the shader's to leave out (its normal's side)
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE);  // radiance adds, alpha stays
  program_.set("view_projection", view_projection);
  program_.set("eye", eye);
  mesh.draw_emissive(program_);
  glDisable(GL_BLEND);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_DEPTH_TEST);
  // Detached, so that the family's textures are not left attached to a second framebuffer.
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, 0, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  check_gl("drawing the emissive surfaces");
}

}  // namespace vplkit
