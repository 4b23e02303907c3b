// Forward shading of glTF metal-roughness materials whose specular lobe is the glint BRDF (or
// Cook-Torrance), lit by point, spot and directional lights and an environment (diffuse by spherical
// harmonics, specular by a pre-filtered map, both without glints). The host compiles one program
// per specular model, SPECULAR_MODEL = SPECULAR_GLINT, SPECULAR_COOK_TORRANCE, SPECULAR_ZIRR_KAPLANYAN
// or SPECULAR_ZIRR_KAPLANYAN_REFERENCE (the same values on the reference shader's schedule), so that
// each carries only its own code and everything else is identical;
// glint materials with coloured cells get their own program (GLINT_COLOURED_CELLS = 1), glint
// programs that anti-alias their glints (GLINT_FILTERED = 1, glint_antialiasing.h) theirs, those
// that also filter their normal map (GLINT_LEAN = 1, normal_map_filtering.h) or read it at its
// finest level (NORMAL_MAP_FINEST = 1, the anti-aliasing reference) theirs, and so do
// glTF alphaMode MASK materials (ALPHA_MASK = 1), materials with KHR_texture_transform
// (TEXTURE_TRANSFORMS = 1) and meshes with vertex colours (VERTEX_COLOURS = 1). The light count is
// compiled in too (LIGHT_COUNT, at most 8): glint programs evaluate every light's P-SDF over one
// walk of the footprint's cells (glintP22Set, GLINT_SLOPE_COUNT slopes). With SHADOWS = 1 the
// lights cast shadows (shadows.glsl). Materials with a KHR_materials_clearcoat coat get their own
// program too (CLEARCOAT = 1, kernel/clearcoat.h): everything the base reflects and emits is dimmed
// by the coat's Fresnel, and the coat's lobe added under every light. The material's glint layer is
// one uniform block, a GlintMaterial (glint_material_block.glsl, kernel/glint_material.h).
#define SPECULAR_GLINT 0
#define SPECULAR_COOK_TORRANCE 1
#define SPECULAR_ZIRR_KAPLANYAN 2
#define SPECULAR_ZIRR_KAPLANYAN_REFERENCE 3
#define ZIRR_KAPLANYAN (SPECULAR_MODEL == SPECULAR_ZIRR_KAPLANYAN || SPECULAR_MODEL == SPECULAR_ZIRR_KAPLANYAN_REFERENCE)
// One slope per light; also the size of the light arrays below (a GLSL array cannot be empty).
#define GLINT_SLOPE_COUNT (LIGHT_COUNT > 0 ? LIGHT_COUNT : 1)
// The specular lobe's smooth target and masking (microfacet_targets.h), compiled in: the paper's
// Beckmann with V-cavity unless the host defines them.
#ifndef GLINT_NDF
#define GLINT_NDF 0
#endif
#if CLEARCOAT
// The coat's lobe reads the albedo tables for its compensation, whatever the base's target.
#define GLINT_ALBEDO_TABLES 1
#endif
#ifndef GLINT_MASKING
#define GLINT_MASKING 0
#endif
// The glint layer's LOD construction (glint_lod.h, glintLodCell), compiled in likewise: the
// paper's unless the host defines GLINT_LOD_CONSTRUCTION as another (GLINT_LOD_CONSISTENT 1,
// GLINT_LOD_TREE 2).
#ifndef GLINT_LOD_CONSTRUCTION
#define GLINT_LOD_CONSTRUCTION 0
#endif
#include "glint_brdf.h"
// The environment's brightest regions and the scene's area lights (emissive rectangles), drawn
// analytically in every program (REGION_COUNT, AREA_LIGHT_COUNT, compiled in like LIGHT_COUNT):
// glint programs walk the footprint's cells once for all of them.
#define EXTENDED_LIGHT_COUNT (REGION_COUNT + AREA_LIGHT_COUNT)
#if EXTENDED_LIGHT_COUNT > 0
#define GLINT_REGION_COUNT EXTENDED_LIGHT_COUNT
#include "glint_extended_lights.h"
#endif
#include "glint_material_block.glsl"
#include "surface.h"
#include "multiple_scattering.h"
#if CLEARCOAT
#include "clearcoat.h"
#endif
#include "normal_map_filtering.h"
#include "lights.h"
#include "glint_dictionary_gl.glsl"
#include "environment.glsl"
#if ZIRR_KAPLANYAN
#include "zirr_kaplanyan.h"
#endif

// With several samples a pixel (CENTROID_SHADING = 1, src/gl/renderer.cpp) a surface that covers
// only some of them, on an edge, is shaded at their centroid, inside it, not at the pixel's centre
// beyond its silhouette, where the normal would have turned away from the camera; the uv stays at
// the centre, so that the glint footprint, its screen derivatives, is the one-sample frame's.
#if CENTROID_SHADING
#define SHADING_POINT centroid
#else
#define SHADING_POINT
#endif
SHADING_POINT in vec3 vPosition;
SHADING_POINT in vec3 vNormal;
SHADING_POINT in vec4 vTangent;
in vec2 vUv;
in vec4 vColour;  // glTF COLOR_0

layout(location = 0) out vec4 outRadiance;

// Texture units; unit 0 is the dictionary (glint_dictionary_gl.glsl), 9 the environment
// (environment.glsl).
layout(binding = 1) uniform sampler2D uBaseColourTexture;
layout(binding = 2) uniform sampler2D uMetallicRoughnessTexture;
layout(binding = 3) uniform sampler2D uNormalTexture;
layout(binding = 4) uniform sampler2D uEmissiveTexture;
layout(binding = 5) uniform sampler2D uOcclusionTexture;
layout(binding = 6) uniform sampler2D uGlintRoughnessTexture;
layout(binding = 7) uniform sampler2D uGlintLogDensityTexture;
layout(binding = 8) uniform sampler2D uGlintRelativeAreaTexture;
#if CLEARCOAT
uniform vec2 uClearcoat;  // clearcoatFactor, clearcoatRoughnessFactor
#if CLEARCOAT_TEXTURES
// Only where the coat has textures (CLEARCOAT_TEXTURES = 1): OpenGL and WebGL2 promise 16 samplers
// a stage, which units 0 to 15 already fill in the largest programs.
layout(binding = 16) uniform sampler2D uClearcoatTexture;
layout(binding = 17) uniform sampler2D uClearcoatRoughnessTexture;
layout(binding = 18) uniform sampler2D uClearcoatNormalTexture;
uniform float uClearcoatNormalScale;
uniform mat3x2 uClearcoatUv;
uniform mat3x2 uClearcoatRoughnessUv;
uniform mat3x2 uClearcoatNormalUv;
#endif
#endif
#if GLINT_LEAN
// The normal map's slope moments (normal_map_filtering.h): (E[sx], E[sy], E[sx^2]), (E[sy^2], E[sx sy], 0).
layout(binding = 11) uniform sampler2D uLeanFirstMoments;
layout(binding = 12) uniform sampler2D uLeanSecondMoments;
#endif

uniform vec4 uCameraPoint;  // the camera's position (w = 1), or for an orthographic camera the direction towards it (w = 0)
uniform vec4 uBaseColour;
uniform float uMetallic;
uniform float uRoughness;
uniform float uNormalScale;
uniform vec3 uEmissive;
uniform float uOcclusionStrength;  // glTF occlusionTexture.strength
// Each texture's glTF KHR_texture_transform: uv' = M * vec3(uv, 1) (scene::UvTransform::matrix).
uniform mat3x2 uBaseColourUv;
uniform mat3x2 uMetallicRoughnessUv;
uniform mat3x2 uNormalUv;
uniform mat3x2 uEmissiveUv;
uniform mat3x2 uOcclusionUv;
uniform float uAlphaCutoff;  // alphaMode MASK (ALPHA_MASK = 1): the alpha below which nothing is drawn

// Whether the material has a glint layer (its roughness is then the layer's). Glint and Zirr &
// Kaplanyan programs draw only such materials (src/gl/renderer.cpp, forwardVariant), so for them
// it is a constant and the Cook-Torrance side of their branches is compiled out: llvmpipe would
// run it for every pixel.
#if SPECULAR_MODEL == SPECULAR_COOK_TORRANCE
#define GLINT_LAYER (uGlintMaterial.enabled != 0u)
#else
#define GLINT_LAYER true
#endif
// The frame's glint settings (the material's are uGlintMaterial, glint_material_block.glsl).
uniform float uGlintFilterScale;  // the anti-aliasing kernel's size: 1 matches the pixel's box
uniform vec3 uGlintFootprintPolicy;  // GlintFootprintPolicy: aniso, cells, drop (0: the paper's footprint)

uniform vec4 uLightPosition[GLINT_SLOPE_COUNT];  // w = 1: point or spot at xyz; w = 0: xyz = unit direction towards the light
uniform vec3 uLightIntensity[GLINT_SLOPE_COUNT];
uniform vec3 uSpotAxis[GLINT_SLOPE_COUNT];  // the direction a spot shines along (kernel/lights.h)
uniform vec2 uSpotCone[GLINT_SLOPE_COUNT];  // glintSpotConeScaleOffset; (0, 1) for lights without a cone
uniform float uLightInverseRange[GLINT_SLOPE_COUNT];  // 1 / range (glintRangeWindow); 0 for lights without a range
#include "shadows.glsl"

uniform vec3 uIrradianceSh[9];  // Ramamoorthi & Hanrahan 2001, coefficients already scaled by A_l

vec3 irradiance(vec3 n) {
  return uIrradianceSh[0] * 0.282095f + uIrradianceSh[1] * (0.488603f * n.y) + uIrradianceSh[2] * (0.488603f * n.z) +
         uIrradianceSh[3] * (0.488603f * n.x) + uIrradianceSh[4] * (1.092548f * n.x * n.y) +
         uIrradianceSh[5] * (1.092548f * n.y * n.z) + uIrradianceSh[6] * (0.315392f * (3.0f * n.z * n.z - 1.0f)) +
         uIrradianceSh[7] * (1.092548f * n.x * n.z) + uIrradianceSh[8] * (0.546274f * (n.x * n.x - n.y * n.y));
}

// The surface's inputs as this renderer looks them up; the kernel assembles the surface from them
// (surface.h), as the path tracer assembles its own. Called in uniform control flow: the normal
// map's moments take derivatives.
GlintSurfaceSamples surfaceSamples() {
  // Without transforms the lookups take the interpolated uv itself, which llvmpipe differentiates
  // for the mip level more cheaply than a computed one.
#if TEXTURE_TRANSFORMS
#define TEXTURE_UV(transform) ((transform) * vec3(vUv, 1.0f))
#else
#define TEXTURE_UV(transform) vUv
#endif
  GlintSurfaceSamples samples;
  samples.baseColour = uBaseColour * texture(uBaseColourTexture, TEXTURE_UV(uBaseColourUv));
#if VERTEX_COLOURS
  samples.baseColour *= vColour;
#endif
  vec4 metallicRoughness = texture(uMetallicRoughnessTexture, TEXTURE_UV(uMetallicRoughnessUv));
  samples.metallicRoughness = vec2(uMetallic * metallicRoughness.b, uRoughness * metallicRoughness.g);
  samples.emission = uEmissive * texture(uEmissiveTexture, TEXTURE_UV(uEmissiveUv)).rgb;
  samples.occlusion = 1.0f + uOcclusionStrength * (texture(uOcclusionTexture, TEXTURE_UV(uOcclusionUv)).r - 1.0f);
  samples.normal = vNormal;
  samples.tangent = vTangent;
  samples.view = normalize(uCameraPoint.xyz - uCameraPoint.w * vPosition);
  samples.normalMapCovariance = vec3(0.0f);
#if GLINT_LEAN
  // The normal map's slope moments at the footprint (made with the normal scale applied): their
  // mean tilts the normal, their covariance widens the glint layer (surface.h).
  vec2 leanUv = TEXTURE_UV(uNormalUv);
  vec3 leanFirst = texture(uLeanFirstMoments, leanUv).xyz;
  vec3 leanSecond = texture(uLeanSecondMoments, leanUv).xyz;
  float leanLambda = glintTextureLevelOfDetail(dFdx(leanUv), dFdy(leanUv), vec2(textureSize(uLeanFirstMoments, 0)));
  samples.mappedNormal = glintLeanMeanNormal(leanFirst);
  samples.normalMapCovariance = glintLeanSlopeCovariance(leanFirst, leanSecond, leanLambda);
#else
#if NORMAL_MAP_FINEST
  samples.mappedNormal = textureLod(uNormalTexture, TEXTURE_UV(uNormalUv), 0.0f).xyz * 2.0f - 1.0f;
#else
  samples.mappedNormal = texture(uNormalTexture, TEXTURE_UV(uNormalUv)).xyz * 2.0f - 1.0f;
#endif
  samples.mappedNormal.xy *= uNormalScale;
#endif
  samples.glintSamples = vec3(texture(uGlintRoughnessTexture, vUv).r, texture(uGlintLogDensityTexture, vUv).r,
                              texture(uGlintRelativeAreaTexture, vUv).r);
  return samples;
}

#if CLEARCOAT
GlintCoatSamples coatSamples() {
  GlintCoatSamples samples;
#if CLEARCOAT_TEXTURES
  samples.factorRoughness = uClearcoat * vec2(texture(uClearcoatTexture, TEXTURE_UV(uClearcoatUv)).r,
                                              texture(uClearcoatRoughnessTexture, TEXTURE_UV(uClearcoatRoughnessUv)).g);
  samples.mappedNormal = texture(uClearcoatNormalTexture, TEXTURE_UV(uClearcoatNormalUv)).xyz * 2.0f - 1.0f;
  samples.mappedNormal.xy *= uClearcoatNormalScale;
#else
  samples.factorRoughness = uClearcoat;
  samples.mappedNormal = vec3(0.0f, 0.0f, 1.0f);
#endif
  return samples;
}
#endif

// The material's glint layer with what the program compiles in: coloured cells, the target and
// its compensation, the LOD construction (one program per variant, forwardVariant in
// src/gl/renderer.cpp). llvmpipe executes both sides of a branch, so read from the block they
// would make every glint material pay for the colours and for every target.
GlintMaterial compiledGlintMaterial() {
  GlintMaterial material = uGlintMaterial;
  material.colouredCells = uint(GLINT_COLOURED_CELLS);
  material.ndf = GLINT_NDF;
  material.masking = GLINT_MASKING;
  material.multipleScattering = uint(GLINT_MULTIPLE_SCATTERING);
  material.lod = GLINT_LOD_CONSTRUCTION;
  return material;
}

GlintFootprintPolicy frameFootprintPolicy() {
  GlintFootprintPolicy policy;
  policy.maxAnisotropy = uGlintFootprintPolicy.x;
  policy.maxCells = uGlintFootprintPolicy.y;
  policy.minBlend = uGlintFootprintPolicy.z;
  return policy;
}

// Each light's direction in the shading frame, its squared distance (1 for a directional one) and
// its falloff: the fraction of its intensity that its cone sends this way, its range lets arrive and
// its shadow lets through.
void gatherLights(GlintSurface surface, out vec3 direction[GLINT_SLOPE_COUNT], out float distance2[GLINT_SLOPE_COUNT],
                  out float falloff[GLINT_SLOPE_COUNT]) {
  for (int i = 0; i < LIGHT_COUNT; ++i) {
    vec3 toLight = uLightPosition[i].xyz - vPosition * uLightPosition[i].w;
    distance2[i] = uLightPosition[i].w > 0.0f ? dot(toLight, toLight) : 1.0f;
    vec3 l = normalize(toLight);
    direction[i] = vec3(dot(l, surface.t), dot(l, surface.b), dot(l, surface.n));
    falloff[i] = glintSpotAttenuation(uSpotAxis[i], l, uSpotCone[i]) * glintRangeWindow(distance2[i], uLightInverseRange[i]);
#if SHADOWS
    falloff[i] *= shadowVisibility(i, uLightPosition[i], vPosition, normalize(vNormal), l, sqrt(distance2[i]));
#endif
  }
}

#if SPECULAR_MODEL == SPECULAR_GLINT
// The glint P-SDF at every light's half vector, from one walk over the footprint's cells. A light
// below the horizon, or whose slope is negligible (glintSlopeIsNegligible), reflects nothing (its
// p22 is 0); when no light is left the walk is skipped. Called in uniform control flow: the
// anti-aliasing filter takes the slopes' screen derivatives.
GlintP22Set litGlintP22s(GlintDictionaryView dict, GlintSurface surface, vec3 lightDirection[GLINT_SLOPE_COUNT],
                         vec2 glintUv, vec2 duvdx, vec2 duvdy) {
  GlintSlopeSet slopes;
  bool lit[GLINT_SLOPE_COUNT];
  bool anyLit = false;
  for (int i = 0; i < LIGHT_COUNT; ++i) {
    vec2 slope = glintSlopeFromNormal(normalize(surface.wo + lightDirection[i]));
    lit[i] = lightDirection[i].z > 0.0f && !glintSlopeIsNegligible(dict, surface.glint, slope);
    // An unlit light's result is discarded; a finite slope keeps its texel reads in range (a light
    // below the horizon can have an infinite one).
    slopes.slope[i] = lit[i] ? slope : vec2(0.0f);
    slopes.derivatives[i] = vec4(0.0f);
#if GLINT_FILTERED
    // The anti-aliasing filter's input: the slope's screen derivatives, taken here, in uniform
    // control flow (every pixel of a quad runs this loop of constant length, before any branch
    // on its result). Where a neighbour's slope is not finite (its light below the horizon) the
    // pixel is left unfiltered.
    vec4 derivatives = vec4(dFdx(slope), dFdy(slope)) * uGlintFilterScale;
    bool finiteDerivatives = !any(isnan(derivatives)) && !any(isinf(derivatives));
    slopes.derivatives[i] = lit[i] && finiteDerivatives ? derivatives : vec4(0.0f);
#endif
    anyLit = anyLit || lit[i];
  }
  GlintP22Set p22s;
  for (int i = 0; i < GLINT_SLOPE_COUNT; ++i) {
    p22s.p22[i] = vec4(0.0f);
  }
  if (GLINT_LAYER && anyLit) {
    p22s = glintP22Set(dict, surface.glint, glintUv, duvdx, duvdy, slopes);
    for (int i = 0; i < LIGHT_COUNT; ++i) {
      p22s.p22[i] = lit[i] ? p22s.p22[i] : vec4(0.0f);
    }
  }
  return p22s;
}
#endif

#if EXTENDED_LIGHT_COUNT > 0
#if REGION_COUNT > 0
uniform vec3 uRegionCorner[4 * REGION_COUNT];  // each region's four corners, unit world directions in order around it
uniform vec3 uRegionRadiance[REGION_COUNT];
#endif
#if AREA_LIGHT_COUNT > 0
uniform vec3 uAreaLightCorner[4 * AREA_LIGHT_COUNT];  // each light's four corners, world positions, counter-clockwise seen from its front
uniform vec3 uAreaLightRadiance[AREA_LIGHT_COUNT];
uniform int uAreaLightTwoSided[AREA_LIGHT_COUNT];
#endif

// Extended light r as seen from here: its four corners (unit world directions, in order around it)
// and its radiance, 0 behind a one-sided light. An environment region is ambient light, which the
// occlusion texture dims as it dims the prefiltered map's; an area light is direct light, which it
// does not (glTF's occlusionTexture), and it is shadowed at its centre (SHADOWS).
vec3 extendedLightAt(int r, GlintSurface surface, out vec3 wi[4]) {
  vec3 radiance = vec3(0.0f);
  for (int k = 0; k < 4; ++k) {
    wi[k] = vec3(0.0f, 0.0f, 1.0f);
  }
#if REGION_COUNT > 0
  if (r < REGION_COUNT) {
    for (int k = 0; k < 4; ++k) {
      wi[k] = uRegionCorner[4 * r + k];
    }
    radiance = uRegionRadiance[r] * surface.occlusion;
  }
#endif
#if AREA_LIGHT_COUNT > 0
  if (r >= REGION_COUNT) {
    int a = r - REGION_COUNT;
    for (int k = 0; k < 4; ++k) {
      wi[k] = normalize(uAreaLightCorner[4 * a + k] - vPosition);
    }
    // Its front faces the side its corners turn counter-clockwise on; a one-sided light is dark
    // behind.
    vec3 front = cross(uAreaLightCorner[4 * a + 1] - uAreaLightCorner[4 * a], uAreaLightCorner[4 * a + 3] - uAreaLightCorner[4 * a]);
    bool lit = uAreaLightTwoSided[a] != 0 || dot(vPosition - uAreaLightCorner[4 * a], front) > 0.0f;
    radiance = lit ? uAreaLightRadiance[a] : vec3(0.0f);
#if SHADOWS
    // The shadow of its centre (a cube map from there, caster LIGHT_COUNT + a): hard, where the
    // tracer's penumbra spans the light's extent.
    vec3 lightCentre = 0.25f * (uAreaLightCorner[4 * a] + uAreaLightCorner[4 * a + 1] + uAreaLightCorner[4 * a + 2] + uAreaLightCorner[4 * a + 3]);
    vec3 toCentre = lightCentre - vPosition;
    float centreDistance = length(toCentre);
    radiance *= shadowVisibility(LIGHT_COUNT + a, vec4(lightCentre, 1.0f), vPosition, normalize(vNormal),
                                 toCentre / max(centreDistance, 1e-20f), centreDistance);
#endif
  }
#endif
  return radiance;
}

// The light of the extended lights (docs/method.md, "Extended lights"): the environment's brightest
// regions, which the prefiltered map and the irradiance lack, and the area lights. Each one's
// diffuse by its cosine-weighted solid angle, and its specular: its radiance times Fresnel and
// glintRegionReflectanceAt, times the mass of the lobe over the half vectors it sends the view
// into: the glint layer's P-SDF (glintRegionMassSet) in glint programs, the smooth lobe's
// (glintSmoothRegionMoments) in the others. environmentScale: what scales the prefiltered map's
// specular, the glint layer's mass outside the environment's regions over the smooth lobe's
// (glintResidualEnvironmentScale; 1 in the other programs).
vec3 extendedLight(GlintSurface surface, vec2 glintUv, vec2 duvdx, vec2 duvdy, out vec3 environmentScale) {
  GlintRegionSet regions;
  vec3 centre[EXTENDED_LIGHT_COUNT];
  vec3 radiance[EXTENDED_LIGHT_COUNT];
  vec3 diffuse = vec3(0.0f);
  for (int r = 0; r < EXTENDED_LIGHT_COUNT; ++r) {
    vec3 wi[4];
    radiance[r] = extendedLightAt(r, surface, wi);
    for (int k = 0; k < 4; ++k) {
      wi[k] = vec3(dot(wi[k], surface.t), dot(wi[k], surface.b), dot(wi[k], surface.n));
    }
    GlintClippedLight light = glintClipLightToHorizon(wi[0], wi[1], wi[2], wi[3]);
    regions.region[r] = glintLightSlopeRegion(surface.wo, light);
    centre[r] = glintClippedLightCentre(light);
    diffuse += radiance[r] * glintClippedLightProjectedSolidAngle(light);
  }
  float rho = GLINT_LAYER ? surface.glint.rho : 0.0f;
  environmentScale = vec3(1.0f);
#if SPECULAR_MODEL == SPECULAR_GLINT
  GlintRegionMassSet masses = glintRegionMassSet(glintDictionary(), surface.glint, glintUv, duvdx, duvdy, regions);
#if REGION_COUNT > 0
  if (GLINT_LAYER) {
    environmentScale = glintResidualEnvironmentScale(masses, REGION_COUNT);
  }
#endif
#endif
  vec3 specular = vec3(0.0f);
  for (int r = 0; r < EXTENDED_LIGHT_COUNT; ++r) {
#if SPECULAR_MODEL == SPECULAR_GLINT
    vec3 mass = masses.mass[r].rgb;
    vec2 meanSlope = masses.meanSlope[r];
#else
    vec3 moments = glintSmoothRegionMoments(GLINT_NDF, surface.smoothAlpha, rho, regions.region[r]);
    vec3 mass = vec3(moments.x);
    vec2 meanSlope = moments.yz;
#endif
    // The light's reflectance where the lobe's mass over it lies (glintRegionReflectanceAt): the
    // glint layer's own mean slope there in glint programs, the smooth lobe's in the others.
    vec3 wh = glintSlopeHalfVector(meanSlope);
    specular += radiance[r] * glintFresnelSchlick(surface.f0, max(dot(surface.wo, wh), 0.0f)) *
                glintRegionReflectanceAt(GLINT_MASKING, GLINT_NDF, surface.smoothAlpha, rho, surface.wo, meanSlope, centre[r]) * mass;
  }
  return surface.diffuse * diffuse + specular;
}

#if CLEARCOAT
// The coat's lobe under the extended lights: the smooth lobe's mass over each light's half vectors
// in the coat's frame (glintSmoothRegionMoments, GGX), as Cook-Torrance programs draw their lobe.
vec3 coatExtendedLight(GlintSurface surface, GlintCoat coat) {
  vec3 wo = glintCoatLocal(coat, surface.wo);
  vec2 alpha = vec2(coat.alpha);
  vec3 specular = vec3(0.0f);
  for (int r = 0; r < EXTENDED_LIGHT_COUNT; ++r) {
    vec3 wi[4];
    vec3 radiance = extendedLightAt(r, surface, wi);
    for (int k = 0; k < 4; ++k) {
      wi[k] = glintCoatLocal(coat, vec3(dot(wi[k], surface.t), dot(wi[k], surface.b), dot(wi[k], surface.n)));
    }
    GlintClippedLight light = glintClipLightToHorizon(wi[0], wi[1], wi[2], wi[3]);
    vec3 moments = glintSmoothRegionMoments(GLINT_NDF_GGX, alpha, 0.0f, glintLightSlopeRegion(wo, light));
    specular += radiance * coat.weight * moments.x *
                glintRegionReflectanceAt(GLINT_MASKING_SMITH, GLINT_NDF_GGX, alpha, 0.0f, wo, moments.yz, glintClippedLightCentre(light));
  }
  return specular;
}
#endif
#endif

// The specular lobe for light direction wi (above the horizon), times Fresnel: the program's model
// for a glint layer (p22: its P-SDF there, glint programs only), Cook-Torrance without one.
vec3 specularReflectance(GlintSurface surface, vec3 wi, vec4 p22, vec2 glintUv, vec2 duvdx, vec2 duvdy) {
  vec3 wo = surface.wo;
  vec3 wh = normalize(wo + wi);
  vec3 fresnel = glintFresnelSchlick(surface.f0, dot(wo, wh));
#if SPECULAR_MODEL == SPECULAR_GLINT
  if (GLINT_LAYER) {
    vec3 tint = p22.w > 0.0f ? p22.rgb / p22.w : vec3(1.0f);
    return fresnel * tint * glintMaskedReflectance(surface.glint, wo, wi, wh, glintNdfFromP22(p22.w, wh.z));
  }
  return fresnel * glintTargetCookTorranceReflectance(GLINT_NDF, GLINT_MASKING, surface.smoothAlpha, 0.0f, wo, wi);
#elif ZIRR_KAPLANYAN
  if (GLINT_LAYER) {
    // Zirr & Kaplanyan 2016 with the glint layer's parameters mapped (docs/zirr-kaplanyan.md);
    // it has no relative area, so its mean is scaled by it to match the glint BRDF's.
#if SPECULAR_MODEL == SPECULAR_ZIRR_KAPLANYAN_REFERENCE
    float zirrKaplanyan =
        glintZirrKaplanyanReferenceReflectance(glintUv, duvdx, duvdy, wo, wi, glintZirrKaplanyanFromGlint(surface.glint));
#else
    float zirrKaplanyan = glintZirrKaplanyanReflectance(glintUv, duvdx, duvdy, wo, wi, glintZirrKaplanyanFromGlint(surface.glint));
#endif
    return fresnel * surface.glint.relativeArea * zirrKaplanyan;
  }
  return fresnel * glintCookTorranceReflectance(surface.smoothAlpha, 0.0f, wo, wi);
#else
  return fresnel * glintTargetCookTorranceReflectance(GLINT_NDF, GLINT_MASKING, surface.smoothAlpha,
                                                      GLINT_LAYER ? surface.glint.rho : 0.0f, wo, wi);
#endif
}

void main() {
  // The glint footprint: screen-space derivatives of the glint uv, taken first, in uniform
  // control flow, before any branch that pixels of a quad could take differently.
  // The layer lies in the base colour texture's uv, its KHR_texture_transform applied (a quantized
  // mesh's uv are brought to [0, 1] by it).
  vec2 glintUv = glintMaterialUv(uGlintMaterial, TEXTURE_UV(uBaseColourUv));
  vec2 duvdx = dFdx(glintUv);
  vec2 duvdy = dFdy(glintUv);

  GlintSurfaceSamples samples = surfaceSamples();
  GlintSurface surface = glintSurface(samples, compiledGlintMaterial(), frameFootprintPolicy());
  vec3 lightDirection[GLINT_SLOPE_COUNT];
  float lightDistance2[GLINT_SLOPE_COUNT];
  float lightFalloff[GLINT_SLOPE_COUNT];
  gatherLights(surface, lightDirection, lightDistance2, lightFalloff);
#if SPECULAR_MODEL == SPECULAR_GLINT
  GlintP22Set glintP22s = litGlintP22s(glintDictionary(), surface, lightDirection, glintUv, duvdx, duvdy);
#endif
#if GLINT_MULTIPLE_SCATTERING
  // The multiple-scattering compensation (multiple_scattering.h): a smooth lobe, the same for glint
  // and Cook-Torrance programs, with Schlick's average Fresnel.
  vec3 multipleFresnel = glintMultipleScatteringFresnel(
      glintSchlickAverageFresnel(surface.f0),
      glintAverageAlbedo(GLINT_NDF, GLINT_MASKING, glintCompensationAlpha(surface.smoothAlpha)));
#endif

#if CLEARCOAT
  // The emission has its own share through the coat, added last.
  vec3 radiance = vec3(0.0f);
  GlintCoatSamples coatInputs = coatSamples();
  GlintCoat coat = glintSurfaceCoat(surface, samples, coatInputs);
  vec3 coatRadiance = vec3(0.0f);
#else
  vec3 radiance = surface.emission;
#endif
  for (int i = 0; i < LIGHT_COUNT; ++i) {
    vec3 wi = lightDirection[i];
    if (wi.z <= 0.0f) {
      continue;
    }
#if SPECULAR_MODEL == SPECULAR_GLINT
    vec4 p22 = glintP22s.p22[i];
#else
    vec4 p22 = vec4(0.0f);
#endif
    vec3 specular = specularReflectance(surface, wi, p22, glintUv, duvdx, duvdy);
#if GLINT_MULTIPLE_SCATTERING
    specular += multipleFresnel * glintMultipleScatteringReflectance(GLINT_NDF, GLINT_MASKING, surface.smoothAlpha, surface.wo, wi);
#endif
    radiance += (surface.diffuse + specular) * wi.z * (uLightIntensity[i] * lightFalloff[i]) / lightDistance2[i];
#if CLEARCOAT
    coatRadiance += glintCoatReflectedCosine(coat, surface.wo, wi) * (uLightIntensity[i] * lightFalloff[i]) / lightDistance2[i];
#endif
  }

#if EXTENDED_LIGHT_COUNT > 0
  // The extended lights, both lobes.
  vec3 environmentScale;
  vec3 extended = extendedLight(surface, glintUv, duvdx, duvdy, environmentScale);
#else
  vec3 environmentScale = vec3(1.0f);
#endif
  // Ambient light: irradiance by spherical harmonics, the pre-filtered environment in the reflected
  // direction, its specular scaled by the glints' share of the lobe outside the environment's
  // regions (glintResidualEnvironmentScale).
  vec3 reflected = reflect(-samples.view, surface.n);
  vec3 ambient = surface.diffuse * irradiance(surface.n) +
                 environmentScale * glintFresnelSchlick(surface.f0, surface.wo.z) *
                     environmentRadiance(reflected, max(surface.smoothAlpha.x, surface.smoothAlpha.y));
  radiance += ambient * surface.occlusion;
#if EXTENDED_LIGHT_COUNT > 0
  // The map less the regions' means (prefiltered, and its irradiance) can dip below zero around them.
  radiance = max(radiance + extended, vec3(0.0f));
#endif
#if CLEARCOAT
  // The coat (kernel/clearcoat.h): the base dimmed by the share it reflects, its own lobe under the
  // lights, the prefiltered environment about its normal and the extended lights.
  vec3 coatNormal = surface.t * coat.n.x + surface.b * coat.n.y + surface.n * coat.n.z;
  coatRadiance += coat.weight * environmentRadiance(reflect(-samples.view, coatNormal), coat.alpha) * surface.occlusion;
#if EXTENDED_LIGHT_COUNT > 0
  coatRadiance = max(coatRadiance + coatExtendedLight(surface, coat), vec3(0.0f));
#endif
  radiance = radiance * (1.0f - coat.weight) + coatRadiance +
             surface.emission * glintCoatedEmissionWeight(coatInputs.factorRoughness.x, samples.normal, samples.view);
#endif
#if ALPHA_MASK
  // glTF alphaMode MASK. The pre-pass left no depth here, so this fragment passes the equal-depth
  // test only where it ties with the surface behind; it is dropped last, after every derivative.
  if (surface.baseColour.a < uAlphaCutoff) {
    discard;
  }
#endif
  outRadiance = vec4(radiance, 1.0f);
}
