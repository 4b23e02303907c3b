// The display pass: a frame's linear radiance to 8-bit sRGB on the GPU (shaders/display.frag, the
// transform of kernel/tonemap.h). The viewer's window and `glint render`'s PNG images both go
// through it, so that the window shows the image's very bytes: the CPU's displayEncode
// (glint/image_io.h) computes the same transform, but its pow differs from the GPU's in the last
// bits, which moves a value on a rounding boundary by one level. Needs a current context.
#pragma once

#include <glad/gl.h>

#include "gl/shader.h"
#include "glint/image.h"
#include "glint/image_io.h"

namespace glint::gl {

class DisplayPass {
 public:
  DisplayPass();
  ~DisplayPass();
  DisplayPass(const DisplayPass&) = delete;
  DisplayPass& operator=(const DisplayPass&) = delete;

  // Draws the radiance texture (RGBA float, rows bottom-up, as Renderer::radianceTexture), texel
  // for pixel, into the bound draw framebuffer's `width` x `height` viewport.
  void draw(GLuint radiance, float exposure, int width, int height) const;
  // The image as displayed: through draw() into an 8-bit framebuffer and read back.
  ImageRgb8 encode(const ImageRgbF& radiance, float exposure) const;

 private:
  ShaderProgram program_;
  GLuint vertexArray_ = 0;
};

// The bound read framebuffer's lower-left `width` x `height` pixels (8-bit RGB), top row first.
ImageRgb8 readFramebufferRgb8(int width, int height);

}  // namespace glint::gl
