// A glTF metal-roughness surface with an optional glint layer, assembled at a shading point for both
// renderers (shaders/forward.frag, which the page compiles too; src/trace/material.cpp), which look up
// their textures their own way and hand the samples here: the shading frame, the lobes' inputs and
// the glint layer's parameters are this file's (docs/architecture.md, "A glint parameter, from a glTF
// file to a pixel"); the lobes are the renderers'.
// glTF 2.0 metal-roughness (Khronos, glTF 2.0 specification, Appendix B): base colour, metallic and
// roughness as factor times texture; diffuse baseColour (1 - metallic) / pi; specular with Schlick's
// F0 = mix(0.04, baseColour, metallic); the normal map in the tangent frame.
#ifndef GLINT_KERNEL_SURFACE_H
#define GLINT_KERNEL_SURFACE_H

#include "prelude.h"
#include "glint_material.h"
#include "normal_map_filtering.h"

GLINT_KERNEL_BEGIN

// The least perceptual roughness both renderers shade a smooth lobe with: 0.03 (alpha 0.0009); a
// narrower lobe is finer than their sampling of it. The path tracer's CPU BSDFs raise alpha further,
// to 0.005 (roughness 0.07; glint_fields.h).
GLINT_CONST float GLINT_SURFACE_MIN_ROUGHNESS = 0.03f;

// What a renderer looked up at a shading point, in world space.
struct GlintSurfaceSamples {
  vec4 baseColour;         // baseColorFactor x texture x COLOR_0 (linear RGBA)
  vec2 metallicRoughness;  // metallicFactor x texture's B, roughnessFactor x texture's G
  vec3 emission;           // emissiveFactor (x strength) x texture
  float occlusion;         // 1 + strength (texture's R - 1): glTF occlusionTexture
  vec3 normal;             // the interpolated vertex normal (any length but 0)
  vec4 tangent;            // xyz the interpolated tangent along +u, w its handedness (+1 or -1)
  vec3 mappedNormal;       // the normal map's normal in the tangent frame (xy scaled by normalTexture.scale),
                           // or the filtered map's mean normal; (0, 0, 1) without a normal map
  vec3 view;               // unit, from the point towards the viewer
  vec3 glintSamples;       // the R channels of the glint layer's roughness, log-density and
                           // relative-area textures (1 where the layer has none)
  vec3 normalMapCovariance;  // the normal map's slope covariance over the footprint (xx, xy, yy;
                             // normal_map_filtering.h), 0 without normal-map filtering
};

// The surface as both renderers shade it.
struct GlintSurface {
  // The shading frame: n the mapped normal turned towards the viewer (a sheet seen from behind shows its
  // visible side), t the tangent re-orthogonalised, b = cross(n, t) times the tangent's handedness (the
  // frame may be left-handed; the layer's alpha_y and rho follow b).
  vec3 t;
  vec3 b;
  vec3 n;
  vec3 wo;           // the view direction in the frame, wo.z at least 1e-4 (grazing views stay lit)
  vec4 baseColour;   // its alpha the coverage that alphaMode MASK compares with the cutoff
  float metallic;
  float roughness;   // perceptual, in [GLINT_SURFACE_MIN_ROUGHNESS, 1]
  vec3 diffuse;      // Lambertian: baseColour (1 - metallic) / pi
  vec3 f0;           // Schlick's F0
  vec3 emission;
  float occlusion;
  // The specular lobe: the glint layer's (its textures applied, widened by the normal map's
  // covariance), else a smooth lobe of alpha = roughness^2.
  uint hasGlintLayer;
  GlintParameters glint;
  vec2 smoothAlpha;  // the lobe's roughness: glint.alpha with a layer, roughness^2 without
  float smoothRho;   // its slope correlation: glint.rho with a layer, 0 without
};

// A unit vector perpendicular to the unit vector n.
GLINT_FN vec3 glintAnyPerpendicular(vec3 n) {
  vec3 axis = abs(n.x) > 0.9f ? vec3(0.0f, 1.0f, 0.0f) : vec3(1.0f, 0.0f, 0.0f);
  return normalize(cross(axis, n));
}

// v orthogonalised against the unit n and normalised; `fallback` where nothing is left (degenerate
// mesh data).
GLINT_FN vec3 glintOrthogonalised(vec3 v, vec3 n, vec3 fallback) {
  vec3 w = v - n * dot(n, v);
  return dot(w, w) > 1e-12f ? normalize(w) : fallback;
}

// The surface at a shading point; `layer` the material's glint layer (enabled 0: none).
GLINT_FN GlintSurface glintSurface(GlintSurfaceSamples s, GlintMaterial layer, GlintFootprintPolicy policy) {
  GlintSurface surface;
  surface.baseColour = s.baseColour;
  surface.metallic = s.metallicRoughness.x;
  surface.roughness = clamp(s.metallicRoughness.y, GLINT_SURFACE_MIN_ROUGHNESS, 1.0f);
  surface.emission = s.emission;
  surface.occlusion = s.occlusion;

  // The shading frame (glTF: the normal map's xyz in the tangent, bitangent and normal).
  float handedness = s.tangent.w < 0.0f ? -1.0f : 1.0f;
  vec3 n = normalize(s.normal);
  vec3 t = glintOrthogonalised(vec3(s.tangent.x, s.tangent.y, s.tangent.z), n, glintAnyPerpendicular(n));
  vec3 b = cross(n, t) * handedness;
  vec3 mapped = t * s.mappedNormal.x + b * s.mappedNormal.y + n * s.mappedNormal.z;
  if (dot(mapped, mapped) > 0.0f) {
    n = normalize(mapped);
  }
  if (dot(n, s.view) < 0.0f) {
    n = -n;
  }
  t = glintOrthogonalised(t, n, t);
  surface.t = t;
  surface.b = cross(n, t) * handedness;
  surface.n = n;
  surface.wo = vec3(dot(s.view, t), dot(s.view, surface.b), max(dot(s.view, n), 1e-4f));

  vec3 base = vec3(s.baseColour.x, s.baseColour.y, s.baseColour.z);
  surface.diffuse = base * (1.0f - surface.metallic) / GLINT_PI;
  surface.f0 = clamp(glintMix(glintSplat3(0.04f), base, surface.metallic), glintSplat3(0.0f), glintSplat3(1.0f));

  // The glint layer from its textures' samples, widened by the normal map's slope covariance (Chermain
  // et al. 2021, I3D, section 5: the covariances add; a small-tilt approximation, as the authors').
  surface.hasGlintLayer = layer.enabled;
  surface.glint = glintMaterialParameters(layer, s.glintSamples.x, s.glintSamples.y, s.glintSamples.z, policy);
  vec3 widened = glintLeanCombinedRoughness(surface.glint.alpha, surface.glint.rho, s.normalMapCovariance);
  surface.glint.alpha = vec2(widened.x, widened.y);
  surface.glint.rho = widened.z;
  surface.smoothAlpha = layer.enabled != 0u ? surface.glint.alpha : glintSplat2(surface.roughness * surface.roughness);
  surface.smoothRho = layer.enabled != 0u ? surface.glint.rho : 0.0f;
  return surface;
}

GLINT_KERNEL_END

#endif
