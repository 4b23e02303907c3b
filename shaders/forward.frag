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
// lights cast shadows (shadows.glsl). The material's glint layer is one uniform block, a
// GlintMaterial (glint_material_block.glsl, kernel/glint_material.h).
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
#ifndef GLINT_MASKING
#define GLINT_MASKING 0
#endif
// The glint layer's LOD construction (glint_brdf.h, glintLodCell), compiled in likewise: the
// paper's unless the host defines GLINT_LOD_CONSTRUCTION as another (GLINT_LOD_CONSISTENT 1,
// GLINT_LOD_TREE 2).
#ifndef GLINT_LOD_CONSTRUCTION
#define GLINT_LOD_CONSTRUCTION 0
#endif
#include "glint_brdf.h"
#include "glint_material_block.glsl"
#include "multiple_scattering.h"
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

void main() {
  // The glint footprint: screen-space derivatives of the glint uv, taken first, in uniform
  // control flow, before any branch that pixels of a quad could take differently.
  vec2 glintUv = glintMaterialUv(uGlintMaterial, vUv);
  vec2 duvdx = dFdx(glintUv);
  vec2 duvdy = dFdy(glintUv);

  // Without transforms the lookups take the interpolated uv itself, which llvmpipe differentiates
  // for the mip level more cheaply than a computed one.
#if TEXTURE_TRANSFORMS
#define TEXTURE_UV(transform) ((transform) * vec3(vUv, 1.0f))
#else
#define TEXTURE_UV(transform) vUv
#endif
  vec4 baseColour = uBaseColour * texture(uBaseColourTexture, TEXTURE_UV(uBaseColourUv));
#if VERTEX_COLOURS
  baseColour *= vColour;
#endif
  vec4 metallicRoughness = texture(uMetallicRoughnessTexture, TEXTURE_UV(uMetallicRoughnessUv));
  float metallic = uMetallic * metallicRoughness.b;
  float roughness = clamp(uRoughness * metallicRoughness.g, 0.03f, 1.0f);
  vec3 emissive = uEmissive * texture(uEmissiveTexture, TEXTURE_UV(uEmissiveUv)).rgb;
  float occlusion = 1.0f + uOcclusionStrength * (texture(uOcclusionTexture, TEXTURE_UV(uOcclusionUv)).r - 1.0f);

  // Shading frame: the normal map's normal, the tangent re-orthogonalised against it; sheets seen
  // from behind (curtains) are shaded on the side facing the camera.
  vec3 view = normalize(uCameraPoint.xyz - uCameraPoint.w * vPosition);
  vec3 n = normalize(vNormal);
  vec3 t = normalize(vTangent.xyz - n * dot(n, vTangent.xyz));
  vec3 b = cross(n, t) * (vTangent.w < 0.0f ? -1.0f : 1.0f);
#if GLINT_LEAN
  // The footprint's mean slope (the moments were made with the normal scale applied); the slopes'
  // covariance widens the glint layer below.
  vec2 leanUv = TEXTURE_UV(uNormalUv);
  vec3 leanFirst = texture(uLeanFirstMoments, leanUv).xyz;
  vec3 leanSecond = texture(uLeanSecondMoments, leanUv).xyz;
  float leanLambda = glintTextureLevelOfDetail(dFdx(leanUv), dFdy(leanUv), vec2(textureSize(uLeanFirstMoments, 0)));
  vec3 mapped = glintLeanMeanNormal(leanFirst);
#else
#if NORMAL_MAP_FINEST
  vec3 mapped = textureLod(uNormalTexture, TEXTURE_UV(uNormalUv), 0.0f).xyz * 2.0f - 1.0f;
#else
  vec3 mapped = texture(uNormalTexture, TEXTURE_UV(uNormalUv)).xyz * 2.0f - 1.0f;
#endif
  mapped.xy *= uNormalScale;
#endif
  n = normalize(mat3(t, b, n) * mapped);
  if (dot(n, view) < 0.0f) {
    n = -n;
  }
  t = normalize(t - n * dot(n, t));
  b = cross(n, t) * (vTangent.w < 0.0f ? -1.0f : 1.0f);
  vec3 wo = vec3(dot(view, t), dot(view, b), max(dot(view, n), 1e-4f));

  // The glint layer's parameters from its textures' samples (kernel/glint_material.h, as the path
  // tracer's). Coloured cells, the target and its compensation are the material's own, compiled
  // in (one program per variant, forwardVariant in src/gl/renderer.cpp): llvmpipe executes both
  // sides of a branch, so read from the block they would make every glint material pay for the
  // colours and for every target.
  GlintMaterial material = uGlintMaterial;
  material.colouredCells = uint(GLINT_COLOURED_CELLS);
  material.ndf = GLINT_NDF;
  material.masking = GLINT_MASKING;
  material.multipleScattering = uint(GLINT_MULTIPLE_SCATTERING);
  material.lod = GLINT_LOD_CONSTRUCTION;
  GlintFootprintPolicy footprintPolicy;
  footprintPolicy.maxAnisotropy = uGlintFootprintPolicy.x;
  footprintPolicy.maxCells = uGlintFootprintPolicy.y;
  footprintPolicy.minBlend = uGlintFootprintPolicy.z;
  GlintParameters params = glintMaterialParameters(material, texture(uGlintRoughnessTexture, vUv).r,
                                                   texture(uGlintLogDensityTexture, vUv).r,
                                                   texture(uGlintRelativeAreaTexture, vUv).r, footprintPolicy);
#if GLINT_LEAN
  // The normal map's slope covariance over the footprint, measured in the tangent frame, added to
  // the glint layer's in the tilted shading frame (a small-tilt approximation, as the authors'),
  // correlation included. (Filtering the glints by it instead, as by the pixel's own kernel, was
  // measured and did worse: docs/antialiasing.md, "Normal-map filtering".)
  vec3 leanRoughness =
      glintLeanCombinedRoughness(params.alpha, params.rho, glintLeanSlopeCovariance(leanFirst, leanSecond, leanLambda));
  params.alpha = vec2(leanRoughness.x, leanRoughness.y);
  params.rho = leanRoughness.z;
#endif
  GlintDictionaryView dict = glintDictionary();

  vec3 f0 = mix(vec3(0.04f), baseColour.rgb, metallic);
  vec3 diffuse = baseColour.rgb * (1.0f - metallic) / GLINT_PI;
  vec2 specularAlpha = GLINT_LAYER ? params.alpha : vec2(roughness * roughness);

  // Each light's direction in the shading frame, its squared distance (1 for a directional one)
  // and the fraction of its intensity that its cone sends this way and its range lets arrive (1
  // for a directional light).
  vec3 lightDirection[GLINT_SLOPE_COUNT];
  float lightDistance2[GLINT_SLOPE_COUNT];
  float lightFalloff[GLINT_SLOPE_COUNT];
  for (int i = 0; i < LIGHT_COUNT; ++i) {
    vec3 toLight = uLightPosition[i].xyz - vPosition * uLightPosition[i].w;
    lightDistance2[i] = uLightPosition[i].w > 0.0f ? dot(toLight, toLight) : 1.0f;
    vec3 l = normalize(toLight);
    lightDirection[i] = vec3(dot(l, t), dot(l, b), dot(l, n));
    lightFalloff[i] = glintSpotAttenuation(uSpotAxis[i], l, uSpotCone[i]) * glintRangeWindow(lightDistance2[i], uLightInverseRange[i]);
#if SHADOWS
    lightFalloff[i] *= shadowVisibility(i, vPosition, normalize(vNormal), l, sqrt(lightDistance2[i]));
#endif
  }

#if SPECULAR_MODEL == SPECULAR_GLINT
  // The glint P-SDF at every light's half vector, from one walk over the footprint's cells. A light
  // below the horizon, or whose slope is negligible (glintSlopeIsNegligible), reflects nothing; when
  // no light is left the walk is skipped.
  GlintSlopeSet glintSlopes;
  bool glintLit[GLINT_SLOPE_COUNT];
  bool anyGlintLit = false;
  for (int i = 0; i < LIGHT_COUNT; ++i) {
    vec2 slope = glintSlopeFromNormal(normalize(wo + lightDirection[i]));
    glintLit[i] = lightDirection[i].z > 0.0f && !glintSlopeIsNegligible(dict, params, slope);
    // An unlit light's result is discarded; a finite slope keeps its texel reads in range (a light
    // below the horizon can have an infinite one).
    glintSlopes.slope[i] = glintLit[i] ? slope : vec2(0.0f);
    glintSlopes.derivatives[i] = vec4(0.0f);
#if GLINT_FILTERED
    // The anti-aliasing filter's input: the slope's screen derivatives, taken here, in uniform
    // control flow (every pixel of a quad runs this loop of constant length, before any branch
    // on its result). Where a neighbour's slope is not finite (its light below the horizon) the
    // pixel is left unfiltered.
    vec4 derivatives = vec4(dFdx(slope), dFdy(slope)) * uGlintFilterScale;
    bool finiteDerivatives = !any(isnan(derivatives)) && !any(isinf(derivatives));
    glintSlopes.derivatives[i] = glintLit[i] && finiteDerivatives ? derivatives : vec4(0.0f);
#endif
    anyGlintLit = anyGlintLit || glintLit[i];
  }
  GlintP22Set glintP22s;
  if (GLINT_LAYER && anyGlintLit) {
    glintP22s = glintP22Set(dict, params, glintUv, duvdx, duvdy, glintSlopes);
  }
#endif

#if GLINT_MULTIPLE_SCATTERING
  // The multiple-scattering compensation (multiple_scattering.h): a smooth lobe, the same for glint
  // and Cook-Torrance programs, with Schlick's average Fresnel.
  vec3 multipleFresnel = glintMultipleScatteringFresnel(
      glintSchlickAverageFresnel(f0), glintAverageAlbedo(GLINT_NDF, GLINT_MASKING, glintCompensationAlpha(specularAlpha)));
#endif
  vec3 radiance = emissive;
  for (int i = 0; i < LIGHT_COUNT; ++i) {
    vec3 wi = lightDirection[i];
    if (wi.z <= 0.0f) {
      continue;
    }
    vec3 wh = normalize(wo + wi);
    vec3 fresnel = glintFresnelSchlick(f0, dot(wo, wh));
    vec3 specular;
#if SPECULAR_MODEL == SPECULAR_GLINT
    if (GLINT_LAYER) {
      vec4 p22 = glintLit[i] ? glintP22s.p22[i] : vec4(0.0f);
      vec3 tint = p22.w > 0.0f ? p22.rgb / p22.w : vec3(1.0f);
      specular = fresnel * tint * glintMaskedReflectance(params, wo, wi, wh, glintNdfFromP22(p22.w, wh.z));
    } else {
      specular = fresnel * glintTargetCookTorranceReflectance(GLINT_NDF, GLINT_MASKING, specularAlpha, 0.0f, wo, wi);
    }
#elif ZIRR_KAPLANYAN
    if (GLINT_LAYER) {
      // Zirr & Kaplanyan 2016 with the glint layer's parameters mapped (docs/zirr-kaplanyan.md);
      // it has no relative area, so its mean is scaled by it to match the glint BRDF's.
#if SPECULAR_MODEL == SPECULAR_ZIRR_KAPLANYAN_REFERENCE
      float zirrKaplanyan = glintZirrKaplanyanReferenceReflectance(glintUv, duvdx, duvdy, wo, wi, glintZirrKaplanyanFromGlint(params));
#else
      float zirrKaplanyan = glintZirrKaplanyanReflectance(glintUv, duvdx, duvdy, wo, wi, glintZirrKaplanyanFromGlint(params));
#endif
      specular = fresnel * params.relativeArea * zirrKaplanyan;
    } else {
      specular = fresnel * glintCookTorranceReflectance(specularAlpha, 0.0f, wo, wi);
    }
#else
    specular = fresnel * glintTargetCookTorranceReflectance(GLINT_NDF, GLINT_MASKING, specularAlpha,
                                                       GLINT_LAYER ? params.rho : 0.0f, wo, wi);
#endif
#if GLINT_MULTIPLE_SCATTERING
    specular += multipleFresnel * glintMultipleScatteringReflectance(GLINT_NDF, GLINT_MASKING, specularAlpha, wo, wi);
#endif
    radiance += (diffuse + specular) * wi.z * (uLightIntensity[i] * lightFalloff[i]) / lightDistance2[i];
  }
  vec3 reflected = reflect(-view, n);
  vec3 ambient = diffuse * irradiance(n) +
                 glintFresnelSchlick(f0, wo.z) * environmentRadiance(reflected, max(specularAlpha.x, specularAlpha.y));
  radiance += ambient * occlusion;
#if ALPHA_MASK
  // glTF alphaMode MASK. The pre-pass left no depth here, so this fragment passes the equal-depth
  // test only where it ties with the surface behind; it is dropped last, after every derivative.
  if (baseColour.a < uAlphaCutoff) {
    discard;
  }
#endif
  outRadiance = vec4(radiance, 1.0f);
}
