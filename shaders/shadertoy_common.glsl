// Shadertoy's Common tab (`glint shader-bundle --shadertoy`, docs/integration.md): the glint kernel
// as GLSL ES 3.00, the shape of the dictionary that Buffer A makes, and the kernel's dictionary hook
// reading it from iChannel0 (which must be Buffer A in the Image pass). Shadertoy has no file
// inputs, so the dictionary is made by a shader (kernel/procedural_dictionary.h): 10 levels of 64
// distributions of 64 texels, 40,960 texel pairs in rows of 256.
#include "glint_kernel.h"

#define GLINT_SHADERTOY_LEVELS 10
#define GLINT_SHADERTOY_DISTRIBUTIONS 64
#define GLINT_SHADERTOY_TEXELS 64
#define GLINT_SHADERTOY_ROW 256
#define GLINT_SHADERTOY_ALPHA_D 0.5
#define GLINT_SHADERTOY_LOBE_STD 0.02
#define GLINT_SHADERTOY_SEED 1u

GlintDictionaryView glintShadertoyDictionary() {
  GlintDictionaryView dict;
  dict.numLevels = GLINT_SHADERTOY_LEVELS;
  dict.numDistributions = GLINT_SHADERTOY_DISTRIBUTIONS;
  dict.texelsPerDistribution = GLINT_SHADERTOY_TEXELS;
  dict.alpha = GLINT_SHADERTOY_ALPHA_D;
  dict.numMips = 1;  // no mip chain: the 2020 model, without the anti-aliasing filter
  dict.mipRowLength = GLINT_SHADERTOY_TEXELS;
  return dict;
}

vec2 glintDictionaryTexelPair(GlintDictionaryView dict, int level, int distribution, int texel) {
  int index = (level * dict.numDistributions + distribution) * dict.texelsPerDistribution + texel;
  return texelFetch(iChannel0, ivec2(index % GLINT_SHADERTOY_ROW, index / GLINT_SHADERTOY_ROW), 0).xy;
}

// Never read without a mip chain; mip 0's pair, as glint's own unfiltered programs.
vec4 glintDictionaryFilteredTexels(GlintDictionaryView dict, int level, int distribution, int index) {
  return vec4(glintDictionaryTexelPair(dict, level, distribution, index), 0.0, 0.0);
}
