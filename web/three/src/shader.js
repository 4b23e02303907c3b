// The glint layer's side of three.js's physical shader: what MeshGlintMaterial's onBeforeCompile
// puts into MeshPhysicalMaterial's program. The model's equations are not here: they are glint's
// kernel (src/glint/kernel/*.h) as GLSL ES 3.00, the file `glint shader-bundle --language glsl-es`
// writes, which the package's build step wraps in generated/glint-kernel-es.js
// (tools/build.mjs). This file is the host's part, as docs/integration.md ("The kernel in your
// shaders") describes it: the dictionary hook over a texture, the footprint's screen derivatives,
// the tangent frame, the material's parameters, and the direct lights' specular lobe handed to
// three's lighting loop in place of its GGX lobe.
import { ShaderChunk } from 'three';
import glintKernelSource from '../generated/glint-kernel-es.js';
import glintExtendedLightsSource from '../generated/glint-extended-lights-es.js';
import { DICTIONARY_TEXTURE_WIDTH } from './dictionary.js';

const TEXEL_ROW_SHIFT = Math.log2(DICTIONARY_TEXTURE_WIDTH);

// Declarations the vertex shader gains: the tangent (glTF TANGENT, w the bitangent's sign) in view
// space, for the layer's frame. three declares the attribute only for normal-mapped or anisotropic
// materials (USE_TANGENT); without the attribute WebGL reads (0, 0, 0, 1) and the fragment shader
// takes the frame from the uv's screen derivatives instead.
const VERTEX_DECLARATIONS = /* glsl */ `
#ifndef USE_TANGENT
attribute vec4 tangent;
#endif
varying vec4 vGlintTangent;
`;

// After <begin_vertex>, where three has its skinning and batching matrices: the tangent through
// the transforms three applies to its own tangent (defaultnormal_vertex, skinnormal_vertex), but
// morph targets'.
const VERTEX_MAIN = /* glsl */ `
  vec3 glintObjectTangent = tangent.xyz;
#ifdef USE_SKINNING
  glintObjectTangent = ( skinMatrix * vec4( glintObjectTangent, 0.0 ) ).xyz;
#endif
#ifdef USE_BATCHING
  glintObjectTangent = mat3( batchingMatrix ) * glintObjectTangent;
#endif
#ifdef USE_INSTANCING
  glintObjectTangent = mat3( instanceMatrix ) * glintObjectTangent;
#endif
  vGlintTangent = vec4( ( modelViewMatrix * vec4( glintObjectTangent, 0.0 ) ).xyz, tangent.w );
`;

// The kernel's compile-time choices for one material (one program each, as in glint's rasteriser):
// the smooth target and masking by the kernel's own constant names, coloured cells, the
// multiple-scattering lobe, the LOD construction (only the one the material asks for is compiled:
// GLINT_LOD_PAPER 0, GLINT_LOD_CONSISTENT 1, GLINT_LOD_TREE 2 in kernel/glint_parameters.h), and the
// smooth lobe in place of the glints.
export const LOD_CONSTRUCTIONS = ['paper', 'consistent', 'tree'];  // the index is the kernel's constant
// The names a layer's ndf and masking take (the extension's), each with the kernel's constant.
export const NDF_NAMES = { ggx: 'GLINT_NDF_GGX', beckmann: 'GLINT_NDF_BECKMANN' };
export const MASKING_NAMES = { smith: 'GLINT_MASKING_SMITH', 'v-cavity': 'GLINT_MASKING_VCAVITY' };
// The layer's compiled-in fields that take a name, each with the names it takes.
export const LAYER_NAME_CHOICES = { ndf: Object.keys(NDF_NAMES), masking: Object.keys(MASKING_NAMES), lod: LOD_CONSTRUCTIONS };

function kernelDefines(variant) {
  return [
    `#define GLINT_MULTIPLE_SCATTERING ${variant.multipleScattering ? 1 : 0}`,
    `#define GLINT_LAYER_NDF ${NDF_NAMES[variant.ndf]}`,
    `#define GLINT_LAYER_MASKING ${MASKING_NAMES[variant.masking]}`,
    `#define GLINT_LAYER_COLOURED_CELLS ${variant.colouredCells ? 1 : 0}`,
    `#define GLINT_LAYER_SMOOTH ${variant.smooth ? 1 : 0}`,
    `#define GLINT_LOD_CONSTRUCTION ${LOD_CONSTRUCTIONS.indexOf(variant.lod)}`,
  ].join('\n');
}

// The host's code after the kernel: resources, the dictionary hook, the per-fragment state and the
// specular lobe.
const FRAGMENT_HOST = /* glsl */ `
uniform highp sampler2D glintDictionaryTexels;  // RG16F texel pairs (src/dictionary.js)
uniform ivec3 glintDictionaryShape;             // levels, distributions, texels per distribution
uniform float glintDictionaryAlpha;             // alpha_d
uniform GlintMaterial glintMaterial;            // the layer's parameters (kernel/glint_material.h)
uniform sampler2D glintRoughnessMap;            // R: multiplies alpha (white when absent)
uniform sampler2D glintLogDensityMap;           // R: onto logDensityRange when hasLogDensityTexture
uniform sampler2D glintRelativeAreaMap;         // R: multiplies relativeArea (white when absent)
varying vec4 vGlintTangent;

GlintDictionaryView glintDictionaryView() {
  GlintDictionaryView dict;
  dict.numLevels = glintDictionaryShape.x;
  dict.numDistributions = glintDictionaryShape.y;
  dict.texelsPerDistribution = glintDictionaryShape.z;
  dict.alpha = glintDictionaryAlpha;
  dict.numMips = 1;  // no mip chain: the 2020 model, unfiltered
  dict.mipRowLength = glintDictionaryShape.z;
  return dict;
}

// The dictionary hook (kernel/prelude.h): texels k and k + 1 of one marginal in one fetch.
vec2 glintDictionaryTexelPair(GlintDictionaryView dict, int level, int distribution, int texel) {
  int index = (level * dict.numDistributions + distribution) * dict.texelsPerDistribution + texel;
  return texelFetch(glintDictionaryTexels, ivec2(index & ${DICTIONARY_TEXTURE_WIDTH - 1}, index >> ${TEXEL_ROW_SHIFT}), 0).rg;
}

// Only the anti-aliased P-SDF (GLINT_FILTERED 1) reads the mip chain; this program is compiled
// without it, so the filtered lookup is never called (the prelude's rule for a host without one).
vec4 glintDictionaryFilteredTexels(GlintDictionaryView dict, int level, int distribution, int index) {
  return vec4(glintDictionaryTexelPair(dict, level, distribution, index), 0.0, 0.0);
}

// Per fragment: the glint uv and its footprint, the layer's parameters, the tangent frame.
vec2 glintUv;
vec2 glintDuvdx;
vec2 glintDuvdy;
GlintParameters glintParameters;
vec3 glintUvDpdu;  // dP/du and dP/dv (times a positive factor) from screen derivatives, for meshes
vec3 glintUvDpdv;  // without tangents
vec3 glintT;
vec3 glintB;

// At the top of main, in uniform control flow (before clipping or alpha-test discards): the screen
// derivatives and the textures' implicit ones (docs/integration.md, "Forward shading", step 1).
void glintBeginFragment() {
  // The layer lies in the base colour map's uv, its KHR_texture_transform applied (three's
  // mapTransform), as glint's renderers place it.
#ifdef USE_MAP
  glintUv = glintMaterialUv(glintMaterial, vMapUv);
#else
  glintUv = glintMaterialUv(glintMaterial, vUv);
#endif
  glintDuvdx = dFdx(glintUv);
  glintDuvdy = dFdy(glintUv);
  GlintMaterial material = glintMaterial;
  material.ndf = GLINT_LAYER_NDF;
  material.masking = GLINT_LAYER_MASKING;
  material.colouredCells = uint(GLINT_LAYER_COLOURED_CELLS);
  material.multipleScattering = uint(GLINT_MULTIPLE_SCATTERING);
  material.lod = GLINT_LOD_CONSTRUCTION;
  GlintFootprintPolicy exact;  // the paper's footprint
  exact.maxAnisotropy = 0.0;
  exact.maxCells = 0.0;
  exact.minBlend = 0.0;
  glintParameters = glintMaterialParameters(material, texture(glintRoughnessMap, vUv).r,
                                            texture(glintLogDensityMap, vUv).r,
                                            texture(glintRelativeAreaMap, vUv).r, exact);
  // Solving [dp/dx dp/dy] = [dP/du dP/dv] [duv/dx duv/dy] for dP/du (the uv's own frame).
  vec3 dpdx = dFdx(-vViewPosition);
  vec3 dpdy = dFdy(-vViewPosition);
  vec2 dstdx = dFdx(vUv);
  vec2 dstdy = dFdy(vUv);
  float detSign = dstdx.x * dstdy.y - dstdy.x * dstdx.y < 0.0 ? -1.0 : 1.0;
  glintUvDpdu = (dpdx * dstdy.y - dpdy * dstdx.y) * detSign;
  glintUvDpdv = (dpdy * dstdx.x - dpdx * dstdy.x) * detSign;
}

// After the normal map: the frame around the shading normal n (view space), the tangent
// re-orthogonalised against it, as glint's rasteriser does (shaders/forward.frag).
void glintShadingFrame(vec3 n) {
  vec3 tangent = vGlintTangent.xyz;
  float handedness = vGlintTangent.w < 0.0 ? -1.0 : 1.0;
  bool fromUv = !(dot(tangent, tangent) > 1e-20);
  if (fromUv) {
    tangent = glintUvDpdu;
  }
  glintT = normalize(tangent - n * dot(n, tangent));
  if (fromUv) {
    // glTF's bitangent, cross(n, t) * w, points towards decreasing v (glint's generated tangents).
    handedness = dot(cross(n, glintT), -glintUvDpdv) < 0.0 ? -1.0 : 1.0;
  }
  glintB = cross(n, glintT) * handedness;
}

// The specular lobe of one direct light (l and v towards the light and the viewer, n the shading
// normal, all in view space), without the cosine: the glint BRDF, or with GLINT_LAYER_SMOOTH its
// smooth target, with three's Schlick Fresnel (F0 and F90 from the core material and
// KHR_materials_specular/ior), and the kernel's multiple-scattering lobe.
vec3 glintDirectSpecular(vec3 l, vec3 v, vec3 n, vec3 f0, float f90) {
  vec3 wo = vec3(dot(v, glintT), dot(v, glintB), max(dot(v, n), 1e-4));
  vec3 wi = vec3(dot(l, glintT), dot(l, glintB), dot(l, n));
  if (wi.z <= 0.0) {
    return vec3(0.0);
  }
  GlintParameters params = glintParameters;
  vec3 wh = normalize(wo + wi);
  vec3 fresnel = F_Schlick(f0, f90, dot(wo, wh));
#if GLINT_LAYER_SMOOTH
  vec3 specular = fresnel * glintTargetCookTorranceReflectance(GLINT_LAYER_NDF, GLINT_LAYER_MASKING, params.alpha,
                                                               params.rho, wo, wi);
#else
  GlintDictionaryView dict = glintDictionaryView();
  vec2 slope = glintSlopeFromNormal(wh);
  vec4 p22 = glintSlopeIsNegligible(dict, params, slope)
                 ? vec4(0.0)
                 : glintP22Coloured(dict, params, glintUv, glintDuvdx, glintDuvdy, slope);
  vec3 tint = p22.w > 0.0 ? p22.rgb / p22.w : vec3(1.0);
  vec3 specular = fresnel * tint * glintMaskedReflectance(params, wo, wi, wh, glintNdfFromP22(p22.w, wh.z));
#endif
#if GLINT_MULTIPLE_SCATTERING
  vec3 multipleFresnel = glintMultipleScatteringFresnel(
      glintSchlickAverageFresnel(f0),
      glintAverageAlbedo(GLINT_LAYER_NDF, GLINT_LAYER_MASKING, glintCompensationAlpha(params.alpha)));
  specular += multipleFresnel * glintMultipleScatteringReflectance(GLINT_LAYER_NDF, GLINT_LAYER_MASKING, params.alpha, wo, wi);
#endif
  return specular;
}
`;

// Programs lit by RectAreaLights (three's NUM_RECT_AREA_LIGHTS) or by an environment's regions
// (src/environment.js, GLINT_ENV_REGION_COUNT): the kernel's second part (glint_extended_lights.h)
// and the hook's third function over the cumulative tables (src/dictionary.js); then each light's
// specular lobe (docs/method.md section 8): the P-SDF's mass over the half vectors that send the
// view into the light, times the reflectance at that mass's mean slope. A RectAreaLight
// takes one walk of the footprint's cells, in place of three's LTC lobe; the regions share one.
const EXTENDED_LIGHTS_HOST = /* glsl */ `
uniform highp sampler2D glintCumulativeTexels;  // RGBA32F (C[k], M[k], p[k], p[k+1]) (src/dictionary.js)

vec4 glintDictionaryCumulativeTexel(GlintDictionaryView dict, int level, int distribution, int texel) {
  int index = (level * dict.numDistributions + distribution) * dict.texelsPerDistribution + texel;
  return texelFetch(glintCumulativeTexels, ivec2(index & ${DICTIONARY_TEXTURE_WIDTH - 1}, index >> ${TEXEL_ROW_SHIFT}), 0);
}

// A light's corners (unit directions in view space) in the shading frame about n, clipped to its horizon.
GlintClippedLight glintShadingFrameLight(vec3 d0, vec3 d1, vec3 d2, vec3 d3, vec3 n) {
  mat3 frame = transpose(mat3(glintT, glintB, n));
  return glintClipLightToHorizon(frame * d0, frame * d1, frame * d2, frame * d3);
}

// The specular lobe of the lights of a region set per unit radiance each (light r's clipped
// centre, for a reflection below the horizon, in centre[r]), with three's Schlick Fresnel at the half
// vector of the lobe's mean slope, as glint's rasteriser (shaders/forward.frag, extendedLight).
// environmentScale: what scales the prefiltered map's specular when the first
// GLINT_ENV_REGION_COUNT regions are an environment's (glintResidualEnvironmentScale).
void glintRegionSpecular(GlintRegionSet regions, vec3 centre[GLINT_REGION_COUNT], vec3 wo, vec3 f0, float f90,
                         out vec3 specular[GLINT_REGION_COUNT], out vec3 environmentScale) {
  GlintParameters params = glintParameters;
  environmentScale = vec3(1.0);
#if !GLINT_LAYER_SMOOTH
  GlintRegionMassSet masses = glintRegionMassSet(glintDictionaryView(), params, glintUv, glintDuvdx, glintDuvdy, regions);
  environmentScale = glintResidualEnvironmentScale(masses, GLINT_ENV_REGION_COUNT);
#endif
  for (int r = 0; r < GLINT_REGION_COUNT; ++r) {
#if GLINT_LAYER_SMOOTH
    vec3 moments = glintSmoothRegionMoments(GLINT_LAYER_NDF, params.alpha, params.rho, regions.region[r]);
    vec3 mass = vec3(moments.x);
    vec2 meanSlope = moments.yz;
#else
    vec3 mass = masses.mass[r].rgb;
    vec2 meanSlope = masses.meanSlope[r];
#endif
    vec3 fresnel = F_Schlick(f0, f90, max(dot(wo, glintSlopeHalfVector(meanSlope)), 0.0));
    specular[r] = fresnel * mass * glintRegionReflectanceAt(GLINT_LAYER_MASKING, GLINT_LAYER_NDF, params.alpha, params.rho, wo,
                                                            meanSlope, centre[r]);
  }
}

vec3 glintViewVector(vec3 v, vec3 n) {
  return vec3(dot(v, glintT), dot(v, glintB), max(dot(v, n), 1e-4));
}

#if GLINT_ENV_REGION_COUNT > 0
uniform vec3 glintRegionCorner[4 * GLINT_ENV_REGION_COUNT];  // each region's corners, unit world directions in order
uniform vec3 glintRegionRadiance[GLINT_ENV_REGION_COUNT];

// The environment's regions: both lobes, the diffuse by each region's projected solid angle. They
// are part of the environment, so they go to the indirect terms, which three's ambient occlusion
// (aoMap) dims, as glint's rasteriser dims them by the occlusion texture. Returns what scales the
// prefiltered residual map's specular (glintResidualEnvironmentScale).
vec3 glintEnvironmentRegions(vec3 n, vec3 v, vec3 f0, float f90, vec3 diffuseColour, inout ReflectedLight reflectedLight) {
  vec3 wo = glintViewVector(v, n);
  GlintRegionSet regions;
  vec3 centre[GLINT_REGION_COUNT];
  vec3 diffuse = vec3(0.0);
  for (int r = 0; r < GLINT_REGION_COUNT; ++r) {
    vec3 d[4];
    for (int k = 0; k < 4; ++k) {
      d[k] = normalize((viewMatrix * vec4(glintRegionCorner[4 * r + k], 0.0)).xyz);
    }
    GlintClippedLight light = glintShadingFrameLight(d[0], d[1], d[2], d[3], n);
    regions.region[r] = glintLightSlopeRegion(wo, light);
    centre[r] = glintClippedLightCentre(light);
    diffuse += glintRegionRadiance[r] * glintClippedLightProjectedSolidAngle(light);
  }
  vec3 specular[GLINT_REGION_COUNT];
  vec3 environmentScale;
  glintRegionSpecular(regions, centre, wo, f0, f90, specular, environmentScale);
  for (int r = 0; r < GLINT_REGION_COUNT; ++r) {
    reflectedLight.indirectSpecular += glintRegionRadiance[r] * specular[r];
  }
  reflectedLight.indirectDiffuse += diffuse * BRDF_Lambert(diffuseColour);
  return environmentScale;
}
#endif

// One RectAreaLight's specular lobe per unit radiance (corners and position in view space, v and n
// towards the viewer and the shading normal), as glint's rasteriser draws an area light
// (shaders/forward.frag, extendedLight): with three's Schlick Fresnel at the half vector of the
// lobe's mean slope. Dark behind the light, as three's LTC_Evaluate (one-sided, counter-clockwise).
vec3 glintAreaLightSpecular(vec3 corners[4], vec3 position, vec3 v, vec3 n, vec3 f0, float f90) {
  if (dot(cross(corners[1] - corners[0], corners[3] - corners[0]), position - corners[0]) < 0.0) {
    return vec3(0.0);
  }
  vec3 wo = glintViewVector(v, n);
  GlintClippedLight light = glintShadingFrameLight(normalize(corners[0] - position), normalize(corners[1] - position),
                                                   normalize(corners[2] - position), normalize(corners[3] - position), n);
  GlintRegionSet regions;
  vec3 centre[GLINT_REGION_COUNT];
  regions.region[0] = glintLightSlopeRegion(wo, light);
  centre[0] = glintClippedLightCentre(light);
  for (int r = 1; r < GLINT_REGION_COUNT; ++r) {
    for (int k = 0; k < GLINT_REGION_VERTICES; ++k) {
      regions.region[r].vertex[k] = vec2(1.0e6);  // no region: its target mass is 0, none of its cells is walked
    }
    centre[r] = vec3(0.0, 0.0, 1.0);
  }
  vec3 specular[GLINT_REGION_COUNT];
  vec3 unused;  // an area light's walk leaves the environment's scale to the regions' own walk
  glintRegionSpecular(regions, centre, wo, f0, f90, specular, unused);
  return specular[0];
}
`;
const THREE_AREA_SPECULAR = 'reflectedLight.directSpecular += lightColor * fresnel * LTC_Evaluate( normal, viewDir, position, mInv, rectCoords );';
const GLINT_AREA_SPECULAR =
  'reflectedLight.directSpecular += lightColor * glintAreaLightSpecular( rectCoords, position, viewDir, normal, material.specularColorBlended, material.specularF90 );';

// three's direct lighting with the glint lobe in place of its GGX lobe. The layer brings its own
// multiple-scattering lobe (the kernel's), so three's compensation factor is not applied to it.
const THREE_SPECULAR = 'vec3 specularBRDF = BRDF_GGX( directLight.direction, geometryViewDir, geometryNormal, material );';
const GLINT_SPECULAR =
  'vec3 specularBRDF = glintDirectSpecular( directLight.direction, geometryViewDir, geometryNormal, material.specularColorBlended, material.specularF90 );';
const THREE_ACCUMULATION = 'reflectedLight.directSpecular += irradiance * specularBRDF * material.multiScatteringCompensation;';
const GLINT_ACCUMULATION = 'reflectedLight.directSpecular += irradiance * specularBRDF;';

function replaceOnce(text, from, to, where) {
  const at = text.indexOf(from);
  if (at < 0 || text.indexOf(from, at + 1) >= 0) {
    throw new Error(`glint-three: three.js's ${where} is not the one this package was written for (three 0.187.0): cannot find "${from}"`);
  }
  return text.slice(0, at) + to + text.slice(at + from.length);
}

// three's physical lighting with glint's lobes; with `areaLights`, under RectAreaLights too.
const glintLightsChunks = new Map();
function lightsChunk(areaLights) {
  if (!glintLightsChunks.has(areaLights)) {
    let chunk = ShaderChunk.lights_physical_pars_fragment;
    chunk = replaceOnce(chunk, THREE_SPECULAR, GLINT_SPECULAR, 'lights_physical_pars_fragment');
    chunk = replaceOnce(chunk, THREE_ACCUMULATION, GLINT_ACCUMULATION, 'lights_physical_pars_fragment');
    if (areaLights) chunk = replaceOnce(chunk, THREE_AREA_SPECULAR, GLINT_AREA_SPECULAR, 'lights_physical_pars_fragment');
    glintLightsChunks.set(areaLights, chunk);
  }
  return glintLightsChunks.get(areaLights);
}

// MeshPhysicalMaterial's program (the `shader` of onBeforeCompile, three's program parameters)
// with the glint layer of one variant; the host's uniforms are added by the material. A program
// lit by RectAreaLights (shader.numRectAreaLights) gets glints under them too, and one with the
// regions of an environment (variant.environmentRegions, src/environment.js) under those.
export function addGlintLayerToShader(shader, variant) {
  shader.vertexShader = replaceOnce(shader.vertexShader, 'void main() {', `${VERTEX_DECLARATIONS}\nvoid main() {`, 'meshphysical vertex shader');
  shader.vertexShader = replaceOnce(shader.vertexShader, '#include <begin_vertex>', `#include <begin_vertex>\n${VERTEX_MAIN}`, 'meshphysical vertex shader');
  const areaLights = shader.numRectAreaLights > 0;
  const regions = variant.environmentRegions;
  const extended = areaLights || regions > 0
    ? `#define GLINT_ENV_REGION_COUNT ${regions}\n#define GLINT_REGION_COUNT ${Math.max(regions, 1)}\n` +
      `${glintExtendedLightsSource}\n${EXTENDED_LIGHTS_HOST}\n`
    : '';
  const fragmentHost = `${kernelDefines(variant)}\n${glintKernelSource}\n${FRAGMENT_HOST}\n${extended}${lightsChunk(areaLights)}`;
  let fragment = shader.fragmentShader;
  fragment = replaceOnce(fragment, '#include <lights_physical_pars_fragment>', fragmentHost, 'meshphysical fragment shader');
  fragment = replaceOnce(fragment, 'void main() {', 'void main() {\n  glintBeginFragment();', 'meshphysical fragment shader');
  fragment = replaceOnce(fragment, '#include <normal_fragment_maps>', '#include <normal_fragment_maps>\n  glintShadingFrame(normal);', 'meshphysical fragment shader');
  if (regions > 0) {
    fragment = replaceOnce(fragment, '#include <lights_fragment_end>',
                           'radiance *= glintEnvironmentRegions(geometryNormal, geometryViewDir, material.specularColorBlended, ' +
                           'material.specularF90, material.diffuseContribution, reflectedLight);\n#include <lights_fragment_end>',
                           'meshphysical fragment shader');
  }
  shader.fragmentShader = fragment;
}
