// The first extension of the glint BRDF: Chermain, Lucas, Sauvage, Dischler & Dachsbacher 2021,
// "Real-Time Geometric Glint Anti-Aliasing with Normal Map Filtering" (I3D; PACMCGIT 4(1)), as
// glint defines it (docs/antialiasing.md):
//
// 1. Slope correlation rho (the paper's Eq. 18): each cell's map to the dictionary's space becomes
//    upper-triangular, M^-1 = sigma_d [[1 / (sx s), -rho / (sy s)], [0, 1 / sy]], s = sqrt(1 - rho^2),
//    so that sigma_d^2 M M^T is the full covariance [[sx^2, rho sx sy], [rho sx sy, sy^2]] and the
//    cells converge to the correlated Beckmann (microfacet.h, glintBeckmannP22).
// 2. Geometric glint anti-aliasing (GGAA). Within a pixel the half vector's slope moves: to first
//    order h(p) = h0 + dx p.x + dy p.y over the pixel's box p in [-1/2, 1/2]^2, with dx, dy its
//    screen derivatives. The pixel's mean P-SDF is then the P-SDF convolved with that box pushed into
//    slope space, whose covariance is K = (dx dx^T + dy dy^T) / 12. glint filters with a kernel of
//    covariance K: in a cell's dictionary space (h_o = R M^-1 h, linear) its covariance is
//    R M^-1 K M^-T R^T, and the cell's two marginals are filtered by its diagonal entries averaged
//    over the cells' random rotation, half its trace (the paper filters each axis by the larger of
//    its two derivatives, times a kernel size of 0.5, a box rather than a variance). The filter is the
//    dictionary's mip chain in glint's texel convention (docs/dictionary.md, "Mip chain"), read
//    with the kernel's own interpolation, so that the CPU and GLSL agree.
// 3. The smooth cells (and the whole pixel where the footprint has no area) are the Beckmann P22;
//    convolved with the same kernel it is the Gaussian of covariance Sigma + K, exactly, so no part
//    of the P-SDF is left unfiltered (the paper leaves them).
#ifndef GLINT_KERNEL_GLINT_ANTIALIASING_H
#define GLINT_KERNEL_GLINT_ANTIALIASING_H

#include "prelude.h"
#include "microfacet.h"
#include "dictionary_lookup.h"

// Whether a walk over the footprint's cells filters. A GLSL program is compiled for one mode
// (GLINT_FILTERED 0: the 2020 model, the default, prelude.h; 1: anti-aliased),
// so that neither pays for the other's code; C++ filters where a slope has derivatives, and with
// none computes the 2020 sums exactly.
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
// with the cell's rotation, Eq. 5), for the target roughness alpha and correlation rho of a
// dictionary of roughness alphaD. With rho = 0 it is exactly the 2020 scaling h alpha_d / alpha: the
// terms rho adds are exact zeros and ones.
GLINT_FN vec2 glintCorrelatedUnscale(vec2 slope, vec2 alpha, float rho, float alphaD) {
  float s = sqrt(1.0f - rho * rho);
  vec2 scale = glintSplat2(alphaD) / alpha;
  return vec2(scale.x * (slope.x - rho * (alpha.x / alpha.y) * slope.y) / s, scale.y * slope.y);
}

// Its inverse, M h_o: from the dictionary's space back to the target's slopes (the sampler's).
GLINT_FN vec2 glintCorrelatedScale(vec2 unscaled, vec2 alpha, float rho, float alphaD) {
  float s = sqrt(1.0f - rho * rho);
  vec2 scale = alpha / glintSplat2(alphaD);
  return vec2(scale.x * (s * unscaled.x + rho * unscaled.y), scale.y * unscaled.y);
}

// The Jacobian det(M^-1) = alpha_d^2 / (alpha_x alpha_y sqrt(1 - rho^2)), the factor of Eq. 15 of
// Chermain et al. 2021 that makes every cell integrate to 1.
GLINT_FN float glintCorrelatedJacobian(vec2 alpha, float rho, float alphaD) {
  return (alphaD * alphaD) / (alpha.x * alpha.y) / sqrt(1.0f - rho * rho);
}

// ---- 2. The filter kernel --------------------------------------------------------------------

// The covariance (xx, xy, yy) of the pixel's box pushed into slope space by the slope's screen
// derivatives (dx.x, dx.y, dy.x, dy.y): K = (dx dx^T + dy dy^T) / 12. Derivatives are clamped to
// 1e4 slope units a pixel (a half vector a thousandth of a degree from the horizon), so that K and
// the covariances it is added to stay finite.
GLINT_FN vec3 glintKernelCovariance(vec4 derivatives) {
  vec4 d = clamp(derivatives, glintSplat4(-1e4f), glintSplat4(1e4f));
  vec2 dx = vec2(d.x, d.y);
  vec2 dy = vec2(d.z, d.w);
  return vec3(dx.x * dx.x + dy.x * dy.x, dx.x * dx.y + dy.x * dy.y, dx.y * dx.y + dy.y * dy.y) *
         (1.0f / 12.0f);
}

// The kernel's variance along a cell's dictionary axes, averaged over the cell's random rotation:
// half the trace of its covariance B in the unscaled space (the rotation only turns B), the same
// for every cell of the pixel. Per cell and axis (the diagonal of R B R^T) was measured too: about
// the same error against the reference, a third more of the anti-aliasing's cost on llvmpipe, two
// levels of detail a cell instead of one a pixel (docs/antialiasing.md).
GLINT_FN float glintKernelVariance(vec3 unscaledCovariance) {
  return 0.5f * (unscaledCovariance.x + unscaledCovariance.z);
}

// The level of detail whose lookup widens a marginal by a kernel of this variance
// (docs/dictionary.md, "Mip chain"). Mip m >= 1 holds box averages of width 2^m h (h the texel
// spacing), read with linear interpolation, which widens a marginal by a variance of
// V_m = (2^m h)^2 / 4: the box's 1/12 and the interpolation's hat's 1/6 (MipChain tests measure
// it); mip 0 by V_0 = 0. A blend of two levels is a mixture, whose variance is the blend of theirs,
// so the blend between the two levels around the kernel's variance v is (v - V_m) / (V_m+1 - V_m):
// the variance is matched exactly, from the smallest kernels on (a log2 of the width, as hardware
// filtering takes, would leave every kernel under half a texel unfiltered). Clamped to the chain.
//
// No logarithm: the mip level, floor(log4(4 v)), is half the binary exponent of 4 v, read from its
// bits (exact; llvmpipe runs a log2 for every lane of every cell).
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

// What a filtered lookup needs of its level of detail lod in [0, numMips - 1], the same for every
// cell of a pixel: the mip level floor(lod), its texel spacing, where it starts in a row, and the
// blend towards the next level.
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

// A marginal at |slope| (< 4 sigma_d) filtered by a kernel: the mip level floor(lod) blended with
// the next, each read with the texel convention's linear interpolation at its own spacing. One
// fetch: a mip texel holds its own pair and the next level's interpolation at the same two
// positions (docs/dictionary.md, "Mip chain"), so both levels share the texel's fraction and the
// blend is of the pairs. At lod 0 it is glintMarginal exactly (the blend adds exact zeros).
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

// The Beckmann P22 (roughness alpha, correlation rho) convolved with a kernel of slope covariance
// K: the Gaussian of covariance Sigma + K; exactly glintBeckmannP22 where there is no kernel.
GLINT_FN float glintFilteredBeckmannP22(vec2 slope, vec2 alpha, float rho, vec3 kernelCovariance) {
  if (kernelCovariance.x + kernelCovariance.z > 0.0f) {
    return glintGaussianSlopeP22(slope, glintBeckmannSlopeCovariance(alpha, rho) + kernelCovariance);
  }
  return glintBeckmannP22(slope, alpha, rho);
}

GLINT_KERNEL_END

#endif
