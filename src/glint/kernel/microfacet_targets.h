// Past the 2020 paper's own limits (docs/method.md, "Targets and masking"): the smooth targets a
// glint layer converges to and the masking of its microfacets.
//
// 1. The GGX (Trowbridge-Reitz) slope distribution, with the slope correlation of microfacet.h:
//    Walter, Marschner, Li & Torrance 2007, "Microfacet Models for Refraction through Rough
//    Surfaces" (EGSR), Eq. 33 written in slope space. Its slopes are a bivariate Student t with
//    two degrees of freedom: a Gaussian (the Beckmann slopes of roughness alpha) whose covariance
//    is divided by w, w ~ Exp(1) (a scale mixture of Gaussians). The glint P-SDF reaches GGX by
//    drawing w per cell (glintCellPrecision): a dictionary cell is Beckmann-like glints of roughness
//    alpha / sqrt(w), so the mean over cells is exactly GGX. The heavy tail (w -> 0, cells wider
//    without bound) is cut at w = GLINT_GGX_TAIL_PRECISION: those cells, one in a hundred, reflect the
//    smooth remainder of the mixture over (0, GLINT_GGX_TAIL_PRECISION), in closed form (ggxTailP22), so
//    that the mean stays exactly GGX and no cell's support is more than 10 times the dictionary's.
// 2. Smith masking-shadowing, height-correlated, for the smooth target's Lambda: Heitz 2014,
//    "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs" (JCGT 3(2)), Eq. 99;
//    Lambda of Beckmann (Eq. 81, after Walter et al. 2007) and of GGX (Eq. 86), along the
//    direction's azimuth for anisotropic, correlated slopes (Heitz 2014 section 5.3: the projected
//    roughness is the slopes' deviation along that azimuth).
// Shared by the CPU library and the GLSL renderer: see prelude.h for the rules.
#ifndef GLINT_KERNEL_MICROFACET_TARGETS_H
#define GLINT_KERNEL_MICROFACET_TARGETS_H

#include "prelude.h"
#include "random.h"
#include "microfacet.h"

GLINT_KERNEL_BEGIN

// The smooth target's normal distribution (GlintParameters::ndf, `ndf` in extras.glint and eval).
GLINT_CONST int GLINT_NDF_BECKMANN = 0;  // the 2020 paper's
GLINT_CONST int GLINT_NDF_GGX = 1;       // glTF's
// The masking of the microfacets (GlintParameters::masking, `masking`).
GLINT_CONST int GLINT_MASKING_VCAVITY = 0;  // the 2020 paper's
GLINT_CONST int GLINT_MASKING_SMITH = 1;    // height-correlated Smith, glTF's

// ---- 1. GGX ----------------------------------------------------------------------------------

// The GGX slope distribution of roughness alpha and slope correlation rho, as a Student t of scale
// covariance Sigma (the Beckmann covariance of the same alpha and rho, glintBeckmannSlopeCovariance):
// P22 = 1 / (2 pi sqrt(det Sigma) (1 + q / 2)^2), q = s^T Sigma^-1 s. For rho = 0 it is
// 1 / (pi alpha_x alpha_y (1 + x^2 / alpha_x^2 + y^2 / alpha_y^2)^2).
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

// The per-cell precision w of the scale mixture is cut at this value: P(w < 0.01) = 1 - e^-0.01,
// about 1%, and a dictionary cell is at most 1 / sqrt(0.01) = 10 times wider than the target's
// Beckmann (docs/method.md, "GGX target", which measures the choice).
GLINT_CONST float GLINT_GGX_TAIL_PRECISION = 0.01f;
GLINT_CONST float GLINT_GGX_TAIL_PROBABILITY = 0.00995016625f;  // 1 - exp(-GLINT_GGX_TAIL_PRECISION)
GLINT_CONST float GLINT_GGX_WIDEST_CELL = 10.0f;                // 1 / sqrt(GLINT_GGX_TAIL_PRECISION)

// 1 - e^-x (1 + x), without the cancellation of that form for small x (its series below 0.1:
// x^2/2 - x^3/3 + x^4/8 - x^5/30, the next term under 2e-6 of the sum); 1 from x = 100 on, where
// e^-x (1 + x) is below 1e-41 (and an infinite x would make it 0 times infinity).
GLINT_FN float glintOneMinusExpTimesOnePlus(float x) {
  if (x < 0.1f) {
    return x * x * (0.5f + x * (-0.333333333f + x * (0.125f + x * -0.0333333333f)));
  }
  return x < 100.0f ? 1.0f - exp(-x) * (1.0f + x) : 1.0f;
}

// The smooth remainder of the GGX scale mixture, normalised: the mixture of the Gaussians of
// covariance Sigma / w over w < GLINT_GGX_TAIL_PRECISION, weighted by e^-w, divided by its mass
// GLINT_GGX_TAIL_PROBABILITY. With b = 1 + q / 2 and W the cut, the integral of e^-w w / (2 pi sqrt(det
// Sigma)) e^(-w q / 2) over (0, W) is (1 - e^(-b W) (1 + b W)) / (2 pi sqrt(det Sigma) b^2).
GLINT_FN float glintStudentTailSlopeP22(vec2 slope, vec3 covariance) {
  float determinant = covariance.x * covariance.z - covariance.y * covariance.y;
  float q = (covariance.z * slope.x * slope.x - 2.0f * covariance.y * slope.x * slope.y +
             covariance.x * slope.y * slope.y) / determinant;
  float b = 1.0f + 0.5f * q;
  return glintOneMinusExpTimesOnePlus(b * GLINT_GGX_TAIL_PRECISION) /
         (2.0f * GLINT_PI * sqrt(determinant) * b * b * GLINT_GGX_TAIL_PROBABILITY);
}

// A cell's draw of the mixture's precision w ~ Exp(1), from the y lane of a second hash of the
// cell's (the first's four lanes are the 2020 model's draws, and glintCellChroma takes the 8 low
// bits they leave of two lanes: too few for w's tail).
GLINT_FN float glintCellPrecision(uvec4 h) {
  return -log(glintHashToUnitOpen(glintPcg4d(h).y));
}

// The smooth target's P22.
GLINT_FN float glintTargetP22(int ndf, vec2 slope, vec2 alpha, float rho) {
  return ndf == GLINT_NDF_GGX ? glintGgxP22(slope, alpha, rho) : glintBeckmannP22(slope, alpha, rho);
}

// The widest a dictionary cell of the target is, relative to the Beckmann scaling: 1 for
// Beckmann, GLINT_GGX_WIDEST_CELL for GGX.
GLINT_FN float glintTargetWidestCell(int ndf) {
  return ndf == GLINT_NDF_GGX ? GLINT_GGX_WIDEST_CELL : 1.0f;
}

// ---- 2. Smith masking ------------------------------------------------------------------------

// Lambda(w) of the smooth target (Heitz 2014, Eqs. 81 and 86), for slopes of covariance
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

// Height-correlated Smith G2 = 1 / (1 + Lambda(wo) + Lambda(wi)) (Heitz 2014, Eq. 99); the
// microfacet must face both directions (the caller's test).
GLINT_FN float glintSmithG2(int ndf, vec2 alpha, float rho, vec3 wo, vec3 wi) {
  return 1.0f / (1.0f + glintSmithLambda(ndf, alpha, rho, wo) + glintSmithLambda(ndf, alpha, rho, wi));
}

// Smith G1(w) = 1 / (1 + Lambda(w)) (Heitz 2014, Eq. 43), for the visible normals' density.
GLINT_FN float glintSmithG1(int ndf, vec2 alpha, float rho, vec3 w) {
  return 1.0f / (1.0f + glintSmithLambda(ndf, alpha, rho, w));
}

// The Cook-Torrance frame around any NDF value D(wh) with the chosen masking, Fresnel excluded,
// without the cosine. V-cavity is glintMicrofacetReflectance itself (bit for bit); Smith uses the
// target's Lambda (ndf, alpha, rho).
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

// Cook-Torrance with the chosen target and masking, F = 1: with (Beckmann, V-cavity) it is
// glintCookTorranceReflectance; with (GGX, Smith) glTF's metallic-roughness specular lobe.
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
