#include "trace/texture.h"

#include <algorithm>
#include <cmath>

#include "glint/error.h"
#include "glint/image_io.h"
#include "glint/kernel/normal_map_filtering.h"

namespace glint::trace {

void requireTexelData(const scene::Texture& texture) {
  if (texture.width < 1 || texture.height < 1 ||
      texture.rgba.size() != static_cast<std::size_t>(texture.width) * texture.height * 4) {
    throw Error("texture '" + texture.name + "': size and data do not agree");
  }
}

MipTexture::MipTexture(const scene::Texture& texture) {
  requireTexelData(texture);
  // 8-bit code values to linear floats, through a table (256 entries instead of one pow per texel).
  float decode[256];
  for (int i = 0; i < 256; ++i) {
    decode[i] = texture.srgb ? srgbToLinear(static_cast<float>(i) / 255.0f) : static_cast<float>(i) / 255.0f;
  }
  Level base{texture.width, texture.height, {}};
  base.texels.resize(static_cast<std::size_t>(texture.width) * texture.height);
  for (std::size_t i = 0; i < base.texels.size(); ++i) {
    base.texels[i] = {decode[texture.rgba[4 * i]], decode[texture.rgba[4 * i + 1]], decode[texture.rgba[4 * i + 2]]};
  }
  levels_.push_back(std::move(base));
  buildMipChain();
}

MipTexture::MipTexture(int width, int height, std::vector<glm::vec3> texels) {
  levels_.push_back(Level{width, height, std::move(texels)});
  buildMipChain();
}

void MipTexture::buildMipChain() {
  // Level k has max(1, floor(size / 2^k)) texels per axis, each the mean of the 2 x 2 texels
  // below it (the last row or column is repeated for odd sizes).
  while (levels_.back().width > 1 || levels_.back().height > 1) {
    const Level& below = levels_.back();
    Level level{std::max(1, below.width / 2), std::max(1, below.height / 2), {}};
    level.texels.resize(static_cast<std::size_t>(level.width) * level.height);
    for (int y = 0; y < level.height; ++y) {
      const int y0 = std::min(2 * y, below.height - 1);
      const int y1 = std::min(2 * y + 1, below.height - 1);
      for (int x = 0; x < level.width; ++x) {
        const int x0 = std::min(2 * x, below.width - 1);
        const int x1 = std::min(2 * x + 1, below.width - 1);
        auto at = [&](int xx, int yy) { return below.texels[static_cast<std::size_t>(yy) * below.width + xx]; };
        level.texels[static_cast<std::size_t>(y) * level.width + x] =
            0.25f * (at(x0, y0) + at(x1, y0) + at(x0, y1) + at(x1, y1));
      }
    }
    levels_.push_back(std::move(level));
  }
}

glm::vec3 MipTexture::bilinear(int levelIndex, glm::vec2 uv) const {
  const Level& level = levels_[static_cast<std::size_t>(levelIndex)];
  return bilinearRepeat(level.texels, level.width, level.height, uv);
}

float MipTexture::levelOfDetail(glm::vec2 duvdx, glm::vec2 duvdy) const {
  const glm::vec2 size(static_cast<float>(levels_.front().width), static_cast<float>(levels_.front().height));
  return kernel::glintTextureLevelOfDetail(duvdx, duvdy, size);
}

glm::vec3 MipTexture::sample(glm::vec2 uv, glm::vec2 duvdx, glm::vec2 duvdy) const {
  const float lambda = levelOfDetail(duvdx, duvdy);
  if (!(lambda > 0.0f)) return bilinear(0, uv);  // magnification, or no footprint
  const int last = levelCount() - 1;
  if (lambda >= static_cast<float>(last)) return bilinear(last, uv);
  const int level = static_cast<int>(std::floor(lambda));
  const float blend = lambda - static_cast<float>(level);
  return (1.0f - blend) * bilinear(level, uv) + blend * bilinear(level + 1, uv);
}

}  // namespace glint::trace
