// The clear coat over a surface: glTF's KHR_materials_clearcoat (Khronos, ratified; its section
// "Layering"), for both renderers (shaders/forward.frag, src/trace/material.cpp):
//   coated = mix(base, coat_brdf, c F_c),    F_c = 0.04 + 0.96 (1 - |v.n_c|)^5  (ior 1.5),
//   coat_brdf = D G / (4 |v.n_c| |l.n_c|),  GGX with height-correlated Smith, alpha = roughness^2,
// c = clearcoatFactor x texture R, roughness = clearcoatRoughnessFactor x texture G, n_c the coat's
// own normal map on the interpolated normal (the base's normal map does not tilt the coat). The
// extension takes the Fresnel at the view, not at the half vector, so the base is dimmed by one factor
// 1 - c F_c for every light: its diffuse, its glint layer or smooth lobe, its environment, and its
// emission (the last at the interpolated normal, glintCoatedEmissionWeight). The coat lobe has its
// own cosine, l.n_c, as the extension's Sample Viewer lights it.
// glint adds the coat lobe's multiple-scattering compensation (multiple_scattering.h, F = 1), so that
// the coat reflects all of the c F_c it takes from the base: under a white furnace a coated base keeps
// the base's albedo (tests/test_clearcoat.cpp). The extension's single-scattering lobe alone loses
// up to 1 - E(mu), at grazing views on rough coats. A shading-language host defines
// GLINT_ALBEDO_TABLES 1 (or GLINT_MULTIPLE_SCATTERING 1) before including the kernel.
#ifndef GLINT_KERNEL_CLEARCOAT_H
#define GLINT_KERNEL_CLEARCOAT_H

#include "prelude.h"
#include "microfacet_targets.h"
#include "multiple_scattering.h"
#include "surface.h"

GLINT_KERNEL_BEGIN

// The coat's F0: ior 1.5, ((1 - 1.5) / (1 + 1.5))^2.
GLINT_CONST float GLINT_COAT_F0 = 0.04f;

// What a renderer looked up for the coat at a shading point.
struct GlintCoatSamples {
  vec2 factorRoughness;  // clearcoatFactor x texture R, clearcoatRoughnessFactor x texture G
  vec3 mappedNormal;     // clearcoatNormalTexture's normal in the tangent frame (xy times its scale);
                         // (0, 0, 1) without one
};

// The coat at a shading point, in the surface's frame (GlintSurface t, b, n).
struct GlintCoat {
  float weight;  // c F_c: the share of the light the coat reflects and takes from the base
  float alpha;   // roughness^2, roughness clamped to [GLINT_SURFACE_MIN_ROUGHNESS, 1]
  vec3 t;        // the coat's own frame, n its normal
  vec3 b;
  vec3 n;
};

// Schlick's Fresnel of the coat.
GLINT_FN float glintCoatFresnel(float cosTheta) {
  float m = clamp(1.0f - cosTheta, 0.0f, 1.0f);
  float m2 = m * m;
  return GLINT_COAT_F0 + (1.0f - GLINT_COAT_F0) * m2 * m2 * m;
}

// The coat of `surface` (glintSurface of the same samples' normal, tangent and view).
GLINT_FN GlintCoat glintSurfaceCoat(GlintSurface surface, GlintSurfaceSamples s, GlintCoatSamples coatSamples) {
  // The coat's normal: its own map in the interpolated frame, turned towards the viewer as the
  // surface's is.
  float handedness = s.tangent.w < 0.0f ? -1.0f : 1.0f;
  vec3 n = normalize(s.normal);
  vec3 t = glintOrthogonalised(vec3(s.tangent.x, s.tangent.y, s.tangent.z), n, glintAnyPerpendicular(n));
  vec3 b = cross(n, t) * handedness;
  vec3 mapped = t * coatSamples.mappedNormal.x + b * coatSamples.mappedNormal.y + n * coatSamples.mappedNormal.z;
  vec3 world = dot(mapped, mapped) > 0.0f ? normalize(mapped) : n;
  if (dot(world, s.view) < 0.0f) {
    world = -world;
  }
  GlintCoat coat;
  coat.n = normalize(vec3(dot(world, surface.t), dot(world, surface.b), dot(world, surface.n)));
  coat.t = glintOrthogonalised(vec3(1.0f, 0.0f, 0.0f), coat.n, glintAnyPerpendicular(coat.n));
  coat.b = cross(coat.n, coat.t);
  float roughness = clamp(coatSamples.factorRoughness.y, GLINT_SURFACE_MIN_ROUGHNESS, 1.0f);
  coat.alpha = roughness * roughness;
  coat.weight = clamp(coatSamples.factorRoughness.x, 0.0f, 1.0f) * glintCoatFresnel(max(dot(surface.wo, coat.n), 0.0f));
  return coat;
}

// A direction of the surface's frame in the coat's.
GLINT_FN vec3 glintCoatLocal(GlintCoat coat, vec3 w) {
  return vec3(dot(w, coat.t), dot(w, coat.b), dot(w, coat.n));
}

// The coat's reflected share for light from wi towards wo (both in the surface's frame), times its
// own cosine: c F_c (coat_brdf + f_ms) max(l.n_c, 0). The host adds it to the base times
// 1 - coat.weight.
GLINT_FN float glintCoatReflectedCosine(GlintCoat coat, vec3 wo, vec3 wi) {
  vec3 o = glintCoatLocal(coat, wo);
  vec3 i = glintCoatLocal(coat, wi);
  if (o.z <= 0.0f || i.z <= 0.0f || coat.weight <= 0.0f) {
    return 0.0f;
  }
  vec2 alpha = glintSplat2(coat.alpha);
  float single = glintTargetCookTorranceReflectance(GLINT_NDF_GGX, GLINT_MASKING_SMITH, alpha, 0.0f, o, i);
  float multiple = glintMultipleScatteringReflectance(GLINT_NDF_GGX, GLINT_MASKING_SMITH, alpha, o, i);
  return coat.weight * (single + multiple) * i.z;
}

// The share of the emission the coat lets through towards `view` (unit): 1 - c F_c at the
// interpolated normal `normal` (any length but 0), so that the path tracer's light samples, which
// look up an emitter without its shading frame, find what its rays find.
GLINT_FN float glintCoatedEmissionWeight(float factor, vec3 normal, vec3 view) {
  return 1.0f - clamp(factor, 0.0f, 1.0f) * glintCoatFresnel(abs(dot(normalize(normal), view)));
}

GLINT_KERNEL_END

#endif
