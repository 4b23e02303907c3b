// Importance sampling of microfacet normals, host only (docs/sampling.md): the glint P-SDF as the
// finite mixture it is (Chermain, Sauvage, Dischler, Dachsbacher 2021, "Importance Sampling of
// Glittering BSDFs based on Finite Mixture Distributions", EGSR; method.md section 5), the
// Beckmann slope distribution, visible normals of the V-cavity model (Heitz & d'Eon 2014), and the
// dielectric interface (Walter, Marschner, Li & Torrance 2007). The BSDF classes of bsdf.h build
// their sample() and pdf() from these; the densities they sample are the kernel's (glint_brdf.h),
// whose per-cell draws are reused, never re-implemented.
//
// Random numbers: every function takes uniforms in [0, 1). Where one uniform makes several
// discrete choices in turn, each choice rescales it to [0, 1) for the next (remapUniform).
#pragma once

#include <optional>

#include <glm/glm.hpp>

#include "glint/kernel/glint_brdf.h"

namespace glint::sampling {

// The largest float below 1: rescaled uniforms are clamped to it so they stay in [0, 1).
inline constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

// A uniform u that fell in [low, low + width) rescaled to [0, 1).
float remapUniform(float u, float low, float width);

// Cosine-weighted direction about +z (Malley's method on a concentric disk); pdf = z / pi. The
// diffuse lobe of the path tracer's materials and the multiple-scattering compensation lobe.
glm::vec3 sampleCosineHemisphere(glm::vec2 u);
inline float cosineHemispherePdf(float cosTheta) { return cosTheta > 0.0f ? cosTheta / 3.14159265358979f : 0.0f; }

// A microfacet normal from its slope: m = (-x, -y, 1) / sqrt(1 + x^2 + y^2) (method.md, notation).
glm::vec3 normalFromSlope(glm::vec2 slope);

// A slope of the anisotropic Beckmann P22 with correlation rho (microfacet.h, glintBeckmannP22): a
// centred Gaussian of std alpha / sqrt(2) per axis and correlation rho, by the Box-Muller transform
// and the covariance's Cholesky factor.
glm::vec2 sampleBeckmannSlope(glm::vec2 alpha, float rho, glm::vec2 u);

// A slope of the GGX P22 (kernel/microfacet_targets.h, glintGgxP22): the Student t's radius t = q / 2
// has the CDF 1 - 1 / (1 + t), inverted, then the same angle and Cholesky factor as Beckmann's.
glm::vec2 sampleGgxSlope(glm::vec2 alpha, float rho, glm::vec2 u);

// A slope of the GGX scale mixture's smooth remainder (glintStudentTailSlopeP22): its radius t = q / 2
// has P(T > t) = (1 - e^(-(1 + t) W)) / ((1 + t) (1 - e^-W)), W = GLINT_GGX_TAIL_PRECISION, inverted by
// bisection in double.
glm::vec2 sampleGgxTailSlope(glm::vec2 alpha, float rho, glm::vec2 u);

// A slope of the smooth target (kernel::GLINT_NDF_BECKMANN or GLINT_NDF_GGX).
glm::vec2 sampleTargetSlope(int ndf, glm::vec2 alpha, float rho, glm::vec2 u);

// A signed dictionary-space slope of distribution `distribution` at level `level`, by inverting
// the CDF of the kernel's piecewise-linear marginal (glintMarginal: texel k at slope k 4 sigma_d / R,
// linear between texels, falling to 0 at 4 sigma_d). The marginal is even: u < 1/2 picks the
// negative side, u >= 1/2 the positive one, and within each |x| follows the CDF of one half, so that
// x is monotonic in u (the inverse of the full CDF). With `complement` 1, the marginal of a
// consistent-LOD block (kernel glintBlockMarginal): the lobes that level + 1 adds to `level`.
float sampleDictionaryMarginal(kernel::GlintDictionaryView dict, int level, int distribution, int complement, float u);

// A slope of the P-SDF P22_P (method.md 2.3-2.5, section 5): the LOD il or il + 1 by the blend
// weight, a cell of that level by its normalised EWA weight (the cells glintLevelP22 visits, with
// its weights), the cell's random properties regenerated with the kernel's own functions, then a
// slope of that cell's P22: the smooth target in the smooth limit, the GGX remainder in a GGX tail
// cell, else the tensor product of two marginals, rotated and scaled (for GGX, by the cell's own
// scale too). Returns nullopt when the chosen cell holds no microfacets (relative area
// mask) or the level has no cell: with probability 1 - integral of P22_P. `uChoice` makes the
// discrete choices and comes back rescaled to [0, 1), for the caller's next choice.
std::optional<glm::vec2> sampleGlintSlope(kernel::GlintDictionaryView dict, const kernel::GlintParameters& params,
                                          glm::vec2 uv, glm::vec2 duvdx, glm::vec2 duvdy, float& uChoice,
                                          glm::vec2 u);

// Visible normals of the V-cavity model (Heitz & d'Eon 2014, "Importance Sampling Microfacet-Based
// BSDFs using the Distribution of Visible Normals", section 5): given m drawn from D(m) m.z with D
// even, the V-cavity made of m and its mirror m' = (-m.x, -m.y, m.z) shows m' with probability
// <wo, m'>+ / (<wo, m>+ + <wo, m'>+); the normal so picked follows visibleNdf. wo.z > 0. `u` comes
// back rescaled to [0, 1).
glm::vec3 sampleVCavityVisibleNormal(glm::vec3 wo, glm::vec3 m, float& u);

// The distribution of visible normals D_wo(m) = G1(wo, m) <wo, m>+ D(m) / wo.z (Heitz 2014, Eq. 2)
// with V-cavity G1, given D(m). wo.z > 0; 0 for m.z <= 0.
float visibleNdf(glm::vec3 wo, glm::vec3 m, float ndf);

// V-cavity G1 on either side of the surface: min(1, |2 m.z w.z / (w.m)|) when w sees the front of
// m from its side (sign(w.m) = sign(w.z)), else 0. m.z > 0.
float vcavityG1TwoSided(glm::vec3 w, glm::vec3 m);

// Fresnel reflectance of a dielectric interface, unpolarised, exact (Born & Wolf; pbrt-v4
// FrDielectric): eta = n_inside / n_outside, cosThetaI = <w, m> with m on the outside; a negative
// cosine means w is inside. 1 under total internal reflection.
float fresnelDielectric(float cosThetaI, float eta);

// Refraction of w (pointing away from the interface) through a microfacet of normal m (m.z > 0)
// with eta = n_inside / n_outside; the result points away on the other side. nullopt under total
// internal reflection.
std::optional<glm::vec3> refractDirection(glm::vec3 w, glm::vec3 m, float eta);

}  // namespace glint::sampling
