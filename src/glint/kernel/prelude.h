// The kernel's language bridge: every file under kernel/ compiles both as C++20 (with glm) and as
// GLSL 4.50 (or GLSL ES 3.00 for WebGL2: the GL_ES branch below), so that the model's equations are written once (docs/conventions.md, "One model, two
// languages"). Rules for kernel code:
//   - every input is a function argument: no uniforms, no derivatives, no globals;
//   - integer hashing on uint (wrap-around is defined in both languages);
//   - float literals carry the f suffix, unsigned ones the u suffix;
//   - no swizzle assignment, no struct constructors (assign fields), no recursion;
//   - functions are declared with GLINT_FN, out-parameters with GLINT_OUT(T), in-out ones with
//     GLINT_INOUT(T).
// The kernel reaches the dictionary only through glintDictionaryTexelPair() (texels k and k+1 of a
// distribution, 0 past the last) and glintDictionaryFilteredTexels() (the same pair from a level
// of the dictionary's mip chain, with the next level's pair: docs/dictionary.md, "Mip chain"),
// which each language defines: below for C++ (a GlintDictionaryView over host memory), in shaders/ for
// GLSL (buffer textures). The host's own code reads single texels with glintDictionaryTexel().
#ifndef GLINT_KERNEL_PRELUDE_H
#define GLINT_KERNEL_PRELUDE_H

#ifdef __cplusplus

#include <cstdint>
#include <glm/glm.hpp>

#define GLINT_KERNEL_BEGIN \
  namespace glint::kernel {  \
  using namespace glm;       \
  using uint = std::uint32_t;
#define GLINT_KERNEL_END }
#define GLINT_FN inline
#define GLINT_CONST inline constexpr
#define GLINT_OUT(T) T&
#define GLINT_INOUT(T) T&

GLINT_KERNEL_BEGIN

// Read-only view of a dictionary in host memory: texels[(level * numDistributions + distribution)
// * texelsPerDistribution + texel], each a float that is exactly representable as binary16, so the
// CPU reads the very values the GPU's R16F texture holds.
struct GlintDictionaryView {
  const float* texels;
  int numLevels;
  int numDistributions;
  int texelsPerDistribution;
  float alpha;  // alpha_d, the dictionary's roughness
  // The mip chain (docs/dictionary.md, "Mip chain"): numMips levels of each distribution, level m
  // of R / 2^m texels, one after the other in a row of mipRowLength texels per distribution; each
  // texel four floats, (p_m[k], p_m[k+1], q_m[k], q_m[k+1]), binary16 values, q_m the next level
  // interpolated at level m's texel positions.
  const float* filteredTexels;
  int numMips;
  int mipRowLength;
};

GLINT_FN float glintDictionaryTexel(GlintDictionaryView dict, int level, int distribution, int texel) {
  return dict.texels[(level * dict.numDistributions + distribution) * dict.texelsPerDistribution + texel];
}

GLINT_FN vec2 glintDictionaryTexelPair(GlintDictionaryView dict, int level, int distribution, int texel) {
  const float* row = dict.texels + (level * dict.numDistributions + distribution) * dict.texelsPerDistribution;
  return vec2(row[texel], texel + 1 < dict.texelsPerDistribution ? row[texel + 1] : 0.0f);
}

// Where level m of the mip chain starts in a distribution's row: R + R/2 + ... + R/2^(m-1) texels.
GLINT_FN int glintMipOffset(int texelsPerDistribution, int mip) {
  return 2 * texelsPerDistribution - ((2 * texelsPerDistribution) >> mip);
}

// Texel `index` of a distribution's row of the mip chain: glintMipOffset(R, m) + k for texel k of
// level m.
GLINT_FN vec4 glintDictionaryFilteredTexels(GlintDictionaryView dict, int level, int distribution, int index) {
  const float* t = dict.filteredTexels + 4 * ((level * dict.numDistributions + distribution) * dict.mipRowLength + index);
  return vec4(t[0], t[1], t[2], t[3]);
}

// GLSL's findLSB and ldexp, under the kernel's names (the GLSL ES branch below writes them out).
GLINT_FN int glintFindLSB(uint v) {
  return glm::findLSB(v);
}

GLINT_FN float glintLdexp(float x, int e) {
  return glm::ldexp(x, e);
}

GLINT_KERNEL_END

#else  // GLSL

#ifdef GL_ES
// GLSL ES 3.00 (WebGL2, web/): what desktop GLSL has and ES 3.00 lacks. findLSB and ldexp are ES
// 3.10 built-ins, given here exactly (through the float's bits, no exp2 or log2 rounding); and
// buffer textures do not exist, so the host lays a buffer's texels row after row in a 2D texture
// 2048 texels wide (web/src/gl45_on_webgl2.cpp, kTexelBufferWidth).
int glintFindLSB(uint v) {
  return v == 0u ? -1 : (floatBitsToInt(float(v & (0u - v))) >> 23) - 127;
}
float glintLdexp(float x, int e) {
  return x * intBitsToFloat((e + 127) << 23);
}
#define GLINT_TEXEL_BUFFER highp sampler2D
#define GLINT_TEXEL_BUFFER_FETCH(buffer, index) texelFetch(buffer, ivec2((index) & 2047, (index) >> 11), 0)
#else
int glintFindLSB(uint v) {
  return findLSB(v);
}
float glintLdexp(float x, int e) {
  return ldexp(x, e);
}
#define GLINT_TEXEL_BUFFER samplerBuffer
#define GLINT_TEXEL_BUFFER_FETCH(buffer, index) texelFetch(buffer, index)
#endif
#include "glint_dictionary.glsl"

#define GLINT_KERNEL_BEGIN
#define GLINT_KERNEL_END
#define GLINT_FN
#define GLINT_CONST const
#define GLINT_OUT(T) out T
#define GLINT_INOUT(T) inout T

#endif

#endif
