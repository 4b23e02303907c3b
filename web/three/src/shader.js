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
  glintUv = glintMaterialUv(glintMaterial, vUv);
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

// Programs lit by RectAreaLights (three's NUM_RECT_AREA_LIGHTS): the kernel's second part
// (glint_extended_lights.h, one light a walk of the footprint's cells), the hook's third function
// over the cumulative tables (src/dictionary.js) and one light's specular lobe, which takes the place
// of three's LTC lobe. docs/method.md section 8: the P-SDF's mass over the half vectors that send the
// view into the light, times the reflectance at the smooth lobe's mean slope there.
const AREA_LIGHT_HOST = /* glsl */ `
uniform highp sampler2D glintCumulativeTexels;  // RGBA32F (C[k], M[k], p[k], p[k+1]) (src/dictionary.js)

vec4 glintDictionaryCumulativeTexel(GlintDictionaryView dict, int level, int distribution, int texel) {
  int index = (level * dict.numDistributions + distribution) * dict.texelsPerDistribution + texel;
  return texelFetch(glintCumulativeTexels, ivec2(index & ${DICTIONARY_TEXTURE_WIDTH - 1}, index >> ${TEXEL_ROW_SHIFT}), 0);
}

// One RectAreaLight's specular lobe per unit radiance (corners and position in view space, v and n
// towards the viewer and the shading normal), as glint's rasteriser draws an area light
// (shaders/forward.frag, extendedLight): with three's Schlick Fresnel at the half vector of the
// lobe's mean slope. Dark behind the light, as three's LTC_Evaluate (one-sided, counter-clockwise).
vec3 glintAreaLightSpecular(vec3 corners[4], vec3 position, vec3 v, vec3 n, vec3 f0, float f90) {
  if (dot(cross(corners[1] - corners[0], corners[3] - corners[0]), position - corners[0]) < 0.0) {
    return vec3(0.0);
  }
  vec3 wo = vec3(dot(v, glintT), dot(v, glintB), max(dot(v, n), 1e-4));
  vec3 wi[4];
  for (int k = 0; k < 4; ++k) {
    vec3 d = normalize(corners[k] - position);
    wi[k] = vec3(dot(d, glintT), dot(d, glintB), dot(d, n));
  }
  GlintClippedLight light = glintClipLightToHorizon(wi[0], wi[1], wi[2], wi[3]);
  GlintRegionSet regions;
  regions.region[0] = glintLightSlopeRegion(wo, light);
  GlintParameters params = glintParameters;
#if GLINT_LAYER_SMOOTH
  vec3 moments = glintSmoothRegionMoments(GLINT_LAYER_NDF, params.alpha, params.rho, regions.region[0]);
  vec3 mass = vec3(moments.x);
  vec2 meanSlope = moments.yz;
#else
  GlintRegionMassSet masses = glintRegionMassSet(glintDictionaryView(), params, glintUv, glintDuvdx, glintDuvdy, regions);
  vec3 mass = masses.mass[0].rgb;
  vec2 meanSlope = masses.targetMeanSlope[0];
#endif
  vec3 fresnel = F_Schlick(f0, f90, max(dot(wo, glintSlopeHalfVector(meanSlope)), 0.0));
  return fresnel * mass * glintRegionReflectanceAt(GLINT_LAYER_MASKING, GLINT_LAYER_NDF, params.alpha, params.rho, wo, meanSlope,
                                                   glintClippedLightCentre(light));
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
// lit by RectAreaLights (shader.numRectAreaLights) gets glints under them too.
export function addGlintLayerToShader(shader, variant) {
  shader.vertexShader = replaceOnce(shader.vertexShader, 'void main() {', `${VERTEX_DECLARATIONS}\nvoid main() {`, 'meshphysical vertex shader');
  shader.vertexShader = replaceOnce(shader.vertexShader, '#include <begin_vertex>', `#include <begin_vertex>\n${VERTEX_MAIN}`, 'meshphysical vertex shader');
  const areaLights = shader.numRectAreaLights > 0;
  const extended = areaLights ? `#define GLINT_REGION_COUNT 1\n${glintExtendedLightsSource}\n${AREA_LIGHT_HOST}\n` : '';
  const fragmentHost = `${kernelDefines(variant)}\n${glintKernelSource}\n${FRAGMENT_HOST}\n${extended}${lightsChunk(areaLights)}`;
  let fragment = shader.fragmentShader;
  fragment = replaceOnce(fragment, '#include <lights_physical_pars_fragment>', fragmentHost, 'meshphysical fragment shader');
  fragment = replaceOnce(fragment, 'void main() {', 'void main() {\n  glintBeginFragment();', 'meshphysical fragment shader');
  fragment = replaceOnce(fragment, '#include <normal_fragment_maps>', '#include <normal_fragment_maps>\n  glintShadingFrame(normal);', 'meshphysical fragment shader');
  shader.fragmentShader = fragment;
}
