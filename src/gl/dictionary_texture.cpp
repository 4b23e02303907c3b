#include "gl/dictionary_texture.h"

#include "gl/shader.h"

namespace glint::gl {

DictionaryTexture::DictionaryTexture(const Dictionary& dictionary) : parameters_(dictionary.parameters()) {
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &texture_);
  glTextureStorage3D(texture_, 1, GL_R16F, parameters_.texelsPerDistribution, parameters_.numDistributions,
                     parameters_.numLevels);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
  glTextureSubImage3D(texture_, 0, 0, 0, 0, parameters_.texelsPerDistribution, parameters_.numDistributions,
                      parameters_.numLevels, GL_RED, GL_HALF_FLOAT, dictionary.halfTexels().data());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
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
