// One cell of the 2020 glint model (Chermain et al. 2020, Eq. 11 and Alg. 3; method.md 2.5): its
// hash, its dictionary level drawn from its expected microfacet count with the density
// randomisation, its rotation and pair of distributions, the slope scaling, and its colour.
#ifndef GLINT_KERNEL_GLINT_CELL_H
#define GLINT_KERNEL_GLINT_CELL_H

#include "prelude.h"
#include "random.h"
#include "dictionary_lookup.h"
#include "glint_parameters.h"

GLINT_KERNEL_BEGIN

// A cell's random colour (the paper's "cheap iridescence"), as its offset from white in the chroma
// plane (colours whose channels average 1): white + a U + b V (glintTintedP22), (a, b) uniform on a
// square of half-width 0.85, so the expected colour is white; at two corners the weakest channel is
// 1 - 0.85 (1 / sqrt 6 + 1 / sqrt 2) = 0.05, never below 0. It reads the low 8 bits the draws leave of
// the first two lanes (glintHashToUnitOpen takes the top 24): no second hash. Linear in (a, b), so a
// footprint's colour sums two numbers a slope. A second hash and a hue wheel cost the coloured car
// paint 8% more fragment instructions than the uncoloured; this 3% (docs/benchmarks.md, "What made it
// fast, and why").
GLINT_FN vec2 glintCellChroma(uvec4 h) {
  return vec2(float(h.x & 0xFFu) - 127.5f, float(h.y & 0xFFu) - 127.5f) * (0.85f / 127.5f);
}

// The colour-weighted P22 from the P22 sum and the chroma sum (P22-weighted glintCellChroma): white
// times the P22 plus the chroma along U = (2, -1, -1) / sqrt 6 and V = (0, 1, -1) / sqrt 2.
GLINT_FN vec3 glintTintedP22(float p22, vec2 chroma) {
  return glintSplat3(p22) + chroma.x * vec3(0.81649658f, -0.40824829f, -0.40824829f) +
         chroma.y * vec3(0.0f, 0.70710678f, -0.70710678f);
}

// The random properties of one cell (method.md 2.5), each drawn in one place, which the P-SDF and the
// host's importance sampler (src/glint/microfacet_sampling.cpp) both call.
//
// Coherent index (Alg. 3, line 1 of Chermain et al. 2020): the level-0 index of the cell's first
// child, so a cell and its descendants draw the same numbers. Masked to the period, the pair is a
// collision-free seed (in place of Alg. 3, line 2's s + 1549 t, which collides); glintPcg4d's four
// lanes are the cell's four draws.
GLINT_FN uvec4 glintCellHash(GlintParameters params, int cellX, int cellY, int level) {
  uint s = (uint(cellX) << uint(level)) & GLINT_CELL_INDEX_MASK;
  uint t = (uint(cellY) << uint(level)) & GLINT_CELL_INDEX_MASK;
  return glintPcg4d(uvec4(s, t, params.patternSeed, 0u));
}

// Microfacet relative area: microfacets with probability MRA (Alg. 3, lines 3-4 of Chermain et al.
// 2020).
GLINT_FN bool glintCellHasMicrofacets(GlintParameters params, uvec4 h) {
  return !(glintHashToUnitOpen(h.x) > params.relativeArea);
}

// n = cellArea * e^D microfacets, cellArea = 4^(level - (L-1)); the dictionary level is
// round(log4(n) + zeta N) clamped to [0, L], N = sqrt 2 erfinv(2 u - 1) from the cell's uniform u,
// level L the smooth limit (Alg. 3, lines 5-9 of Chermain et al. 2020; level L is its line 10).
// Without inverting the normal per cell: the level reaches j when u >= Phi((j - log4(n) - 1/2) / zeta),
// L thresholds that glintLevelDraw computes once per footprint level; a cell's level is the count its
// u passes, a binary search of five comparisons (erfinv was 19% of the glint shader's instructions).
// Thresholds past the dictionary's L are above every u, so the search has a fixed length.
GLINT_CONST int GLINT_MAX_DICTIONARY_LEVELS = 16;  // the largest L a Dictionary accepts

struct GlintLevelDraw {
  float threshold[GLINT_MAX_DICTIONARY_LEVELS];  // threshold[j - 1]: the u from which the level is >= j
};

// The threshold from which a cell of this footprint level reaches dictionary level j. The margin
// j - log4(n) - 1/2 is an exact integer minus a part the same at every level, so level + 1's
// thresholds are level's shifted by one, bit for bit (glintNextLevelDraw).
GLINT_FN float glintLevelThreshold(GlintDictionaryView dict, GlintParameters params, float logDensity, int level, int j) {
  if (j > dict.numLevels) {
    return 2.0f;  // never: u < 2
  }
  float margin = float(j + (dict.numLevels - 1) - level) - (logDensity * GLINT_INV_LN4 + 0.5f);
  if (params.densityRandomisation > 0.0f) {
    return glintNormalCdf(margin / params.densityRandomisation);  // the normal must reach margin / zeta
  }
  return margin <= 0.0f ? 0.0f : 2.0f;  // no randomisation: round(log4(n)) itself
}

GLINT_FN GlintLevelDraw glintLevelDraw(GlintDictionaryView dict, GlintParameters params, float logDensity, int level) {
  GlintLevelDraw draw;
  for (int j = 1; j <= GLINT_MAX_DICTIONARY_LEVELS; ++j) {
    draw.threshold[j - 1] = glintLevelThreshold(dict, params, logDensity, level, j);
  }
  return draw;
}

// glintLevelDraw(level + 1) from glintLevelDraw(level) with one glintNormalCdf instead of L: cells 4
// times larger, log4(n) one more, so its threshold for j is this level's for j - 1.
GLINT_FN GlintLevelDraw glintNextLevelDraw(GlintDictionaryView dict, GlintParameters params, float logDensity, int level,
                                           GlintLevelDraw draw) {
  GlintLevelDraw next;
  next.threshold[0] = glintLevelThreshold(dict, params, logDensity, level + 1, 1);
  for (int j = 2; j <= GLINT_MAX_DICTIONARY_LEVELS; ++j) {
    next.threshold[j - 1] = j > dict.numLevels ? 2.0f : draw.threshold[j - 2];
  }
  return next;
}

GLINT_FN int glintCellDictionaryLevel(GlintLevelDraw draw, uvec4 h) {
  float u = glintHashToUnitOpen(h.y);
  // The thresholds rise with j: a binary search over the 16, four comparisons each against a threshold
  // the earlier ones select (selects of constant indices, no indexed read), plus the last threshold's.
  // The same count as 16 comparisons; 0.8% fewer instructions in the car's fragment shader
  // (docs/benchmarks.md, item 10 of "What made it fast").
  bool b8 = u >= draw.threshold[7];
  bool b4 = u >= (b8 ? draw.threshold[11] : draw.threshold[3]);
  float t2 = b8 ? (b4 ? draw.threshold[13] : draw.threshold[9]) : (b4 ? draw.threshold[5] : draw.threshold[1]);
  bool b2 = u >= t2;
  float t1 = b8 ? (b4 ? (b2 ? draw.threshold[14] : draw.threshold[12]) : (b2 ? draw.threshold[10] : draw.threshold[8]))
                : (b4 ? (b2 ? draw.threshold[6] : draw.threshold[4]) : (b2 ? draw.threshold[2] : draw.threshold[0]));
  bool b1 = u >= t1;
  return (b8 ? 8 : 0) + (b4 ? 4 : 0) + (b2 ? 2 : 0) + (b1 ? 1 : 0) + (u >= draw.threshold[15] ? 1 : 0);
}

// The cell's rotation theta = 2 pi hash (Alg. 3, line 13 of Chermain et al. 2020), as (cos theta,
// sin theta). Reduced exactly to [-pi/4, pi/4] in quarter turns (hash * 4 and its rounding are
// exact), then Cephes' single-precision minimax cosf and sinf (error below 2e-7,
// GlintBrdf.CellRotationMatchesTheAngle). llvmpipe's sin and cos each reduce the angle: the pair was
// 12% of the glint shader's instructions, this about a third of that.
GLINT_FN vec2 glintCellRotation(uvec4 h) {
  float quarterTurns = 4.0f * glintHashToUnitOpen(h.z);
  float quadrant = floor(quarterTurns + 0.5f);
  float phi = (quarterTurns - quadrant) * 1.57079633f;
  float phi2 = phi * phi;
  float s = phi + phi * phi2 * (-1.6666654611e-1f + phi2 * (8.3321608736e-3f + phi2 * -1.9515295891e-4f));
  float c = 1.0f - 0.5f * phi2 +
            phi2 * phi2 * (4.166664568298827e-2f + phi2 * (-1.388731625493765e-3f + phi2 * 2.443315711809948e-5f));
  int quarter = int(quadrant) & 3;
  vec2 rotation = (quarter & 1) != 0 ? vec2(-s, c) : vec2(c, s);  // a quarter turn: (c, s) -> (-s, c)
  return quarter >= 2 ? -rotation : rotation;                     // a half turn
}

// The cell's two distributions (i, j) (Alg. 3, lines 17-18 of Chermain et al. 2020) from the last
// lane's 16-bit halves: exact integer arithmetic in every language.
GLINT_FN ivec2 glintCellDistributions(GlintDictionaryView dict, uvec4 h) {
  uint n = uint(dict.numDistributions);
  return ivec2(int(((h.w >> 16u) * n) >> 16u), int(((h.w & 0xFFFFu) * n) >> 16u));
}

// Into the dictionary's space, (x', y') = R(-theta) M^-1 slope (Alg. 3, line 16 of Chermain et al.
// 2020; Eq. 5 of Chermain et al. 2021, I3D), in two steps: undo the scaling and correlation M (Eq.
// 18 of the 2021 paper; with rho = 0 the 2020 S = alpha / alpha_d), the same for every cell ...
GLINT_FN vec2 glintUnscaledSlope(GlintDictionaryView dict, GlintParameters params, vec2 slope) {
  return glintCorrelatedUnscale(slope, params.alpha, params.rho, dict.alpha);
}

// ... whose inverse takes a dictionary-space slope, rotated back, to the target's slopes.
GLINT_FN vec2 glintScaledSlope(GlintDictionaryView dict, GlintParameters params, vec2 unscaled) {
  return glintCorrelatedScale(unscaled, params.alpha, params.rho, dict.alpha);
}

// ... then the cell's rotation.
GLINT_FN vec2 glintDictionarySlope(vec2 rotation, vec2 unscaled) {
  float x = rotation.x * unscaled.x + rotation.y * unscaled.y;
  float y = -rotation.y * unscaled.x + rotation.x * unscaled.y;
  return vec2(x, y);
}

// Jacobian of the scaling, det(M^-1): the 1 / (S_x S_y) of Alg. 3, line 19 of Chermain et al. 2020.
GLINT_FN float glintScalingJacobian(GlintDictionaryView dict, GlintParameters params) {
  return glintCorrelatedJacobian(params.alpha, params.rho, dict.alpha);
}

// Whether an unscaled slope lies beyond the dictionary's square support at every rotation: past its
// circumradius 4 sigma_d sqrt 2.
GLINT_FN bool glintBeyondEveryRotatedSupport(GlintDictionaryView dict, vec2 unscaled) {
  float fourSigma = glintDictionaryDomain(dict);
  return dot(unscaled, unscaled) >= 2.0f * fourSigma * fourSigma;
}

// The real-time renderer's one approximation (docs/renderer.md, "Cost"): beyond every rotated support
// no dictionary cell reflects and the smooth P22 is below exp(-16) = 1.1e-7 of its peak
// (|unscaled|^2 / (2 sigma_d^2) >= 16), so the renderer takes P22 = 0 for that light and skips the
// walk when no light is left. The CPU BSDF keeps the exact value: its sampler can draw such a slope
// from a smooth cell and needs a non-zero pdf there. With GGX the widest cell reaches 10 times
// further, a slope of 40 alpha, where GGX's P22 (and remainder) is below (1 + 1600)^-2 = 3.9e-7 of its
// peak.
GLINT_FN bool glintSlopeIsNegligible(GlintDictionaryView dict, GlintParameters params, vec2 slope) {
  return glintBeyondEveryRotatedSupport(dict, glintUnscaledSlope(dict, params, slope) / glintTargetWidestCell(params.ndf));
}

// One cell's contribution to P22 (method.md 2.5): its SDF of Eq. 11 and Alg. 3 of Chermain et al.
// 2020 (with correlation, Eq. 4 of Chermain et al. 2021, I3D). What is the same for every cell is
// computed once per footprint (glintLevelP22), what is the same for every slope once per cell: a cell
// is empty, smooth (the target's P22) or reads the dictionary (two marginals at its rotated slope
// times the scaling Jacobian).
struct GlintCell {
  uvec4 hash;
  bool readsDictionary;
  bool smoothLimit;
  bool ggxTail;         // a GGX cell in the smooth remainder of the scale mixture (microfacet_targets.h)
  int dictionaryLevel;  // when it reads the dictionary: the level of the tables it reads (glintTreeTableLevel)
  // Its distributions (i, j): glintCellDistributions, but under the tree construction those chosen
  // by its descent from its own cell (glintLodCell).
  ivec2 distributions;
  // Consistent LOD (glintLodCell): 1 on an axis whose marginal is the lobes dictionary level
  // dictionaryLevel + 1 adds (glintBlockMarginal), 0 for the level itself. 0 under paper and tree.
  ivec2 complement;
  // GGX: the cell's precision w; its dictionary slopes are the unscaled slope times sqrt(w) (unscale),
  // its P22 times w (the Jacobian). 1 for Beckmann.
  float scalePrecision;
  float unscale;
  // The share of the cell's area its microfacets cover, multiplying its P22: 1 but under the tree
  // construction, which carries the relative area down as coverage instead of drawing it
  // (glintTreeOwnCell).
  float coverage;
};

GLINT_FN GlintCell glintCell(GlintDictionaryView dict, GlintParameters params, GlintLevelDraw draw, int cellX, int cellY,
                             int level) {
  GlintCell cell;
  cell.hash = glintCellHash(params, cellX, cellY, level);
  cell.readsDictionary = false;
  cell.smoothLimit = false;
  cell.ggxTail = false;
  cell.dictionaryLevel = 0;
  cell.distributions = ivec2(0, 0);
  cell.complement = ivec2(0, 0);
  cell.scalePrecision = 1.0f;
  cell.unscale = 1.0f;
  cell.coverage = 1.0f;
  if (glintCellHasMicrofacets(params, cell.hash)) {
    cell.dictionaryLevel = glintCellDictionaryLevel(draw, cell.hash);
    cell.distributions = glintCellDistributions(dict, cell.hash);  // read only where it reads the dictionary
    // The smooth limit (Alg. 3, line 10): colours average out to white too.
    cell.smoothLimit = cell.dictionaryLevel == dict.numLevels;
    cell.readsDictionary = !cell.smoothLimit;
    if (params.ndf == GLINT_NDF_GGX && cell.readsDictionary) {
      // GGX scale mixture: glints of roughness alpha / sqrt(w), or the smooth remainder below the cut.
      float w = glintCellPrecision(cell.hash);
      cell.ggxTail = w < GLINT_GGX_TAIL_PRECISION;
      cell.readsDictionary = !cell.ggxTail;
      cell.scalePrecision = w;
      cell.unscale = sqrt(w);
    }
  }
  return cell;
}

GLINT_KERNEL_END

#endif
