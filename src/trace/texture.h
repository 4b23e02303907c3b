// Scene textures as the real-time renderer samples them: decoded to linear floats (sRGB colour
// textures decoded per texel, as a GL_SRGB8_ALPHA8 texture is before filtering), a box-filtered
// mip chain (glGenerateTextureMipmap), repeat wrapping, and trilinear filtering
// (GL_LINEAR_MIPMAP_LINEAR) at the level of detail of the footprint, which the path tracer takes
// from its ray differentials where the rasteriser takes it from screen-space derivatives.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace glint::trace {

class MipTexture {
 public:
  explicit MipTexture(const scene::Texture& texture);

  // RGB at uv with the footprint's uv derivatives (OpenGL 4.5 core, section 8.14: rho is the
  // longer of the two derivatives in texels, lambda = log2(rho); lambda <= 0 magnifies with
  // bilinear filtering of level 0).
  glm::vec3 sample(glm::vec2 uv, glm::vec2 duvdx, glm::vec2 duvdy) const;
  // Bilinear filtering of one level.
  glm::vec3 bilinear(int level, glm::vec2 uv) const;
  int levelCount() const { return static_cast<int>(levels_.size()); }

 private:
  struct Level {
    int width;
    int height;
    std::vector<glm::vec3> texels;  // rows from the top, as scene::Texture
  };
  std::vector<Level> levels_;
};

}  // namespace glint::trace
