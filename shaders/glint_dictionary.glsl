// GLSL side of the kernel's dictionary access (the C++ side is in src/glint/kernel/prelude.h):
// the dictionary is a buffer texture of RG16F texels, distribution after distribution, level after
// level, texel k holding (p[k], p[k+1]) so that one texelFetch serves an interpolation; read with
// texelFetch so the kernel's own interpolation (glintMarginal) is the only one, exactly as on the
// CPU. Its shape and alpha come from uniforms set from the Dictionary the host loaded. Programs
// that anti-alias glints (GLINT_FILTERED = 1) also read the dictionary's mip chain
// (docs/dictionary.md, "Mip chain").
#ifndef GLINT_DICTIONARY_GLSL
#define GLINT_DICTIONARY_GLSL

#ifndef GLINT_FILTERED
#define GLINT_FILTERED 0
#endif

struct GlintDictionaryView {
  int numLevels;
  int numDistributions;
  int texelsPerDistribution;
  float alpha;
  int numMips;       // the mip chain's levels (docs/dictionary.md, "Mip chain")
  int mipRowLength;  // texels of all mip levels of one distribution
};

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

// Where level m of the mip chain starts in a distribution's row (as in prelude.h).
int glintMipOffset(int texelsPerDistribution, int mip) {
  return 2 * texelsPerDistribution - ((2 * texelsPerDistribution) >> mip);
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

#endif
