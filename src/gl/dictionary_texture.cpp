#include "gl/dictionary_texture.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "gl/shader.h"
#include "glint/error.h"

namespace glint::gl {

namespace {

// A buffer texture over `values` (binary16 or float), `components` values a texel.
template <typename T>
void createBufferTexture(std::span<const T> values, int components, GLenum format, const char* what, GLuint& buffer,
                         GLuint& texture) {
  GLint maxTexels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
  const std::size_t texels = values.size() / static_cast<std::size_t>(components);
  if (static_cast<std::size_t>(maxTexels) < texels) {
    throw Error(std::string(what) + " of " + std::to_string(texels) +
                " texels exceeds this OpenGL's buffer texture limit (" + std::to_string(maxTexels) + " texels)");
  }
  glCreateBuffers(1, &buffer);
  glNamedBufferStorage(buffer, static_cast<GLsizeiptr>(values.size() * sizeof(T)), values.data(), 0);
  glCreateTextures(GL_TEXTURE_BUFFER, 1, &texture);
  glTextureBuffer(texture, format, buffer);
}

}  // namespace

DictionaryTexture::DictionaryTexture(const Dictionary& dictionary)
    : parameters_(dictionary.parameters()), numMips_(dictionary.numMips()), mipRowLength_(dictionary.mipRowLength()) {
  // Texel k of a distribution holds the pair (p[k], p[k+1]) (Dictionary::halfTexelPairs), so that
  // glintMarginal's linear interpolation costs one fetch instead of two: on llvmpipe the fetches
  // were about 40% of the glint shader's time (docs/benchmarks.md).
  const std::vector<std::uint16_t> pairs = dictionary.halfTexelPairs();
  // A buffer texture, not a texture array: llvmpipe's texelFetch on an array computes a mip level,
  // row and layer stride per pixel, about 100 instructions around each fetch; on a buffer it is a
  // bounds check and a gather (docs/benchmarks.md, "What made it fast, and why"). The mip chain
  // likewise: four values a texel, so that one fetch serves both levels of a filtered lookup.
  createBufferTexture(std::span<const std::uint16_t>(pairs), 2, GL_RG16F, "dictionary", buffer_, texture_);
  createBufferTexture(dictionary.filteredHalfTexels(), 4, GL_RGBA16F, "dictionary mip chain", mipBuffer_, mipTexture_);
  // The cumulative tables of glints under extended lights with each texel's pair, four 32-bit floats
  // a texel: one fetch an integral.
  createBufferTexture(dictionary.cumulativeTexels(), 4, GL_RGBA32F, "dictionary cumulative tables", cumulativeBuffer_,
                      cumulativeTexture_);
}

DictionaryTexture::~DictionaryTexture() {
  glDeleteTextures(1, &texture_);
  glDeleteBuffers(1, &buffer_);
  glDeleteTextures(1, &mipTexture_);
  glDeleteBuffers(1, &mipBuffer_);
  glDeleteTextures(1, &cumulativeTexture_);
  glDeleteBuffers(1, &cumulativeBuffer_);
}

void DictionaryTexture::bind(const ShaderProgram& program) const {
  glBindTextureUnit(0, texture_);
  glBindTextureUnit(10, mipTexture_);
  glBindTextureUnit(15, cumulativeTexture_);
  glUniform2i(program.uniform("uGlintDictionaryMips"), numMips_, mipRowLength_);
  glUniform3i(program.uniform("uGlintDictionaryShape"), parameters_.numLevels, parameters_.numDistributions,
              parameters_.texelsPerDistribution);
  glUniform1f(program.uniform("uGlintDictionaryAlpha"), parameters_.alpha);
}

}  // namespace glint::gl
