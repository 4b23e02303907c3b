#include "gl/dictionary_texture.h"

#include <cstdint>
#include <span>
#include <vector>

#include "gl/shader.h"

namespace glint::gl {

DictionaryTexture::DictionaryTexture(const Dictionary& dictionary) : parameters_(dictionary.parameters()) {
  // Texel k of a distribution holds the pair (p[k], p[k+1]), with p[R] = 0 (the marginal falls to
  // 0 at 4 sigma_d), so that glintMarginal's linear interpolation costs one fetch instead of two:
  // on llvmpipe the fetches were about 40% of the glint shader's time (docs/benchmarks.md).
  const std::span<const std::uint16_t> halves = dictionary.halfTexels();
  const std::size_t texels = static_cast<std::size_t>(parameters_.texelsPerDistribution);
  std::vector<std::uint16_t> pairs(2 * halves.size());
  for (std::size_t i = 0; i < halves.size(); ++i) {
    const bool lastOfDistribution = (i + 1) % texels == 0;
    pairs[2 * i] = halves[i];
    pairs[2 * i + 1] = lastOfDistribution ? std::uint16_t{0} : halves[i + 1];  // binary16 +0
  }
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &texture_);
  glTextureStorage3D(texture_, 1, GL_RG16F, parameters_.texelsPerDistribution, parameters_.numDistributions,
                     parameters_.numLevels);
  glTextureSubImage3D(texture_, 0, 0, 0, 0, parameters_.texelsPerDistribution, parameters_.numDistributions,
                      parameters_.numLevels, GL_RG, GL_HALF_FLOAT, pairs.data());
  // texelFetch ignores filtering; set it so the texture is complete on every driver.
  glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
}

DictionaryTexture::~DictionaryTexture() { glDeleteTextures(1, &texture_); }

void DictionaryTexture::bind(const ShaderProgram& program) const {
  glBindTextureUnit(0, texture_);
  glUniform3i(program.uniform("uGlintDictionaryShape"), parameters_.numLevels, parameters_.numDistributions,
              parameters_.texelsPerDistribution);
  glUniform1f(program.uniform("uGlintDictionaryAlpha"), parameters_.alpha);
}

}  // namespace glint::gl
