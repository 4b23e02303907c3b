// Scene textures as the real-time renderer samples them: decoded to linear floats (sRGB colour
// textures decoded per texel, as a GL_SRGB8_ALPHA8 texture is before filtering), a box-filtered
// mip chain (glGenerateTextureMipmap), and the texture's glTF sampler (scene::TextureSampler: repeat
// wrapping and trilinear filtering, GL_LINEAR_MIPMAP_LINEAR, unless the file says otherwise, as
// OpenGL 4.5 core, section 8.14, defines each) at the level of detail of the footprint, which the
// path tracer takes from its ray differentials where the rasteriser takes it from screen-space
// derivatives.
#pragma once

#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace glint::trace {

// GL_LINEAR on one level: bilinear filtering with repeat wrapping of width x height texels (rows
// from the top: uv (0, 0) is the first stored row, as glTF's top), texel centres at (i + 0.5) / size.
template <typename Texel>
Texel bilinearRepeat(const std::vector<Texel>& texels, int width, int height, glm::vec2 uv) {
  const float x = uv.x * static_cast<float>(width) - 0.5f;
  const float y = uv.y * static_cast<float>(height) - 0.5f;
  if (!std::isfinite(x) || !std::isfinite(y)) return texels.front();
  const float fx = std::floor(x);
  const float fy = std::floor(y);
  const float tx = x - fx;
  const float ty = y - fy;
  auto wrap = [](float i, int size) {
    const float m = std::fmod(i, static_cast<float>(size));
    return static_cast<int>(m < 0.0f ? m + static_cast<float>(size) : m) % size;
  };
  const int x0 = wrap(fx, width);
  const int x1 = (x0 + 1) % width;
  const int y0 = wrap(fy, height);
  const int y1 = (y0 + 1) % height;
  auto at = [&](int xx, int yy) { return texels[static_cast<std::size_t>(yy) * static_cast<std::size_t>(width) + static_cast<std::size_t>(xx)]; };
  return (1.0f - ty) * ((1.0f - tx) * at(x0, y0) + tx * at(x1, y0)) + ty * ((1.0f - tx) * at(x0, y1) + tx * at(x1, y1));
}

// One texel coordinate of `size` under a wrap mode (OpenGL 4.5 core, section 8.14.2).
int wrapTexel(int i, int size, scene::TextureSampler::Wrap mode);

// GL_NEAREST or GL_LINEAR on one level under the sampler's wrap modes.
glm::vec3 filteredTexel(const std::vector<glm::vec3>& texels, int width, int height, glm::vec2 uv,
                        const scene::TextureSampler& sampler, bool nearest);

// Throws Error naming the texture when its RGBA8 data does not hold width x height texels.
void requireTexelData(const scene::Texture& texture);

class MipTexture {
 public:
  explicit MipTexture(const scene::Texture& texture);
  // Linear float texels, rows from the top (normal-map moments, scene/normal_map_moments.h).
  MipTexture(int width, int height, std::vector<glm::vec3> texels);

  // RGB at uv with the footprint's uv derivatives (OpenGL 4.5 core, section 8.14: rho is the
  // longer of the two derivatives in texels, lambda = log2(rho); lambda <= 0 magnifies with
  // bilinear filtering of level 0).
  glm::vec3 sample(glm::vec2 uv, glm::vec2 duvdx, glm::vec2 duvdy) const;
  // Bilinear filtering of one level (nearest: the texel the uv falls in), under the sampler's wrap.
  glm::vec3 bilinear(int level, glm::vec2 uv, bool nearest = false) const;
  int levelCount() const { return static_cast<int>(levels_.size()); }
  // The level of detail sample() takes for these derivatives (log2 of the longer in texels).
  float levelOfDetail(glm::vec2 duvdx, glm::vec2 duvdy) const;

 private:
  struct Level {
    int width;
    int height;
    std::vector<glm::vec3> texels;  // rows from the top, as scene::Texture
  };
  std::vector<Level> levels_;
  scene::TextureSampler sampler_;

  void buildMipChain();
};

}  // namespace glint::trace
