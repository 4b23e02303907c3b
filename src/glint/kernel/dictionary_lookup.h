// Reading the dictionary's marginals (docs/dictionary.md, "Texel convention"), for the 2020 P-SDF
// (glint_brdf.h) and its anti-aliasing (glint_antialiasing.h).
#ifndef GLINT_KERNEL_DICTIONARY_LOOKUP_H
#define GLINT_KERNEL_DICTIONARY_LOOKUP_H

#include "prelude.h"

GLINT_KERNEL_BEGIN

// The dictionary's slope support 4 sigma_d = 4 alpha_d / sqrt(2): marginals vanish beyond it.
GLINT_FN float glintDictionaryDomain(GlintDictionaryView dict) {
  return 2.82842712f * dict.alpha;
}

// One 1D marginal at |slope|: texel k holds the density at slope k * 4 sigma_d / R, and past the last
// texel it falls linearly to 0 at 4 sigma_d. The caller guarantees 0 <= absSlope < 4 sigma_d.
GLINT_FN float glintMarginal(GlintDictionaryView dict, int level, int distribution, float absSlope) {
  float x = absSlope * (float(dict.texelsPerDistribution) / glintDictionaryDomain(dict));
  int k = min(int(x), dict.texelsPerDistribution - 1);
  float f = x - float(k);
  vec2 ab = glintDictionaryTexelPair(dict, level, distribution, k);
  return ab.x + f * (ab.y - ab.x);
}

GLINT_KERNEL_END

#endif
