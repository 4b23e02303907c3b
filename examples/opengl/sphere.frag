#version 450 core
// glint_opengl's fragment shader: a dielectric sphere whose specular lobe is the glint BRDF, under
// one point light and a uniform sky. The model comes from glint's installed kernel headers; this
// file supplies what the kernel leaves to its host (docs/integration.md, "The kernel in your
// shaders"): the dictionary hook, the material block and the lighting.
//
// #include is resolved by GL_ARB_shading_language_include: main.cpp makes every file of glint's
// installed shader folder a named string under /glint and compiles this shader with /glint as its
// include path, so the kernel's own includes ("prelude.h", ...) resolve beside glint_kernel.h.
#extension GL_ARB_shading_language_include : require
#include "glint_kernel.h"

in vec3 vPosition;
in vec3 vNormal;
in vec4 vTangent;
in vec2 vUv;

layout(location = 0) out vec4 outRadiance;

// The glint layer, filled on the CPU as a glint::kernel::GlintMaterial: one layout in C++ and std140.
layout(std140, binding = 0) uniform MaterialBlock { GlintMaterial uGlintMaterial; };
uniform vec3 uBaseColour;

uniform vec3 uCameraPosition;
uniform vec3 uLightPosition;
uniform vec3 uLightIntensity;  // W/sr
uniform vec3 uSkyRadiance;     // the same from every direction

// ---- The dictionary hook (prelude.h) ------------------------------------------------------------
// The texels as glint::Dictionary::texels() gives them: distribution after distribution, level after
// level, R floats each, in a storage buffer. This is the example's own binding, not glint's
// renderer's (installed as glint_dictionary_gl.glsl, which reads buffer textures of texel pairs
// through uniforms named for glint's renderer): a host binds the texels the way it binds its data.
layout(std430, binding = 0) readonly buffer GlintDictionaryTexels { float uGlintTexels[]; };
uniform ivec3 uGlintDictionaryShape;  // levels, distributions, texels per distribution
uniform float uGlintDictionaryAlpha;  // alpha_d

GlintDictionaryView glintDictionary() {
  GlintDictionaryView dict;
  dict.numLevels = uGlintDictionaryShape.x;
  dict.numDistributions = uGlintDictionaryShape.y;
  dict.texelsPerDistribution = uGlintDictionaryShape.z;
  dict.alpha = uGlintDictionaryAlpha;
  dict.numMips = 1;  // no mip chain: only the anti-aliased P-SDF reads one
  dict.mipRowLength = uGlintDictionaryShape.z;
  return dict;
}

// Texels k and k + 1 of one marginal, 0 past its last texel.
vec2 glintDictionaryTexelPair(GlintDictionaryView dict, int level, int distribution, int texel) {
  int first = (level * dict.numDistributions + distribution) * dict.texelsPerDistribution;
  float next = texel + 1 < dict.texelsPerDistribution ? uGlintTexels[first + texel + 1] : 0.0f;
  return vec2(uGlintTexels[first + texel], next);
}

// Defined because the kernel declares it; this shader calls the unfiltered P-SDF, which never reads it.
vec4 glintDictionaryFilteredTexels(GlintDictionaryView dict, int level, int distribution, int index) {
  return vec4(glintDictionaryTexelPair(dict, level, distribution, index), 0.0f, 0.0f);
}

// ---- Shading ------------------------------------------------------------------------------------
void main() {
  // The footprint first, in uniform control flow: the glint uv's screen derivatives.
  vec2 glintUv = glintMaterialUv(uGlintMaterial, vUv);
  vec2 duvdx = dFdx(glintUv);
  vec2 duvdy = dFdy(glintUv);

  // The shading frame: z the normal (turned to the camera where interpolation tilts it away, at the
  // silhouette), x the tangent made perpendicular to it, y = cross(z, x) times the handedness.
  vec3 view = normalize(uCameraPosition - vPosition);
  vec3 n = normalize(vNormal);
  if (dot(n, view) < 0.0f) {
    n = -n;
  }
  vec3 t = normalize(vTangent.xyz - n * dot(n, vTangent.xyz));
  vec3 b = cross(n, t) * (vTangent.w < 0.0f ? -1.0f : 1.0f);
  vec3 wo = vec3(dot(view, t), dot(view, b), max(dot(view, n), 1e-4f));

  // No glint textures: each sample is 1. The paper's footprint (the zero policy).
  GlintFootprintPolicy exactFootprint;
  exactFootprint.maxAnisotropy = 0.0f;
  exactFootprint.maxCells = 0.0f;
  exactFootprint.minBlend = 0.0f;
  GlintParameters params = glintMaterialParameters(uGlintMaterial, 1.0f, 1.0f, 1.0f, exactFootprint);

  vec3 f0 = vec3(0.04f);  // a dielectric's reflectance at normal incidence
  vec3 diffuse = uBaseColour / GLINT_PI;
  // The sky: irradiance pi L on the Lambertian part, L times Fresnel on the specular one.
  vec3 radiance = diffuse * GLINT_PI * uSkyRadiance + glintFresnelSchlick(f0, wo.z) * uSkyRadiance;

  vec3 toLight = uLightPosition - vPosition;
  vec3 l = normalize(toLight);
  vec3 wi = vec3(dot(l, t), dot(l, b), dot(l, n));
  if (wi.z > 0.0f) {
    vec3 wh = normalize(wo + wi);
    // The glint BRDF for one light (F = 1, no cosine) times Schlick's Fresnel at the half vector.
    vec3 specular = glintFresnelSchlick(f0, dot(wo, wh)) *
                    glintReflectance(glintDictionary(), params, glintUv, duvdx, duvdy, wo, wi);
    radiance += (diffuse + specular) * wi.z * uLightIntensity / dot(toLight, toLight);
  }
  outRadiance = vec4(radiance, 1.0f);
}
