// The first extension of the glint BRDF: Chermain, Lucas, Sauvage, Dischler & Dachsbacher 2021,
// "Real-Time Geometric Glint Anti-Aliasing with Normal Map Filtering" (I3D; PACMCGIT 4(1)), as glint
// defines it (docs/antialiasing.md gives the derivations and measurements):
// 1. Slope correlation rho (the paper's Eq. 18): each cell's map to the dictionary's space becomes
//    upper-triangular, M^-1 = sigma_d [[1 / (sx s), -rho / (sy s)], [0, 1 / sy]], s = sqrt(1 - rho^2).
// 2. Geometric glint anti-aliasing: the pixel's box pushed into slope space by the half vector's
//    screen derivatives dx, dy has covariance K = (dx dx^T + dy dy^T) / 12; a cell's marginals are
//    filtered by half the trace of K in dictionary space, through the dictionary's mip chain read with
//    the kernel's own interpolation, so CPU and GLSL agree (the paper: each axis by its larger
//    derivative times 0.5, a box width, not a variance).
// 3. The smooth cells' Beckmann P22 convolved with K is exactly the Gaussian of covariance Sigma + K
//    (the paper leaves them unfiltered).
#ifndef GLINT_KERNEL_GLINT_ANTIALIASING_H
#define GLINT_KERNEL_GLINT_ANTIALIASING_H

#include "prelude.h"
#include "microfacet.h"
#include "dictionary_lookup.h"

// Whether a walk filters: a shading language compiles one mode (GLINT_FILTERED 0, the 2020 model and
// the default; 1, anti-aliased), so neither pays for the other's code; C++ filters where a slope has
// derivatives and otherwise computes the 2020 sums exactly.
#if defined(__cplusplus)
#define GLINT_FILTERS(anyDerivative) (anyDerivative)
#elif GLINT_FILTERED
#define GLINT_FILTERS(anyDerivative) true
#else
#define GLINT_FILTERS(anyDerivative) false
#endif

GLINT_KERNEL_BEGIN

// ---- 1. Slope correlation --------------------------------------------------------------------

// The linear part of a cell's map to the dictionary's space, M^-1 h (Eq. 18 of Chermain et al. 2021;
// with the rotation, Eq. 5), for target roughness alpha, correlation rho, dictionary roughness alphaD.
// rho = 0 gives exactly the 2020 scaling h alpha_d / alpha (exact zeros and ones).
GLINT_FN vec2 glintCorrelatedUnscale(vec2 slope, vec2 alpha, float rho, float alphaD) {
  float s = sqrt(1.0f - rho * rho);
  vec2 scale = glintSplat2(alphaD) / alpha;
  return vec2(scale.x * (slope.x - rho * (alpha.x / alpha.y) * slope.y) / s, scale.y * slope.y);
}

// Its inverse, M h_o: dictionary space back to the target's slopes (the sampler's).
GLINT_FN vec2 glintCorrelatedScale(vec2 unscaled, vec2 alpha, float rho, float alphaD) {
  float s = sqrt(1.0f - rho * rho);
  vec2 scale = alpha / glintSplat2(alphaD);
  return vec2(scale.x * (s * unscaled.x + rho * unscaled.y), scale.y * unscaled.y);
}

// det(M^-1) = alpha_d^2 / (alpha_x alpha_y sqrt(1 - rho^2)), the factor of Eq. 15 of Chermain et al.
// 2021 that makes every cell integrate to 1.
GLINT_FN float glintCorrelatedJacobian(vec2 alpha, float rho, float alphaD) {
  return (alphaD * alphaD) / (alpha.x * alpha.y) / sqrt(1.0f - rho * rho);
}

// ---- 2. The filter kernel --------------------------------------------------------------------

// K = (dx dx^T + dy dy^T) / 12 (xx, xy, yy) from the slope's screen derivatives (dx.x, dx.y, dy.x,
// dy.y), clamped to 1e4 slope units a pixel (a half vector a thousandth of a degree from the horizon)
// so that K and the covariances it is added to stay finite.
GLINT_FN vec3 glintKernelCovariance(vec4 derivatives) {
  vec4 d = clamp(derivatives, glintSplat4(-1e4f), glintSplat4(1e4f));
  vec2 dx = vec2(d.x, d.y);
  vec2 dy = vec2(d.z, d.w);
  return vec3(dx.x * dx.x + dy.x * dy.x, dx.x * dx.y + dy.x * dy.y, dx.y * dx.y + dy.y * dy.y) *
         (1.0f / 12.0f);
}

// The kernel's variance along a cell's dictionary axes, averaged over the random rotation: half the
// trace of its unscaled covariance B, the same for every cell of the pixel. Per cell and axis (the
// diagonal of R B R^T) measured about the same error for a third more of the anti-aliasing's cost on
// llvmpipe (docs/antialiasing.md).
GLINT_FN float glintKernelVariance(vec3 unscaledCovariance) {
  return 0.5f * (unscaledCovariance.x + unscaledCovariance.z);
}

// The level of detail whose lookup widens a marginal by a kernel of this variance (docs/dictionary.md,
// "Mip chain"). Mip m >= 1, box averages of width 2^m h read with linear interpolation, widens by
// V_m = (2^m h)^2 / 4 (box 1/12 plus the interpolation's hat 1/6; MipChain tests measure it); mip 0 by
// V_0 = 0. A blend of two levels is a mixture whose variance is the blend of theirs, so the blend
// (v - V_m) / (V_m+1 - V_m) matches v exactly, even for the smallest kernels (a log2 of the width, as
// hardware takes, leaves every kernel under half a texel unfiltered). Clamped to the chain.
// No logarithm (llvmpipe runs one per lane per cell): the mip, floor(log4(4 v)), is half the binary
// exponent of 4 v, read exactly from its bits.
GLINT_FN float glintMarginalLod(GlintDictionaryView dict, float variance) {
  float spacing = glintDictionaryDomain(dict) / float(dict.texelsPerDistribution);
  float v = min(max(variance, 0.0f) / (spacing * spacing), 1e30f);  // in texels^2
  int exponent = ((glintFloatBitsToInt(4.0f * max(v, 1.0f)) >> 23) & 255) - 127;  // floor(log2(4 v)) >= 2
  int mip = min(exponent / 2, dict.numMips - 1);
  float level = float(1 << (2 * mip)) * 0.25f;            // V_mip
  float lod = float(mip) + (v - level) / (3.0f * level);  // V_mip+1 - V_mip = 3 V_mip
  // Below V_1 = 1 texel^2, the blend of mip 0 (V_0 = 0) and mip 1.
  return v < 1.0f ? v : min(lod, float(dict.numMips - 1));
}

// What a filtered lookup needs of its level of detail lod in [0, numMips - 1], the same for every cell
// of a pixel.
struct GlintMarginalFilter {
  float texelsPerSlope;  // R / (4 sigma_d) / 2^mip
  int lastTexel;         // R / 2^mip - 1
  int mipOffset;         // glintMipOffset(R, mip)
  float blend;           // lod - mip
};

GLINT_FN GlintMarginalFilter glintMarginalFilter(GlintDictionaryView dict, float lod) {
  int mip = int(lod);
  GlintMarginalFilter marginalFilter;
  marginalFilter.texelsPerSlope = (float(dict.texelsPerDistribution) / glintDictionaryDomain(dict)) * (1.0f / float(1 << mip));
  marginalFilter.lastTexel = (dict.texelsPerDistribution >> mip) - 1;
  marginalFilter.mipOffset = glintMipOffset(dict.texelsPerDistribution, mip);
  marginalFilter.blend = lod - float(mip);
  return marginalFilter;
}

// A marginal at |slope| (< 4 sigma_d) filtered by a kernel: mip floor(lod) blended with the next, each
// linearly interpolated at its own spacing. One fetch: a mip texel holds its pair and the next level
// interpolated at the same two positions (docs/dictionary.md, "Mip chain"), so the levels share the
// fraction and the pairs are blended. At lod 0 it is exactly glintMarginal.
GLINT_FN float glintFilteredMarginal(GlintDictionaryView dict, GlintMarginalFilter marginalFilter, int level, int distribution,
                                     float absSlope) {
  float x = absSlope * marginalFilter.texelsPerSlope;
  int k = min(int(x), marginalFilter.lastTexel);
  float f = x - float(k);
  vec4 t = glintDictionaryFilteredTexels(dict, level, distribution, marginalFilter.mipOffset + k);
  vec2 pair = vec2(t.x, t.y) + marginalFilter.blend * (vec2(t.z, t.w) - vec2(t.x, t.y));
  return pair.x + f * (pair.y - pair.x);
}

// ---- 3. The smooth lobe ----------------------------------------------------------------------

// The Beckmann P22 convolved with a kernel of slope covariance K: the Gaussian of covariance
// Sigma + K; exactly glintBeckmannP22 without a kernel.
GLINT_FN float glintFilteredBeckmannP22(vec2 slope, vec2 alpha, float rho, vec3 kernelCovariance) {
  if (kernelCovariance.x + kernelCovariance.z > 0.0f) {
    return glintGaussianSlopeP22(slope, glintBeckmannSlopeCovariance(alpha, rho) + kernelCovariance);
  }
  return glintBeckmannP22(slope, alpha, rho);
}

GLINT_KERNEL_END

#endif
