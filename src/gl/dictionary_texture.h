// The dictionary on the GPU: an RG16F buffer texture indexed (level * N + distribution) * R + k,
// texel k holding the pair of neighbours (p[k], p[k+1]) that linear interpolation needs: the very
// binary16 values the CPU evaluates (docs/dictionary.md, "Storage"); and its mip chain for
// anti-aliasing, an RGBA16F buffer texture in the layout of the kernel's filteredTexels
// (docs/dictionary.md, "Mip chain"); and the cumulative tables of glints under extended lights, an
// RGBA32F buffer texture (docs/dictionary.md, "Cumulative tables").
#pragma once

#include <glad/gl.h>

#include "glint/dictionary.h"

namespace glint::gl {

class ShaderProgram;

class DictionaryTexture {
 public:
  explicit DictionaryTexture(const Dictionary& dictionary);
  ~DictionaryTexture();
  DictionaryTexture(const DictionaryTexture&) = delete;
  DictionaryTexture& operator=(const DictionaryTexture&) = delete;

  // Binds the texture to unit 0, the mip chain to unit 10 and the cumulative tables to unit 15, and sets the shape uniforms of
  // shaders/glint_dictionary_gl.glsl for `program`, which must be in use.
  void bind(const ShaderProgram& program) const;

 private:
  GLuint texture_ = 0;
  GLuint buffer_ = 0;
  GLuint mipTexture_ = 0;
  GLuint mipBuffer_ = 0;
  GLuint cumulativeTexture_ = 0;
  GLuint cumulativeBuffer_ = 0;
  DictionaryParameters parameters_;
  int numMips_ = 1;
  int mipRowLength_ = 0;
};

}  // namespace glint::gl
