// Multiple scattering as a compensation lobe: Kulla & Conty 2017, "Revisiting Physically Based
// Shading at Imageworks" (SIGGRAPH course "Physically Based Shading in Theory and Practice"), after
// Jakob et al. 2014 and Turquin 2019's form of the energy lost (docs/method.md 6.3):
//   f_ms(wo, wi) = (1 - E(mu_o)) (1 - E(mu_i)) / (pi (1 - E_avg)),
// E(mu) the single-scattering lobe's directional albedo (F = 1), E_avg = 2 integral of E(mu) mu dmu,
// so that with F = 1 the albedo of f + f_ms is 1 at every view angle. With Fresnel, f_ms is times
// F_avg^2 E_avg / (1 - F_avg (1 - E_avg)), F_avg the cosine-weighted hemispherical mean of F (each
// further bounce keeps F_avg). E and E_avg are glint's tables (kernel/albedo_tables.h, `glint
// albedo-tables`) per target and masking, for isotropic roughness; an anisotropic or correlated lobe
// reads alpha = sqrt(alpha_x alpha_y). The glint BRDF adds its smooth target's lobe: its mean over
// positions has the target's albedo. Shading languages include the tables only with
// GLINT_MULTIPLE_SCATTERING 1 or GLINT_ALBEDO_TABLES 1 (the tables without the base's lobe, for the
// clear coat's, clearcoat.h).
#ifndef GLINT_KERNEL_MULTIPLE_SCATTERING_H
#define GLINT_KERNEL_MULTIPLE_SCATTERING_H

#include "prelude.h"
#include "microfacet.h"
#include "microfacet_targets.h"

GLINT_KERNEL_BEGIN

// The tables' grid: mu_j = (j / 31)^2, alpha_i = 2 (i / 31)^2, denser at grazing views and smooth
// surfaces, where E changes fastest; bilinear in (sqrt(mu), sqrt(alpha / 2)), clamped (alpha above 2
// reads 2).
GLINT_CONST int GLINT_ALBEDO_MU_NODES = 32;
GLINT_CONST int GLINT_ALBEDO_ALPHA_NODES = 32;
GLINT_CONST float GLINT_ALBEDO_MAX_ALPHA = 2.0f;

// The table of a target and masking: 2 ndf + masking.
GLINT_FN int glintAlbedoTableIndex(int ndf, int masking) {
  return 2 * ndf + masking;
}

// The grid coordinates of mu and alpha, in nodes.
GLINT_FN float glintAlbedoMuCoordinate(float mu) {
  return sqrt(clamp(mu, 0.0f, 1.0f)) * float(GLINT_ALBEDO_MU_NODES - 1);
}

GLINT_FN float glintAlbedoAlphaCoordinate(float alpha) {
  return sqrt(clamp(alpha, 0.0f, GLINT_ALBEDO_MAX_ALPHA) / GLINT_ALBEDO_MAX_ALPHA) * float(GLINT_ALBEDO_ALPHA_NODES - 1);
}

// The isotropic roughness whose table an anisotropic, correlated lobe reads.
GLINT_FN float glintCompensationAlpha(vec2 alpha) {
  return sqrt(alpha.x * alpha.y);
}

// Schlick's F_avg: 2 integral of (f0 + (1 - f0)(1 - mu)^5) mu dmu = f0 + (1 - f0) / 21.
GLINT_FN vec3 glintSchlickAverageFresnel(vec3 f0) {
  return f0 + (glintSplat3(1.0f) - f0) * (1.0f / 21.0f);
}

// The Fresnel factor of the compensation lobe: F_avg^2 E_avg / (1 - F_avg (1 - E_avg)) (1 with F = 1).
GLINT_FN vec3 glintMultipleScatteringFresnel(vec3 averageFresnel, float averageAlbedo) {
  return averageFresnel * averageFresnel * averageAlbedo /
         (glintSplat3(1.0f) - averageFresnel * (1.0f - averageAlbedo));
}

GLINT_KERNEL_END

#if defined(__cplusplus) || GLINT_MULTIPLE_SCATTERING || GLINT_ALBEDO_TABLES
// The tables' values. A shading-language host may define GLINT_ALBEDO_TABLE_HOOK 1 and then define,
// like the dictionary hook, the two functions below, reading GLINT_ALBEDO_WORDS and
// GLINT_AVERAGE_ALBEDO_WORDS from a buffer it binds as R16_UNORM texels: glslang's SPIR-V copies a
// large constant array into a local at each dynamic read, and Mesa's lavapipe made each read a branch
// per element, taking the test shader's compile from 6 s to over 15 minutes (docs/integration.md).
#if !defined(__cplusplus) && defined(GLINT_ALBEDO_TABLE_HOOK) && GLINT_ALBEDO_TABLE_HOOK
float glintAlbedoTableValue(int index);         // GLINT_ALBEDO_TABLE_NODE(GLINT_ALBEDO_WORDS, index)
float glintAverageAlbedoTableValue(int index);  // GLINT_ALBEDO_TABLE_NODE(GLINT_AVERAGE_ALBEDO_WORDS, index)
#define GLINT_ALBEDO_AT(index) glintAlbedoTableValue(index)
#define GLINT_AVERAGE_ALBEDO_AT(index) glintAverageAlbedoTableValue(index)
#else
#include "albedo_tables.h"
// Node `index` of a table: 16-bit unorm values, two a 32-bit word, the first in the low half (half
// the text of the shortest float literals, within 7.7e-6 of them).
#define GLINT_ALBEDO_TABLE_NODE(words, index) \
  (float(((words)[(index) / 2] >> (((index) % 2 == 1) ? 16u : 0u)) & 0xffffu) * (1.0f / 65535.0f))
#define GLINT_ALBEDO_AT(index) GLINT_ALBEDO_TABLE_NODE(GLINT_ALBEDO_WORDS, index)
#define GLINT_AVERAGE_ALBEDO_AT(index) GLINT_ALBEDO_TABLE_NODE(GLINT_AVERAGE_ALBEDO_WORDS, index)
#endif

GLINT_KERNEL_BEGIN

// E(mu) of the single-scattering lobe of roughness alpha (isotropic), F = 1.
GLINT_FN float glintDirectionalAlbedo(int ndf, int masking, float alpha, float mu) {
  float x = glintAlbedoMuCoordinate(mu);
  float y = glintAlbedoAlphaCoordinate(alpha);
  int i = min(int(y), GLINT_ALBEDO_ALPHA_NODES - 2);
  int j = min(int(x), GLINT_ALBEDO_MU_NODES - 2);
  float fy = y - float(i);
  float fx = x - float(j);
  int base = (glintAlbedoTableIndex(ndf, masking) * GLINT_ALBEDO_ALPHA_NODES + i) * GLINT_ALBEDO_MU_NODES + j;
  float low = glintMix(GLINT_ALBEDO_AT(base), GLINT_ALBEDO_AT(base + 1), fx);
  float high = glintMix(GLINT_ALBEDO_AT(base + GLINT_ALBEDO_MU_NODES), GLINT_ALBEDO_AT(base + GLINT_ALBEDO_MU_NODES + 1), fx);
  return glintMix(low, high, fy);
}

// E_avg of the lobe of roughness alpha.
GLINT_FN float glintAverageAlbedo(int ndf, int masking, float alpha) {
  float y = glintAlbedoAlphaCoordinate(alpha);
  int i = min(int(y), GLINT_ALBEDO_ALPHA_NODES - 2);
  int base = glintAlbedoTableIndex(ndf, masking) * GLINT_ALBEDO_ALPHA_NODES + i;
  return glintMix(GLINT_AVERAGE_ALBEDO_AT(base), GLINT_AVERAGE_ALBEDO_AT(base + 1), y - float(i));
}

// f_ms(wo, wi) with F = 1, without the cosine; 0 below either horizon.
GLINT_FN float glintMultipleScatteringReflectance(int ndf, int masking, vec2 alpha, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) {
    return 0.0f;
  }
  float a = glintCompensationAlpha(alpha);
  float average = glintAverageAlbedo(ndf, masking, a);
  return (1.0f - glintDirectionalAlbedo(ndf, masking, a, wo.z)) * (1.0f - glintDirectionalAlbedo(ndf, masking, a, wi.z)) /
         (GLINT_PI * max(1.0f - average, 1e-6f));
}

GLINT_KERNEL_END

#endif

#endif
