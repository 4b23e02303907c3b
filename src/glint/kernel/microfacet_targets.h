// Past the 2020 paper (docs/method.md 6): the smooth targets a glint layer converges to and the
// masking of its microfacets.
// 1. GGX (Trowbridge-Reitz) with microfacet.h's slope correlation: Walter, Marschner, Li & Torrance
//    2007, "Microfacet Models for Refraction through Rough Surfaces" (EGSR), Eq. 33 in slope space: a
//    bivariate Student t, Beckmann slopes of roughness alpha with covariance divided by w ~ Exp(1).
//    The P-SDF draws w per cell (glintCellPrecision), cells of roughness alpha / sqrt(w), so the mean
//    is exactly GGX; below w = GLINT_GGX_TAIL_PRECISION cells reflect the mixture's smooth remainder
//    (method.md 6.1).
// 2. Height-correlated Smith masking for the smooth target: Heitz 2014, "Understanding the
//    Masking-Shadowing Function in Microfacet-Based BRDFs" (JCGT 3(2)), Eq. 99; Lambda of Beckmann
//    (Eq. 81, after Walter et al. 2007) and GGX (Eq. 86), along the direction's azimuth for
//    anisotropic, correlated slopes (Heitz 2014 section 5.3).
#ifndef GLINT_KERNEL_MICROFACET_TARGETS_H
#define GLINT_KERNEL_MICROFACET_TARGETS_H

#include "prelude.h"
#include "random.h"
#include "microfacet.h"

GLINT_KERNEL_BEGIN

// The smooth target's NDF (GlintParameters::ndf, `ndf` in extras.glint and eval).
GLINT_CONST int GLINT_NDF_BECKMANN = 0;  // the 2020 paper's
GLINT_CONST int GLINT_NDF_GGX = 1;       // glTF's
// The masking of the microfacets (GlintParameters::masking, `masking`).
GLINT_CONST int GLINT_MASKING_VCAVITY = 0;  // the 2020 paper's
GLINT_CONST int GLINT_MASKING_SMITH = 1;    // height-correlated Smith, glTF's

// ---- 1. GGX ----------------------------------------------------------------------------------

// GGX P22 of roughness alpha and correlation rho: a Student t of scale covariance Sigma
// (glintBeckmannSlopeCovariance), P22 = 1 / (2 pi sqrt(det Sigma) (1 + q / 2)^2), q = s^T Sigma^-1 s;
// for rho = 0, 1 / (pi alpha_x alpha_y (1 + x^2 / alpha_x^2 + y^2 / alpha_y^2)^2).
GLINT_FN float glintStudentSlopeP22(vec2 slope, vec3 covariance) {
  float determinant = covariance.x * covariance.z - covariance.y * covariance.y;
  float q = (covariance.z * slope.x * slope.x - 2.0f * covariance.y * slope.x * slope.y +
             covariance.x * slope.y * slope.y) / determinant;
  float b = 1.0f + 0.5f * q;
  return 1.0f / (2.0f * GLINT_PI * sqrt(determinant) * b * b);
}

GLINT_FN float glintGgxP22(vec2 slope, vec2 alpha, float rho) {
  return glintStudentSlopeP22(slope, glintBeckmannSlopeCovariance(alpha, rho));
}

// The cut on the per-cell precision w: P(w < 0.01) = 1 - e^-0.01, about 1%, and a cell at most
// 1 / sqrt(0.01) = 10 times wider than the target's Beckmann (docs/method.md 6.1 measures the choice).
GLINT_CONST float GLINT_GGX_TAIL_PRECISION = 0.01f;
GLINT_CONST float GLINT_GGX_TAIL_PROBABILITY = 0.00995016625f;  // 1 - exp(-GLINT_GGX_TAIL_PRECISION)
GLINT_CONST float GLINT_GGX_WIDEST_CELL = 10.0f;                // 1 / sqrt(GLINT_GGX_TAIL_PRECISION)

// 1 - e^-x (1 + x) without that form's cancellation at small x (below 0.1 its series
// x^2/2 - x^3/3 + x^4/8 - x^5/30, the next term under 2e-6 of the sum); 1 from x = 100, where
// e^-x (1 + x) < 1e-41 (and an infinite x would give 0 times infinity).
GLINT_FN float glintOneMinusExpTimesOnePlus(float x) {
  if (x < 0.1f) {
    return x * x * (0.5f + x * (-0.333333333f + x * (0.125f + x * -0.0333333333f)));
  }
  return x < 100.0f ? 1.0f - exp(-x) * (1.0f + x) : 1.0f;
}

// The GGX mixture's smooth remainder, normalised: Gaussians of covariance Sigma / w over
// w < GLINT_GGX_TAIL_PRECISION = W, weighted by e^-w, over their mass GLINT_GGX_TAIL_PROBABILITY. With
// b = 1 + q / 2, the integral of e^-w w / (2 pi sqrt(det Sigma)) e^(-w q / 2) over (0, W) is
// (1 - e^(-b W) (1 + b W)) / (2 pi sqrt(det Sigma) b^2).
GLINT_FN float glintStudentTailSlopeP22(vec2 slope, vec3 covariance) {
  float determinant = covariance.x * covariance.z - covariance.y * covariance.y;
  float q = (covariance.z * slope.x * slope.x - 2.0f * covariance.y * slope.x * slope.y +
             covariance.x * slope.y * slope.y) / determinant;
  float b = 1.0f + 0.5f * q;
  return glintOneMinusExpTimesOnePlus(b * GLINT_GGX_TAIL_PRECISION) /
         (2.0f * GLINT_PI * sqrt(determinant) * b * b * GLINT_GGX_TAIL_PROBABILITY);
}

// A cell's w ~ Exp(1), from the y lane of a second hash (the first's lanes are the 2020 draws, and
// glintCellChroma takes the 8 low bits they leave of two: too few for w's tail).
GLINT_FN float glintCellPrecision(uvec4 h) {
  return -log(glintHashToUnitOpen(glintPcg4d(h).y));
}

// The smooth target's P22.
GLINT_FN float glintTargetP22(int ndf, vec2 slope, vec2 alpha, float rho) {
  return ndf == GLINT_NDF_GGX ? glintGgxP22(slope, alpha, rho) : glintBeckmannP22(slope, alpha, rho);
}

// The widest a target's dictionary cell is, relative to the Beckmann scaling.
GLINT_FN float glintTargetWidestCell(int ndf) {
  return ndf == GLINT_NDF_GGX ? GLINT_GGX_WIDEST_CELL : 1.0f;
}

// ---- 2. Smith masking ------------------------------------------------------------------------

// Lambda(w) of the smooth target (Heitz 2014, Eqs. 81 and 86), slopes of covariance
// glintBeckmannSlopeCovariance(alpha, rho) (GGX: its scale matrix): with a = 1 / (alpha_w tan theta),
// alpha_w^2 = 2 u^T Sigma u along w's azimuth u,
//   Beckmann: (erf(a) - 1) / 2 + exp(-a^2) / (2 a sqrt(pi)), erf(a) - 1 = -2 Phi(-a sqrt 2);
//   GGX:      (-1 + sqrt(1 + 1 / a^2)) / 2.
GLINT_FN float glintSmithLambda(int ndf, vec2 alpha, float rho, vec3 w) {
  vec3 c = glintBeckmannSlopeCovariance(alpha, rho);
  // alpha_w^2 tan^2 theta = 2 (w.xy)^T Sigma (w.xy) / w.z^2: no azimuth to normalise.
  float projected = 2.0f * (c.x * w.x * w.x + 2.0f * c.y * w.x * w.y + c.z * w.y * w.y) / (w.z * w.z);
  if (!(projected > 0.0f)) {
    return 0.0f;  // at normal incidence nothing is masked
  }
  if (ndf == GLINT_NDF_GGX) {
    return 0.5f * (sqrt(1.0f + projected) - 1.0f);
  }
  float a = glintInverseSqrt(projected);
  return -glintNormalCdf(-a * 1.41421356f) + exp(-a * a) / (2.0f * a * 1.77245385f);
}

// Height-correlated Smith G2 = 1 / (1 + Lambda(wo) + Lambda(wi)) (Heitz 2014, Eq. 99); the caller
// tests that the microfacet faces both directions.
GLINT_FN float glintSmithG2(int ndf, vec2 alpha, float rho, vec3 wo, vec3 wi) {
  return 1.0f / (1.0f + glintSmithLambda(ndf, alpha, rho, wo) + glintSmithLambda(ndf, alpha, rho, wi));
}

// Smith G1(w) = 1 / (1 + Lambda(w)) (Heitz 2014, Eq. 43), for the visible normals' density.
GLINT_FN float glintSmithG1(int ndf, vec2 alpha, float rho, vec3 w) {
  return 1.0f / (1.0f + glintSmithLambda(ndf, alpha, rho, w));
}

// The Cook-Torrance frame with the chosen masking, without Fresnel and the cosine: V-cavity is
// glintMicrofacetReflectance (bit for bit); Smith uses the target's Lambda.
GLINT_FN float glintMaskedMicrofacetReflectance(int masking, int ndf, vec2 alpha, float rho, vec3 wo, vec3 wi, vec3 wh,
                                           float d) {
  if (masking != GLINT_MASKING_SMITH) {
    return glintMicrofacetReflectance(wo, wi, wh, d);
  }
  if (wo.z <= 0.0f || wi.z <= 0.0f || wh.z <= 0.0f || dot(wo, wh) <= 0.0f || dot(wi, wh) <= 0.0f) {
    return 0.0f;
  }
  return glintSmithG2(ndf, alpha, rho, wo, wi) * d / (4.0f * wo.z * wi.z);
}

// Cook-Torrance with the chosen target and masking, F = 1: (Beckmann, V-cavity) is
// glintCookTorranceReflectance; (GGX, Smith) glTF's metallic-roughness specular lobe.
GLINT_FN float glintTargetCookTorranceReflectance(int ndf, int masking, vec2 alpha, float rho, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) {
    return 0.0f;
  }
  vec3 wh = normalize(wo + wi);
  return glintMaskedMicrofacetReflectance(masking, ndf, alpha, rho, wo, wi, wh,
                                     glintNdfFromP22(glintTargetP22(ndf, glintSlopeFromNormal(wh), alpha, rho), wh.z));
}

GLINT_KERNEL_END

#endif
