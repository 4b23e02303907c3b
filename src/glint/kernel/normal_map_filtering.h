// Normal-map filtering for glints: the second part of Chermain, Lucas, Sauvage, Dischler & Dachsbacher
// 2021, "Real-Time Geometric Glint Anti-Aliasing with Normal Map Filtering" (I3D), after LEAN mapping
// (Olano & Baker 2010, "LEAN Mapping", I3D). A normal map's tangent-frame slopes s are stored as two
// moment textures, (E[sx], E[sy], E[sx^2]) and (E[sy^2], E[sx sy], 0), whose box-average mips give the
// moments over any footprint in one lookup each. The mean slope tilts the shading normal; the slopes'
// covariance, which a filtered normal loses, is added to the glint layer's, correlation kept
// (docs/antialiasing.md, "Normal-map filtering").
#ifndef GLINT_KERNEL_NORMAL_MAP_FILTERING_H
#define GLINT_KERNEL_NORMAL_MAP_FILTERING_H

#include "prelude.h"
#include "microfacet.h"

GLINT_KERNEL_BEGIN

// The normal whose slope is the footprint's mean slope, in the tangent frame.
GLINT_FN vec3 glintLeanMeanNormal(vec3 firstMoments) {
  return normalize(vec3(-firstMoments.x, -firstMoments.y, 1.0f));
}

// The slopes' covariance (xx, xy, yy) over the footprint from the two moment lookups. Each variance
// is clamped at 0 on its own (filtering and half precision can take E[s^2] - E[s]^2 a hair below 0;
// the authors' shader drops both when either is small, losing a ridge's filtering), the correlation
// to at most GLINT_LEAN_MAX_CORRELATION.
GLINT_CONST float GLINT_LEAN_MAX_CORRELATION = 0.99f;

//
// Under magnification E[s^2] - E[s]^2 is the spread of interpolated neighbours, not of the slopes in
// the shrinking footprint: below a texel the covariance is scaled by the footprint's area in texels,
// 4^lambda for the lookup's level of detail lambda < 0 (OpenGL's), so a normal map seen up close adds
// no roughness and the covariance is continuous at lambda = 0.
GLINT_FN vec3 glintLeanSlopeCovariance(vec3 firstMoments, vec3 secondMoments, float lambda) {
  float vx = max(firstMoments.z - firstMoments.x * firstMoments.x, 0.0f);
  float vy = max(secondMoments.x - firstMoments.y * firstMoments.y, 0.0f);
  float bound = GLINT_LEAN_MAX_CORRELATION * sqrt(vx * vy);
  float cxy = clamp(secondMoments.y - firstMoments.x * firstMoments.y, -bound, bound);
  return vec3(vx, cxy, vy) * exp2(2.0f * min(lambda, 0.0f));
}

// OpenGL's level of detail of a lookup (OpenGL 4.5 core, section 8.14): log2 of the longer uv
// derivative in texels.
GLINT_FN float glintTextureLevelOfDetail(vec2 duvdx, vec2 duvdy, vec2 size) {
  float longest = max(length(duvdx * size), length(duvdy * size));
  return longest > 0.0f ? log2(longest) : -128.0f;
}

// A Beckmann target (alpha, rho) widened by an independent slope covariance: the covariances add.
// Returns (alpha_x, alpha_y, rho), alpha clamped to the model's [0.01, 2], rho to its range; exactly
// (alpha, rho) without a covariance (a constant normal map changes nothing).
GLINT_FN vec3 glintLeanCombinedRoughness(vec2 alpha, float rho, vec3 covariance) {
  if (!(covariance.x + covariance.z > 0.0f)) {
    return vec3(alpha, rho);
  }
  vec3 total = glintBeckmannSlopeCovariance(alpha, rho) + covariance;
  vec2 sigma = sqrt(vec2(total.x, total.z));
  float combinedRho = clamp(total.y / (sigma.x * sigma.y), -GLINT_LEAN_MAX_CORRELATION, GLINT_LEAN_MAX_CORRELATION);
  vec2 combinedAlpha = clamp(sigma * 1.41421356f, glintSplat2(0.01f), glintSplat2(2.0f));
  return vec3(combinedAlpha, combinedRho);
}

GLINT_KERNEL_END

#endif
