#include "gl/dictionary_texture.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "gl/shader.h"
#include "glint/error.h"

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
  // A buffer texture, not a texture array: llvmpipe's texelFetch on an array computes a mip level,
  // row and layer stride per pixel, about 100 instructions around each fetch; on a buffer it is a
  // bounds check and a gather (docs/benchmarks.md, third round).
  GLint maxTexels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
  if (static_cast<std::size_t>(maxTexels) < halves.size()) {
    throw Error("dictionary of " + std::to_string(halves.size()) + " texels exceeds this OpenGL's buffer texture limit (" +
                std::to_string(maxTexels) + " texels)");
  }
  glCreateBuffers(1, &buffer_);
  glNamedBufferStorage(buffer_, static_cast<GLsizeiptr>(pairs.size() * sizeof(std::uint16_t)), pairs.data(), 0);
  glCreateTextures(GL_TEXTURE_BUFFER, 1, &texture_);
  glTextureBuffer(texture_, GL_RG16F, buffer_);
}

DictionaryTexture::~DictionaryTexture() {
  glDeleteTextures(1, &texture_);
  glDeleteBuffers(1, &buffer_);
}

void DictionaryTexture::bind(const ShaderProgram& program) const {
  glBindTextureUnit(0, texture_);
  glUniform3i(program.uniform("uGlintDictionaryShape"), parameters_.numLevels, parameters_.numDistributions,
              parameters_.texelsPerDistribution);
  glUniform1f(program.uniform("uGlintDictionaryAlpha"), parameters_.alpha);
}

}  // namespace glint::gl
