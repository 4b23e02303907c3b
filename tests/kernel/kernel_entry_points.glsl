// The whole kernel, included as another renderer would, and its main entry points called once each:
// the body of the shading-language tests (KernelLanguages.*, tests/CMakeLists.txt), written in the
// kernel's dialect (src/glint/kernel/prelude.h) so that one text serves GLSL 4.50 for OpenGL and
// Vulkan, GLSL ES 3.00 and HLSL. The including file defines the dictionary hook.
#ifndef KERNEL_ENTRY_POINTS_GLSL
#define KERNEL_ENTRY_POINTS_GLSL

// The largest configuration: the anti-aliased walk, two slopes a walk, the albedo tables.
#define GLINT_FILTERED 1
#define GLINT_MULTIPLE_SCATTERING 1
#define GLINT_SLOPE_COUNT 2
#include "glint_brdf.h"
#include "glint_antialiasing.h"
#include "microfacet.h"
#include "microfacet_targets.h"
#include "multiple_scattering.h"
#include "albedo_tables.h"
#include "normal_map_filtering.h"
#include "lights.h"
#include "tonemap.h"
#include "zirr_kaplanyan.h"
// glint's extension to extended lights, two regions a walk.
#define GLINT_REGION_COUNT 2
#include "glint_extended_lights.h"
// glTF surfaces and the clear coat over them (glint's extension).
#include "surface.h"
#include "clearcoat.h"

// Every entry point a renderer or a sampler calls, on inputs packed in three vec4s, summed so that
// each result is used.
vec4 kernelEntryPoints(GlintDictionaryView dict, vec4 a, vec4 b, vec4 c) {
  GlintParameters params;
  params.alpha = vec2(a.x, a.y);
  params.rho = a.z;
  params.logDensity = a.w;
  params.relativeArea = b.x;
  params.densityRandomisation = b.y;
  params.maxAnisotropy = b.z;
  params.patternSeed = uint(b.w);
  params.colouredCells = c.x > 0.5f;
  params.ndf = c.y > 0.5f ? GLINT_NDF_GGX : GLINT_NDF_BECKMANN;
  params.masking = c.z > 0.5f ? GLINT_MASKING_SMITH : GLINT_MASKING_VCAVITY;
  params.multipleScattering = true;
  params.lod = c.w > 40.0f ? GLINT_LOD_CONSISTENT : GLINT_LOD_PAPER;
  params.footprintPolicy.maxAnisotropy = 0.0f;
  params.footprintPolicy.maxCells = c.w;
  params.footprintPolicy.minBlend = 0.0f;
  vec2 uv = vec2(b.x, b.y);
  vec2 duvdx = vec2(1e-3f, 0.0f);
  vec2 duvdy = vec2(0.0f, 1e-3f);
  vec3 wo = normalize(vec3(a.x, a.y, 1.0f));
  vec3 wi = normalize(vec3(-a.y, a.x, 1.0f));
  vec3 wh = normalize(wo + wi);
  vec2 slope = glintSlopeFromNormal(wh);

  // The glint BRDF (Chermain et al. 2020) and its anti-aliasing (2021).
  float f = glintReflectance(dict, params, uv, duvdx, duvdy, wo, wi);
  float ndf = glintNdf(dict, params, uv, duvdx, duvdy, wh);
  float filtered = glintFilteredP22(dict, params, uv, duvdx, duvdy, slope, vec4(1e-2f, 0.0f, 0.0f, 1e-2f));
  GlintSlopeSet slopes = glintSingleSlope(slope);
  slopes.slope[1] = -slope;
  GlintP22Set p22 = glintP22Set(dict, params, uv, duvdx, duvdy, slopes);
  bool negligible = glintSlopeIsNegligible(dict, params, slope);
  // What the host's sampler walks: the pixel's footprint, its cells and their draws.
  GlintFootprint footprint = glintPixelFootprint(duvdx, duvdy, params, dict.numLevels);
  int level = glintLodLevel(footprint);
  GlintCellGrid grid = glintCellGrid(footprint, glintWrapUv(uv, dict.numLevels), dict.numLevels, level);
  GlintLevelDraw draw = glintLevelDraw(dict, params, footprint.logDensity, level);
  GlintLodDraws draws = glintLodDraws(dict, params, footprint.logDensity, level, draw);
  GlintCellWalk walk = glintWalkStart(grid);
  float weights = 0.0f;
  while (glintWalkGoing(grid, walk)) {
    ivec2 index = glintCellAt(grid, walk.s, walk.t);
    float weight = glintWalkWeight(grid, walk);
    GlintCell cell = glintLodCell(dict, params, draws, index.x, index.y, level);
    weights += (cell.readsDictionary ? weight * glintCellRotation(cell.hash).x * float(1 + cell.complement.x) : weight) *
               cell.coverage;
    walk = glintWalkStep(grid, walk);
  }
  vec2 scaled = glintScaledSlope(dict, params, glintUnscaledSlope(dict, params, slope));

  // Smooth targets, masking, Fresnel, multiple scattering.
  float cookTorrance = glintCookTorranceReflectance(params.alpha, params.rho, wo, wi) +
                       glintTargetCookTorranceReflectance(params.ndf, params.masking, params.alpha, params.rho, wo, wi);
  float smith = glintSmithG1(params.ndf, params.alpha, params.rho, wo) * glintVCavityG1(wo, wh);
  vec3 fresnel = glintFresnelSchlick(glintSplat3(0.04f), dot(wo, wh)) +
                 glintFresnelConductor(vec3(0.2f, 0.9f, 1.1f), vec3(3.9f, 2.4f, 2.2f), dot(wo, wh));
  float multiple = glintMultipleScatteringReflectance(params.ndf, params.masking, params.alpha, wo, wi);
  vec3 compensation = glintMultipleScatteringFresnel(
      glintSchlickAverageFresnel(fresnel), glintAverageAlbedo(params.ndf, params.masking, glintCompensationAlpha(params.alpha)));

  // Normal-map filtering, lights, the display transform.
  vec3 lean = glintLeanCombinedRoughness(params.alpha, params.rho, glintLeanSlopeCovariance(vec3(a.xyz), vec3(b.xyz), -1.0f)) +
              glintLeanMeanNormal(vec3(c.xyz));
  float lod = glintTextureLevelOfDetail(duvdx, duvdy, vec2(1024.0f, 1024.0f));
  float light = glintSpotAttenuation(vec3(0.0f, 0.0f, -1.0f), wi, glintSpotConeScaleOffset(0.3f, 0.5f)) *
                glintRangeWindow(4.0f, 0.1f);
  vec3 display = glintDisplayCodeValues(vec3(f, ndf, filtered), 1.0f, ivec2(int(a.x * 64.0f), int(a.y * 64.0f)));

  // Zirr & Kaplanyan 2016, on glint's parameters, on both schedules.
  GlintZirrKaplanyanParameters zk = glintZirrKaplanyanFromGlint(params);
  float zirrKaplanyan = glintZirrKaplanyanReflectance(uv, duvdx, duvdy, wo, wi, zk) +
                        glintZirrKaplanyanReferenceReflectance(uv, duvdx, duvdy, wo, wi, zk);

  // Extended lights: an area light's region, its glints' and smooth lobe's mass, its diffuse.
  GlintClippedLight area = glintClipLightToHorizon(normalize(vec3(-0.3f, -0.2f, 1.0f)), normalize(vec3(0.3f, -0.2f, 1.0f)),
                                                   normalize(vec3(0.3f, 0.2f, 1.0f)), normalize(vec3(-0.3f, 0.2f, -0.1f)));
  GlintRegionSet regions;
  regions.region[0] = glintLightSlopeRegion(wo, area);
  regions.region[1] = glintLightSlopeRegion(wi, area);
  GlintRegionMassSet masses = glintRegionMassSet(dict, params, uv, duvdx, duvdy, regions);
  vec3 smoothMoments = glintSmoothRegionMoments(params.ndf, params.alpha, params.rho, regions.region[0]);
  float extended = masses.mass[0].w + masses.mass[1].x + masses.targetMass[1] +
                   glintRegionReflectanceAt(params.masking, params.ndf, params.alpha, params.rho, wo, masses.meanSlope[0],
                                            glintClippedLightCentre(area)) +
                   glintClippedLightProjectedSolidAngle(area) + smoothMoments.y + masses.targetMeanSlope[1].x +
                   glintResidualEnvironmentScale(masses, 1).y;

  // A clear coat over a surface's frame: its weight, frame and lobe, and the emission's share.
  GlintSurfaceSamples coatInputs;
  coatInputs.normal = vec3(0.0f, 0.0f, 1.0f);
  coatInputs.tangent = vec4(1.0f, 0.0f, 0.0f, 1.0f);
  coatInputs.view = wo;
  GlintSurface coated;
  coated.t = vec3(1.0f, 0.0f, 0.0f);
  coated.b = vec3(0.0f, 1.0f, 0.0f);
  coated.n = vec3(0.0f, 0.0f, 1.0f);
  coated.wo = wo;
  GlintCoatSamples coatSamples;
  coatSamples.factorRoughness = vec2(c.x, a.x);
  coatSamples.mappedNormal = normalize(vec3(a.y, b.y, 1.0f));
  GlintCoat coat = glintSurfaceCoat(coated, coatInputs, coatSamples);
  float coatLight = glintCoatReflectedCosine(coat, wo, wi) + glintCoatedEmissionWeight(c.x, coatInputs.normal, wo);

  return vec4(f + ndf + filtered + p22.p22[0].w + p22.p22[1].x + (negligible ? 1.0f : 0.0f) + weights + extended,
              cookTorrance + smith + multiple + scaled.x + lod + light, fresnel.x + compensation.y + lean.z + display.x,
              zirrKaplanyan + coatLight);
}

#endif
