// The glint BRDF of Chermain, Sauvage, Dischler & Dachsbacher 2020, "Procedural Physically based BRDF
// for Real-Time Rendering of Glints" (Pacific Graphics; CGF 39(7)): the cells summed into the P-SDF
// over a pixel footprint, the P-NDF and the BRDF (Alg. 1 and 2 and Eq. 14; method.md 2.4-3). Its
// parts: inputs (glint_parameters.h), footprint and walk (glint_footprint.h), a cell's draws
// (glint_cell.h), level-of-detail constructions (glint_lod.h). The walk also carries the 2021 slope
// correlation and filter (glint_antialiasing.h), which leave the 2020 values unchanged bit for bit
// when rho = 0 and the slopes have no derivatives.
#ifndef GLINT_KERNEL_GLINT_BRDF_H
#define GLINT_KERNEL_GLINT_BRDF_H

#include "prelude.h"
#include "random.h"
#include "microfacet.h"
#include "dictionary_lookup.h"
#include "glint_antialiasing.h"
#include "microfacet_targets.h"
#include "glint_parameters.h"
#include "glint_footprint.h"
#include "glint_cell.h"
#include "glint_lod.h"

GLINT_KERNEL_BEGIN

// The smooth target's P22 convolved with the kernel of slope covariance K: for Beckmann
// glintFilteredBeckmannP22; for GGX the Student t of scale covariance Sigma + K, an approximation (a t
// convolved with a Gaussian is no t), exact without a kernel.
GLINT_FN float glintFilteredTargetP22(GlintParameters params, vec2 slope, vec3 kernelCovariance) {
  if (params.ndf != GLINT_NDF_GGX) {
    return glintFilteredBeckmannP22(slope, params.alpha, params.rho, kernelCovariance);
  }
  return glintStudentSlopeP22(slope, glintBeckmannSlopeCovariance(params.alpha, params.rho) + kernelCovariance);
}

// The P-SDF at several slopes from one walk: the renderer shades a pixel's lights at once, one half
// vector each, so a cell's draws are made once per pixel, not per light (docs/renderer.md, "Cost");
// each slope gets exactly the sums of a walk of its own. A compile-time constant: the renderer's
// programs define their scene's light count; the CPU library and sampler use one.
#ifndef GLINT_SLOPE_COUNT
#define GLINT_SLOPE_COUNT 1
#endif

struct GlintSlopeSet {
  vec2 slope[GLINT_SLOPE_COUNT];
  // Each slope's screen derivatives (dx.x, dx.y, dy.x, dy.y) times the kernel size: the filter's
  // input (glint_antialiasing.h). Zero: no filtering.
  vec4 derivatives[GLINT_SLOPE_COUNT];
};

struct GlintP22Set {
  vec4 p22[GLINT_SLOPE_COUNT];  // each as glintP22Coloured's
};

// A set whose every slope is this one (the single-slope functions below).
GLINT_FN GlintSlopeSet glintSingleSlope(vec2 slope) {
  GlintSlopeSet slopes;
  for (int k = 0; k < GLINT_SLOPE_COUNT; ++k) {
    slopes.slope[k] = slope;
    slopes.derivatives[k] = glintSplat4(0.0f);
  }
  return slopes;
}

// A level's average over its walked cells, as glintLevelP22 and the extended lights' region masses
// take it: the dictionary cells' sum times `dictionaryScale` (.rgb tinted by the chroma sum with
// coloured cells) plus the untinted smooth and GGX-tail parts, over the summed weight. Clamped at 0
// under the consistent construction, whose complement texels can dip below 0 (glintBlockMarginal).
GLINT_FN vec4 glintLevelAverage(GlintParameters params, float dictionarySum, vec2 chromaSum, float dictionaryScale, float smoothPart,
                                float tailPart, float weightSum) {
  vec3 colourWeighted = params.colouredCells ? glintTintedP22(dictionarySum, chromaSum) : glintSplat3(dictionarySum);
  vec4 average = (vec4(colourWeighted, dictionarySum) * dictionaryScale + glintSplat4(smoothPart) + glintSplat4(tailPart)) / weightSum;
#if GLINT_CONSISTENT_LOD_COMPILED
  if (params.lod == GLINT_LOD_CONSISTENT) {
    average = max(average, glintSplat4(0.0f));
  }
#endif
  return average;
}

// P22 over the footprint at one level (Alg. 2 of Chermain et al. 2020; method.md 2.4), at each slope:
// the EWA-weighted mean of its cells' P22 in .w, .rgb weighted by the cells' colours (uncoloured
// cells are white: .rgb = .w). The scaling Jacobian (Alg. 3, line 19 of Chermain et al. 2020;
// det(M^-1) of Eq. 15 of Chermain et al. 2021, I3D) and the smooth cells' P22 (Alg. 3, line 10) are
// the same for every cell, so they multiply the weighted sums once.
GLINT_FN GlintP22Set glintLevelP22(GlintDictionaryView dict, GlintParameters params, GlintFootprint footprint, vec2 uv,
                                   int level, GlintLevelDraw draw, GlintSlopeSet slopes) {
  GlintCellGrid grid = glintCellGrid(footprint, uv, dict.numLevels, level);
  vec2 unscaled[GLINT_SLOPE_COUNT];
  float dictionarySum[GLINT_SLOPE_COUNT];
  vec2 chromaSum[GLINT_SLOPE_COUNT];
  // A slope beyond every rotated support reads no dictionary cell (glintCellMarginals' per-axis test
  // agrees but for rounding, so the slope is gated as a walk of its own would be); when all are,
  // rotations and texel reads are skipped.
  bool inSupport[GLINT_SLOPE_COUNT];
  bool anyInSupport = false;
  // Each slope's kernel: its slope-space covariance (smooth cells) and, from its unscaled covariance,
  // the dictionary cells' level of detail.
  vec3 slopeKernel[GLINT_SLOPE_COUNT];
  GlintMarginalFilter kernelFilter[GLINT_SLOPE_COUNT];
  float kernelVariance[GLINT_SLOPE_COUNT];  // GGX cells filter at their own scale
  bool anyDerivative = false;
  // A GGX cell's support reaches GLINT_GGX_WIDEST_CELL times further (exactly 1 for Beckmann).
  float widestUnscale = 1.0f / glintTargetWidestCell(params.ndf);
  for (int k = 0; k < GLINT_SLOPE_COUNT; ++k) {
    unscaled[k] = glintUnscaledSlope(dict, params, slopes.slope[k]);
    dictionarySum[k] = 0.0f;
    chromaSum[k] = glintSplat2(0.0f);
    inSupport[k] = !glintBeyondEveryRotatedSupport(dict, unscaled[k] * widestUnscale);
    anyInSupport = anyInSupport || inSupport[k];
    vec4 d = slopes.derivatives[k];
    slopeKernel[k] = glintKernelCovariance(d);
    vec2 ux = glintUnscaledSlope(dict, params, vec2(d.x, d.y));
    vec2 uy = glintUnscaledSlope(dict, params, vec2(d.z, d.w));
    kernelVariance[k] = glintKernelVariance(glintKernelCovariance(vec4(ux, uy)));
    kernelFilter[k] = glintMarginalFilter(dict, glintMarginalLod(dict, kernelVariance[k]));
    anyDerivative = anyDerivative || slopeKernel[k].x + slopeKernel[k].z > 0.0f;
  }
  bool filtering = GLINT_FILTERS(anyDerivative);
  // The parent's or own level's draws, for the consistent and tree constructions (glintLodCell).
  GlintLodDraws draws = glintLodDraws(dict, params, footprint.logDensity, level, draw);
  float weightSum = 0.0f;
  float smoothWeightSum = 0.0f;
  float tailWeightSum = 0.0f;
  // One loop over the cells, not a loop over lines around a loop over a line's cells: pixels shaded in
  // lockstep (llvmpipe's SIMD lanes, GPU warps) then pay for the most cells any visits, not the longest
  // line of any, line after line. Measured cheaper even where predication makes every iteration pay for
  // the line change (docs/benchmarks.md, "What made it fast, and why"). Same cells, weights and order
  // as the nested loops, bit for bit.
  GlintCellWalk walk = glintWalkStart(grid);
  while (glintWalkGoing(grid, walk)) {
    float weight = glintWalkWeight(grid, walk);
    ivec2 index = glintCellAt(grid, walk.s, walk.t);
    walk = glintWalkStep(grid, walk);
    if (weight > 0.0f) {
      weightSum += weight;
      GlintCell cell = glintLodCell(dict, params, draws, index.x, index.y, level);
      float covered = weight * cell.coverage;  // weight itself but under the tree construction
      smoothWeightSum += cell.smoothLimit ? covered : 0.0f;
      tailWeightSum += cell.ggxTail ? covered : 0.0f;
      if (cell.readsDictionary && anyInSupport) {
        vec2 rotation = glintCellRotation(cell.hash);
        ivec2 distributions = cell.distributions;
        vec2 chroma = params.colouredCells ? glintCellChroma(cell.hash) : glintSplat2(0.0f);
        for (int k = 0; k < GLINT_SLOPE_COUNT; ++k) {
          float p = 0.0f;
          if (inSupport[k]) {
            vec2 cellUnscaled = unscaled[k] * cell.unscale;
            GlintMarginalFilter cellFilter = kernelFilter[k];
            if (filtering && params.ndf == GLINT_NDF_GGX) {
              cellFilter = glintMarginalFilter(dict, glintMarginalLod(dict, cell.scalePrecision * kernelVariance[k]));
            }
            p = filtering ? glintCellFilteredMarginals(dict, cell.dictionaryLevel, distributions, cell.complement,
                                                       rotation, cellUnscaled, cellFilter)
                          : glintCellMarginals(dict, cell.dictionaryLevel, distributions, cell.complement, rotation,
                                               cellUnscaled);
            p *= cell.scalePrecision;
          }
          // Alg. 2, line 3 of Chermain et al. 2020.
          float weighted = covered * p;
          dictionarySum[k] += weighted;
          if (params.colouredCells) {
            chromaSum[k] += weighted * chroma;
          }
        }
      }
    }
  }
  GlintP22Set p22;
  for (int k = 0; k < GLINT_SLOPE_COUNT; ++k) {
    p22.p22[k] = glintSplat4(0.0f);
    if (weightSum > 0.0f) {
      float smoothPart = 0.0f;
      if (smoothWeightSum > 0.0f) {
        float smoothP22 = filtering ? glintFilteredTargetP22(params, slopes.slope[k], slopeKernel[k])
                                 : glintTargetP22(params.ndf, slopes.slope[k], params.alpha, params.rho);
        smoothPart = smoothWeightSum * smoothP22;
      }
      float tailPart = 0.0f;
      if (tailWeightSum > 0.0f) {
        vec3 covariance = glintBeckmannSlopeCovariance(params.alpha, params.rho) + (filtering ? slopeKernel[k] : glintSplat3(0.0f));
        tailPart = tailWeightSum * glintStudentTailSlopeP22(slopes.slope[k], covariance);
      }
      p22.p22[k] = glintLevelAverage(params, dictionarySum[k], chromaSum[k], glintScalingJacobian(dict, params), smoothPart, tailPart,
                                     weightSum);
    }
  }
  return p22;
}

// The P-SDF: P22 over the pixel footprint, blended between two levels (Alg. 1, line 8 of Chermain et
// al. 2020; method.md 2.3), at each slope, in .w; .rgb weighted by the cells' colours.
GLINT_FN GlintP22Set glintP22Set(GlintDictionaryView dict, GlintParameters params, vec2 uv, vec2 duvdx, vec2 duvdy,
                                 GlintSlopeSet slopes) {
  GlintFootprint footprint = glintPixelFootprint(duvdx, duvdy, params, dict.numLevels);
  GlintP22Set p22;
  if (footprint.degenerate) {
    for (int k = 0; k < GLINT_SLOPE_COUNT; ++k) {
      p22.p22[k] = glintSplat4(glintFilteredTargetP22(params, slopes.slope[k], glintKernelCovariance(slopes.derivatives[k])));
    }
    return p22;
  }
  vec2 wrapped = glintWrapUv(uv, dict.numLevels);
  int level = glintLodLevel(footprint);
  float blend = glintLodBlend(footprint);
  GlintLevelDraw draw = glintLevelDraw(dict, params, footprint.logDensity, level);
  p22 = glintLevelP22(dict, params, footprint, wrapped, level, draw, slopes);
  for (int k = 0; k < GLINT_SLOPE_COUNT; ++k) {
    p22.p22[k] = (1.0f - blend) * p22.p22[k];
  }
  if (blend > 0.0f) {
    GlintLevelDraw next = glintNextLevelDraw(dict, params, footprint.logDensity, level, draw);
    GlintP22Set coarser = glintLevelP22(dict, params, footprint, wrapped, level + 1, next, slopes);
    for (int k = 0; k < GLINT_SLOPE_COUNT; ++k) {
      p22.p22[k] += blend * coarser.p22[k];
    }
  }
  return p22;
}

// The P-SDF at one slope.
GLINT_FN vec4 glintP22Coloured(GlintDictionaryView dict, GlintParameters params, vec2 uv, vec2 duvdx, vec2 duvdy,
                               vec2 slope) {
  return glintP22Set(dict, params, uv, duvdx, duvdy, glintSingleSlope(slope)).p22[0];
}

GLINT_FN float glintP22(GlintDictionaryView dict, GlintParameters params, vec2 uv, vec2 duvdx, vec2 duvdy, vec2 slope) {
  return glintP22Coloured(dict, params, uv, duvdx, duvdy, slope).w;
}

// The anti-aliased P-SDF at one slope with screen derivatives (times the kernel size) `derivatives`
// (glint_antialiasing.h); zero derivatives give glintP22.
GLINT_FN float glintFilteredP22(GlintDictionaryView dict, GlintParameters params, vec2 uv, vec2 duvdx, vec2 duvdy,
                                vec2 slope, vec4 derivatives) {
  GlintSlopeSet slopes = glintSingleSlope(slope);
  for (int k = 0; k < GLINT_SLOPE_COUNT; ++k) {
    slopes.derivatives[k] = derivatives;
  }
  return glintP22Set(dict, params, uv, duvdx, duvdy, slopes).p22[0].w;
}

// The P-NDF at a normal m (m.z > 0): D_P(m) = P22_P(slope(m)) / m.z^4 (Chermain et al. 2020: the
// slope is Eq. 1, Alg. 1, line 2; D_P is Alg. 1, line 10).
GLINT_FN float glintNdf(GlintDictionaryView dict, GlintParameters params, vec2 uv, vec2 duvdx, vec2 duvdy, vec3 m) {
  return glintNdfFromP22(glintP22(dict, params, uv, duvdx, duvdy, glintSlopeFromNormal(m)), m.z);
}

// The Cook-Torrance frame around a P-NDF value with the material's masking (microfacet_targets.h).
GLINT_FN float glintMaskedReflectance(GlintParameters params, vec3 wo, vec3 wi, vec3 wh, float ndf) {
  return glintMaskedMicrofacetReflectance(params.masking, params.ndf, params.alpha, params.rho, wo, wi, wh, ndf);
}

// The glint BRDF, Eq. 14 of Chermain et al. 2020 (Alg. 1; wh is its line 1), F = 1, no colour or
// cosine.
GLINT_FN float glintReflectance(GlintDictionaryView dict, GlintParameters params, vec2 uv, vec2 duvdx, vec2 duvdy,
                                vec3 wo, vec3 wi) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) {
    return 0.0f;
  }
  vec3 wh = normalize(wo + wi);
  return glintMaskedReflectance(params, wo, wi, wh, glintNdf(dict, params, uv, duvdx, duvdy, wh));
}

GLINT_KERNEL_END

#endif
