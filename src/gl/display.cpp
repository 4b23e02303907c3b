#include "gl/display.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace glint::gl {

DisplayPass::DisplayPass() : program_({{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "display.frag"}}) {
  glCreateVertexArrays(1, &vertexArray_);
}

DisplayPass::~DisplayPass() { glDeleteVertexArrays(1, &vertexArray_); }

void DisplayPass::draw(GLuint radiance, float exposure, int width, int height) const {
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  // Dithering, on by default, may perturb the conversion to 8 bits; the code values are exact.
  glDisable(GL_DITHER);
  glUseProgram(program_.id());
  glUniform1f(program_.uniform("uExposure"), exposure);
  glBindTextureUnit(0, radiance);
  glBindVertexArray(vertexArray_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

ImageRgb8 DisplayPass::encode(const ImageRgbF& radiance, float exposure) const {
  const int width = radiance.width;
  const int height = radiance.height;
  // Uploaded bottom row first, as the renderer leaves its frames.
  std::vector<float> rgb(static_cast<std::size_t>(width) * height * 3);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const glm::vec3& p = radiance.at(x, height - 1 - y);
      float* out = &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
      out[0] = p.r;
      out[1] = p.g;
      out[2] = p.b;
    }
  }
  GLuint source = 0;
  GLuint target = 0;
  GLuint framebuffer = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &source);
  glTextureStorage2D(source, 1, GL_RGBA32F, width, height);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(source, 0, 0, 0, width, height, GL_RGB, GL_FLOAT, rgb.data());
  glCreateTextures(GL_TEXTURE_2D, 1, &target);
  glTextureStorage2D(target, 1, GL_RGBA8, width, height);
  glCreateFramebuffers(1, &framebuffer);
  glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, target, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  draw(source, exposure, width, height);
  ImageRgb8 image = readFramebufferRgb8(width, height);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteFramebuffers(1, &framebuffer);
  glDeleteTextures(1, &target);
  glDeleteTextures(1, &source);
  return image;
}

ImageRgb8 readFramebufferRgb8(int width, int height) {
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(width) * height * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
  ImageRgb8 image(width, height, {0, 0, 0});
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::uint8_t* p = &rgb[(static_cast<std::size_t>(height - 1 - y) * width + x) * 3];
      image.at(x, y) = {p[0], p[1], p[2]};
    }
  }
  return image;
}

}  // namespace glint::gl
