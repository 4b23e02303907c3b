// A dictionary texel computed where it is read, for hosts that load no file (a Shadertoy buffer pass,
// `glint shader-bundle --shadertoy`, makes the whole dictionary every frame). glint's generator's
// construction (docs/dictionary.md, "Generation"): level l of distribution n is the even mixture of
// its first 2^l Gaussian lobes of std s, means from the half-normal |Normal(0, sigma_d)|, so levels
// are nested. The means come from a hash of (n, k, seed), not PCG32 streams (the paper's "independent"
// placement), and the mixture is normalised analytically; docs/integration.md gives the difference.
#ifndef GLINT_KERNEL_PROCEDURAL_DICTIONARY_H
#define GLINT_KERNEL_PROCEDURAL_DICTIONARY_H

#include "prelude.h"
#include "random.h"

GLINT_KERNEL_BEGIN

// The mean |mu| of lobe k of distribution n: the half-normal quantile sigma_d sqrt 2 erfinv(u) of a
// hashed uniform u, kept below 1 so that erfinv stays finite.
GLINT_FN float glintProceduralLobeMean(int distribution, int lobe, uint seed, float sigmaD) {
  uvec4 h = glintPcg4d(uvec4(uint(distribution), uint(lobe), seed, 0x9E3779B9u));
  float u = min(glintHashToUnitOpen(h.x), 0.99999988f);
  return sigmaD * 1.41421356f * glintErfinvApprox(u);
}

// Texel k of level l of distribution n (docs/dictionary.md, "Texel convention"): the density at slope
// x_k = k 4 sigma_d / R of
//   p_l(x) = 1 / (2 2^l) sum_{k' < 2^l} [ g(x; mu_k', s) + g(-x; mu_k', s) ],
// g the normal density; lobes over 6 s from x (under 1.6e-8 of their peak) are skipped. Costs 2^l lobe
// means (a hash and an erfinv each): a host calls it once per texel and keeps it.
GLINT_FN float glintProceduralDictionaryTexel(int level, int distribution, int texel, int texelsPerDistribution,
                                              float alphaD, float lobeStd, uint seed) {
  float sigmaD = alphaD * 0.70710678f;
  float x = float(texel) * (4.0f * sigmaD / float(texelsPerDistribution));
  float cutoff = 6.0f * lobeStd;
  float inverseTwoVariance = 0.5f / (lobeStd * lobeStd);
  float sum = 0.0f;
  int lobes = 1 << level;
  for (int k = 0; k < lobes; ++k) {
    float mu = glintProceduralLobeMean(distribution, k, seed, sigmaD);
    float a = x - mu;
    float b = x + mu;
    if (abs(a) < cutoff) sum += exp(-a * a * inverseTwoVariance);
    if (b < cutoff) sum += exp(-b * b * inverseTwoVariance);
  }
  // 1 / (s sqrt(2 pi)) for g, 1 / (2 2^l) for the mixture.
  return sum * (0.39894228f / lobeStd) / (2.0f * float(lobes));
}

GLINT_KERNEL_END

#endif
