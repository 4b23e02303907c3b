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
  sampler_ = texture.sampler;
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

int wrapTexel(int i, int size, scene::TextureSampler::Wrap mode) {
  switch (mode) {
    case scene::TextureSampler::Wrap::ClampToEdge: return std::clamp(i, 0, size - 1);
    case scene::TextureSampler::Wrap::MirroredRepeat: {
      // mirror(i) = i mod 2 size, folded back past size.
      const int period = 2 * size;
      const int m = ((i % period) + period) % period;
      return m < size ? m : period - 1 - m;
    }
    case scene::TextureSampler::Wrap::Repeat: break;
  }
  return ((i % size) + size) % size;
}

glm::vec3 filteredTexel(const std::vector<glm::vec3>& texels, int width, int height, glm::vec2 uv,
                        const scene::TextureSampler& sampler, bool nearest) {
  // A texel coordinate an int cannot hold (or not finite) reads the first texel, as bilinearRepeat
  // reads for a uv that is not finite; the loader keeps uv within 1e6, far below.
  constexpr float kLargest = 1e9f;
  const float x = uv.x * static_cast<float>(width) - (nearest ? 0.0f : 0.5f);
  const float y = uv.y * static_cast<float>(height) - (nearest ? 0.0f : 0.5f);
  if (!(std::abs(x) < kLargest && std::abs(y) < kLargest)) return texels.front();
  const float fx = std::floor(x);
  const float fy = std::floor(y);
  auto at = [&](float i, float j) {
    const int xx = wrapTexel(static_cast<int>(i), width, sampler.wrapS);
    const int yy = wrapTexel(static_cast<int>(j), height, sampler.wrapT);
    return texels[static_cast<std::size_t>(yy) * static_cast<std::size_t>(width) + static_cast<std::size_t>(xx)];
  };
  if (nearest) return at(fx, fy);
  const float tx = x - fx;
  const float ty = y - fy;
  return (1.0f - ty) * ((1.0f - tx) * at(fx, fy) + tx * at(fx + 1.0f, fy)) +
         ty * ((1.0f - tx) * at(fx, fy + 1.0f) + tx * at(fx + 1.0f, fy + 1.0f));
}

glm::vec3 MipTexture::bilinear(int levelIndex, glm::vec2 uv, bool nearest) const {
  const Level& level = levels_[static_cast<std::size_t>(levelIndex)];
  // glTF's default sampler takes the path every texture took before samplers were read.
  if (!nearest && sampler_.wrapS == scene::TextureSampler::Wrap::Repeat && sampler_.wrapT == scene::TextureSampler::Wrap::Repeat) {
    return bilinearRepeat(level.texels, level.width, level.height, uv);
  }
  return filteredTexel(level.texels, level.width, level.height, uv, sampler_, nearest);
}

float MipTexture::levelOfDetail(glm::vec2 duvdx, glm::vec2 duvdy) const {
  const glm::vec2 size(static_cast<float>(levels_.front().width), static_cast<float>(levels_.front().height));
  return kernel::glintTextureLevelOfDetail(duvdx, duvdy, size);
}

glm::vec3 MipTexture::sample(glm::vec2 uv, glm::vec2 duvdx, glm::vec2 duvdy) const {
  const float lambda = levelOfDetail(duvdx, duvdy);
  const bool nearest = sampler_.minifyNearest;
  // Magnification below c (section 8.14: 0.5 where a linear magnification meets a nearest-mipmap
  // minification, else 0), or no footprint.
  const float c = !sampler_.magnifyNearest && nearest && sampler_.mipmap != scene::TextureSampler::Mipmap::None ? 0.5f : 0.0f;
  if (!(lambda > c)) return bilinear(0, uv, sampler_.magnifyNearest);
  const int last = levelCount() - 1;
  switch (sampler_.mipmap) {
    case scene::TextureSampler::Mipmap::None: return bilinear(0, uv, nearest);
    case scene::TextureSampler::Mipmap::Nearest: {
      // The nearest level: ceil(lambda + 1/2) - 1 (section 8.14.3).
      const int level = lambda <= 0.5f ? 0 : std::min(last, static_cast<int>(std::ceil(lambda + 0.5f)) - 1);
      return bilinear(level, uv, nearest);
    }
    case scene::TextureSampler::Mipmap::Linear: break;
  }
  if (lambda >= static_cast<float>(last)) return bilinear(last, uv, nearest);
  const int level = static_cast<int>(std::floor(lambda));
  const float blend = lambda - static_cast<float>(level);
  return (1.0f - blend) * bilinear(level, uv, nearest) + blend * bilinear(level + 1, uv, nearest);
}

}  // namespace glint::trace
