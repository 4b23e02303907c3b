// GLSL side of the kernel's dictionary access (the C++ side is in src/glint/kernel/prelude.h):
// the dictionary is a buffer texture of RG16F texels, distribution after distribution, level after
// level, texel k holding (p[k], p[k+1]) so that one texelFetch serves an interpolation; read with
// texelFetch so the kernel's own interpolation (glintMarginal) is the only one, exactly as on the
// CPU. Its shape and alpha come from uniforms set from the Dictionary the host loaded.
#ifndef GLINT_DICTIONARY_GLSL
#define GLINT_DICTIONARY_GLSL

struct DictionaryView {
  int numLevels;
  int numDistributions;
  int texelsPerDistribution;
  float alpha;
};

layout(binding = 0) uniform samplerBuffer uGlintDictionary;
uniform ivec3 uGlintDictionaryShape;  // L, N, R
uniform float uGlintDictionaryAlpha;  // alpha_d

DictionaryView glintDictionary() {
  DictionaryView dict;
  dict.numLevels = uGlintDictionaryShape.x;
  dict.numDistributions = uGlintDictionaryShape.y;
  dict.texelsPerDistribution = uGlintDictionaryShape.z;
  dict.alpha = uGlintDictionaryAlpha;
  return dict;
}

vec2 glintDictionaryTexelPair(DictionaryView dict, int level, int distribution, int texel) {
  return texelFetch(uGlintDictionary, (level * dict.numDistributions + distribution) * dict.texelsPerDistribution + texel).rg;
}

#endif
