// Microfacet terms shared by the glint BRDF and the Cook-Torrance baseline, in the local shading
// frame (docs/conventions.md: z the normal, directions away from the surface).
#ifndef GLINT_KERNEL_MICROFACET_H
#define GLINT_KERNEL_MICROFACET_H

#include "prelude.h"

GLINT_KERNEL_BEGIN

GLINT_CONST float GLINT_PI = 3.14159265358979f;

// Slope of a normal m: (-m.x / m.z, -m.y / m.z) (Eq. 1 of Chermain et al. 2020).
GLINT_FN vec2 glintSlopeFromNormal(vec3 m) {
  return vec2(-m.x / m.z, -m.y / m.z);
}

// Anisotropic Beckmann P22: a centred Gaussian, sigma = alpha / sqrt(2) per axis, correlation rho,
// covariance [[sx^2, rho sx sy], [rho sx sy, sy^2]] (Walter et al. 2007, Eq. 25 in slope space; rho
// of Chermain et al. 2021, I3D). rho = 0 is exactly the uncorrelated expression (exact zeros, ones).
GLINT_FN float glintBeckmannP22(vec2 slope, vec2 alpha, float rho) {
  vec2 sigma = alpha * 0.70710678f;
  vec2 t = slope / sigma;
  float oneMinusRho2 = 1.0f - rho * rho;
  float q = (dot(t, t) - 2.0f * rho * t.x * t.y) / oneMinusRho2;
  return exp(-0.5f * q) / (2.0f * GLINT_PI * sigma.x * sigma.y * sqrt(oneMinusRho2));
}

// A centred Gaussian P22 of covariance (xx, xy, yy), positive definite: Beckmann widened by a kernel
// of covariance K is this with Sigma + K.
GLINT_FN float glintGaussianSlopeP22(vec2 slope, vec3 covariance) {
  float determinant = covariance.x * covariance.z - covariance.y * covariance.y;
  float q = (covariance.z * slope.x * slope.x - 2.0f * covariance.y * slope.x * slope.y +
             covariance.x * slope.y * slope.y) / determinant;
  return exp(-0.5f * q) / (2.0f * GLINT_PI * sqrt(determinant));
}

// The covariance (xx, xy, yy) of the Beckmann slopes of roughness alpha and correlation rho.
GLINT_FN vec3 glintBeckmannSlopeCovariance(vec2 alpha, float rho) {
  vec2 sigma = alpha * 0.70710678f;
  return vec3(sigma.x * sigma.x, rho * sigma.x * sigma.y, sigma.y * sigma.y);
}

// D(m) = P22(slope(m)) / cos^4(theta_m); for the P-SDF, Alg. 1, line 10 of Chermain et al. 2020.
GLINT_FN float glintNdfFromP22(float p22, float cosThetaM) {
  float c2 = cosThetaM * cosThetaM;
  return p22 / (c2 * c2);
}

// V-cavity masking (Heitz & d'Eon 2014, Eq. 5; the glint paper's choice):
// G1(w, m) = min(1, 2 (m.z)(w.z) / (w.m)).
GLINT_FN float glintVCavityG1(vec3 w, vec3 m) {
  return min(1.0f, 2.0f * m.z * w.z / dot(w, m));
}

// The Cook-Torrance frame around any D(wh), without Fresnel and the cosine:
// f = G1(wo) G1(wi) D / (4 wo.z wi.z) (Eq. 14 of Chermain et al. 2020; method.md 3). Zero below
// either horizon and for back-facing microfacets.
GLINT_FN float glintMicrofacetReflectance(vec3 wo, vec3 wi, vec3 wh, float ndf) {
  if (wo.z <= 0.0f || wi.z <= 0.0f || wh.z <= 0.0f || dot(wo, wh) <= 0.0f || dot(wi, wh) <= 0.0f) {
    return 0.0f;
  }
  return glintVCavityG1(wo, wh) * glintVCavityG1(wi, wh) * ndf / (4.0f * wo.z * wi.z);
}

// Schlick 1994, "An Inexpensive BRDF Model for Physically-based Rendering".
GLINT_FN vec3 glintFresnelSchlick(vec3 f0, float cosThetaI) {
  float c = clamp(1.0f - cosThetaI, 0.0f, 1.0f);
  float c2 = c * c;
  return f0 + (glintSplat3(1.0f) - f0) * (c2 * c2 * c);
}

// Conductor Fresnel, complex IOR eta + i k (relative to the outside), unpolarised, per channel: Born &
// Wolf's exact expression as in pbrt-v3 (FrConductor).
GLINT_FN vec3 glintFresnelConductor(vec3 eta, vec3 k, float cosThetaI) {
  float c = clamp(cosThetaI, 0.0f, 1.0f);
  float c2 = c * c;
  float s2 = 1.0f - c2;
  vec3 eta2 = eta * eta;
  vec3 k2 = k * k;
  vec3 t0 = eta2 - k2 - glintSplat3(s2);
  vec3 a2plusb2 = sqrt(t0 * t0 + 4.0f * eta2 * k2);
  vec3 t1 = a2plusb2 + glintSplat3(c2);
  vec3 a = sqrt(0.5f * (a2plusb2 + t0));
  vec3 t2 = 2.0f * c * a;
  vec3 rs = (t1 - t2) / (t1 + t2);
  vec3 t3 = c2 * a2plusb2 + glintSplat3(s2 * s2);
  vec3 t4 = t2 * s2;
  vec3 rp = rs * (t3 - t4) / (t3 + t4);
  return 0.5f * (rp + rs);
}

// The Cook-Torrance baseline the glint BRDF converges to: Beckmann (rho), V-cavity, F = 1.
GLINT_FN float glintCookTorranceReflectance(vec2 alpha, float rho, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) {
    return 0.0f;
  }
  vec3 wh = normalize(wo + wi);
  return glintMicrofacetReflectance(wo, wi, wh, glintNdfFromP22(glintBeckmannP22(glintSlopeFromNormal(wh), alpha, rho), wh.z));
}

GLINT_KERNEL_END

#endif
