// glint's renderer's side of the kernel's dictionary hook (src/glint/kernel/prelude.h): where the
// dictionary's texels live in glint's OpenGL and WebGL2 programs, which include this file after the
// kernel. The dictionary is a buffer texture of RG16F texels, distribution after distribution,
// level after level, texel k holding (p[k], p[k+1]) so that one texelFetch serves an
// interpolation; read with texelFetch so the kernel's own interpolation (glintMarginal) is the only
// one, exactly as on the CPU. Its shape and alpha come from uniforms set from the Dictionary the
// host loaded (src/gl/dictionary_texture.cpp). Programs that anti-alias glints (GLINT_FILTERED 1)
// also read the dictionary's mip chain (docs/dictionary.md, "Mip chain").
#ifndef GLINT_DICTIONARY_GL_GLSL
#define GLINT_DICTIONARY_GL_GLSL

#include "prelude.h"

#ifdef GL_ES
// GLSL ES 3.00 (WebGL2) has no buffer textures: the host lays a buffer's texels row after row in a
// 2D texture 2048 texels wide (web/src/gl45_on_webgl2.cpp, kTexelBufferWidth).
#define GLINT_TEXEL_BUFFER highp sampler2D
#define GLINT_TEXEL_BUFFER_FETCH(buffer, index) texelFetch(buffer, ivec2((index) & 2047, (index) >> 11), 0)
#else
#define GLINT_TEXEL_BUFFER samplerBuffer
#define GLINT_TEXEL_BUFFER_FETCH(buffer, index) texelFetch(buffer, index)
#endif

layout(binding = 0) uniform GLINT_TEXEL_BUFFER uGlintDictionary;
uniform ivec3 uGlintDictionaryShape;  // L, N, R
uniform float uGlintDictionaryAlpha;  // alpha_d
#if GLINT_FILTERED
// The mip chain: RGBA16F texels (p_m[k], p_m[k+1], q_m[k], q_m[k+1]), q_m the next level at level
// m's positions, row after row as the C++ GlintDictionaryView's filteredTexels.
layout(binding = 10) uniform GLINT_TEXEL_BUFFER uGlintFilteredDictionary;
uniform ivec2 uGlintDictionaryMips;  // numMips, mipRowLength
#endif

GlintDictionaryView glintDictionary() {
  GlintDictionaryView dict;
  dict.numLevels = uGlintDictionaryShape.x;
  dict.numDistributions = uGlintDictionaryShape.y;
  dict.texelsPerDistribution = uGlintDictionaryShape.z;
  dict.alpha = uGlintDictionaryAlpha;
#if GLINT_FILTERED
  dict.numMips = uGlintDictionaryMips.x;
  dict.mipRowLength = uGlintDictionaryMips.y;
#else
  dict.numMips = 1;
  dict.mipRowLength = uGlintDictionaryShape.z;
#endif
  return dict;
}

vec2 glintDictionaryTexelPair(GlintDictionaryView dict, int level, int distribution, int texel) {
  return GLINT_TEXEL_BUFFER_FETCH(uGlintDictionary, (level * dict.numDistributions + distribution) * dict.texelsPerDistribution + texel).rg;
}

#if GLINT_FILTERED
vec4 glintDictionaryFilteredTexels(GlintDictionaryView dict, int level, int distribution, int index) {
  return GLINT_TEXEL_BUFFER_FETCH(uGlintFilteredDictionary, (level * dict.numDistributions + distribution) * dict.mipRowLength + index);
}
#else
// Unfiltered programs never read the mip chain; the kernel's filtered lookup, compiled but not
// called there, reads mip 0's pair.
vec4 glintDictionaryFilteredTexels(GlintDictionaryView dict, int level, int distribution, int index) {
  return vec4(glintDictionaryTexelPair(dict, level, distribution, index), 0.0f, 0.0f);
}
#endif

// The cumulative tables (Dictionary::cumulativeTexels), for programs that include
// glint_extended_lights.h before this file.
#ifdef GLINT_KERNEL_GLINT_EXTENDED_LIGHTS_H
layout(binding = 15) uniform GLINT_TEXEL_BUFFER uGlintCumulativeDictionary;

vec4 glintDictionaryCumulativeTexel(GlintDictionaryView dict, int level, int distribution, int texel) {
  return GLINT_TEXEL_BUFFER_FETCH(uGlintCumulativeDictionary, (level * dict.numDistributions + distribution) * dict.texelsPerDistribution + texel);
}
#endif

#endif
