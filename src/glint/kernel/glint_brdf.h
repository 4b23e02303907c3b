// The glint BRDF of Chermain, Sauvage, Dischler & Dachsbacher 2020, "Procedural Physically based
// BRDF for Real-Time Rendering of Glints" (Pacific Graphics; CGF 39(7)): the P-SDF over a pixel
// footprint (docs/conventions.md), its P-NDF, and the BRDF. The walk over the footprint's cells
// also carries the 2021 extension's slope correlation and anti-aliasing filter
// (glint_antialiasing.h), which leave the 2020 values unchanged bit for bit when rho = 0 and the
// slopes have no derivatives.
// Shared by the CPU library and the GLSL renderer: see prelude.h for the rules.
#ifndef GLINT_KERNEL_GLINT_BRDF_H
#define GLINT_KERNEL_GLINT_BRDF_H

#include "prelude.h"
#include "random.h"
#include "microfacet.h"
#include "dictionary_lookup.h"
#include "glint_antialiasing.h"
#include "microfacet_targets.h"

GLINT_KERNEL_BEGIN

GLINT_CONST float GLINT_INV_LN4 = 0.72134752f;  // 1 / ln(4): log4(n) = ln(n) / ln(4)
// Gaussian filter of pbrt-v3's EWA: exp(-alpha r^2) - exp(-alpha), alpha = 2.
GLINT_CONST float GLINT_EWA_FILTER_FLOOR = 0.13533528f;  // exp(-2)
// The level-0 cell grid wraps after 2^16 cells per axis, which makes the 32-bit cell seed
// (s | t << 16) collision-free over the whole period; see glintFootprintPeriod().
GLINT_CONST uint GLINT_CELL_INDEX_MASK = 0xFFFFu;

// How far the renderer may depart from the paper's pixel footprint to bound the cost of the walk
// over its cells (docs/antialiasing.md, "Footprint policies"): a setting of the renderer, not of the
// material, shared by the P-SDF and the host's sampler (glintPixelFootprint), so that both keep
// seeing the same cells. All zero is the paper's footprint (`exact`), bit for bit.
struct GlintFootprintPolicy {
  float maxAnisotropy;  // aniso=A: a second anisotropy clamp, min(A, the material's); 0: none
  float maxCells;       // cells=K: the walk of each level visits at most K cells; 0: no bound
  float minBlend;       // drop=W: the coarser level is skipped below this blend weight; 0: never
};

// How the cells of neighbouring levels of detail relate (method.md 2.7): GLINT_LOD_PAPER, each cell
// draws its own glints (the 2020 model; a cell shares its first child's draws through the coherent
// index only); GLINT_LOD_CONSISTENT, a cell's four children share out its lobes, so that its P-SDF
// is the mean of theirs wherever the nested dictionary can split it; GLINT_LOD_TREE, every cell
// below a level set by the density is the mean of its four children, read from the dictionary's
// tree levels (method.md 2.8).
GLINT_CONST int GLINT_LOD_PAPER = 0;
GLINT_CONST int GLINT_LOD_CONSISTENT = 1;
GLINT_CONST int GLINT_LOD_TREE = 2;

// Which constructions are compiled in. A GLSL program is compiled for the construction its
// material uses (GLINT_LOD_CONSTRUCTION 0, the paper's, pays nothing for the others, as llvmpipe
// runs both sides of a branch; 1 or 2 compiles that one in beside it, and the material's `lod`
// chooses); C++ and programs that leave it undefined compile all, and the paper's values are the
// same bit for bit either way.
#if defined(__cplusplus) || !defined(GLINT_LOD_CONSTRUCTION)
#define GLINT_CONSISTENT_LOD_COMPILED 1
#define GLINT_TREE_LOD_COMPILED 1
#else
#define GLINT_CONSISTENT_LOD_COMPILED (GLINT_LOD_CONSTRUCTION == 1)
#define GLINT_TREE_LOD_COMPILED (GLINT_LOD_CONSTRUCTION == 2)
#endif

// The material inputs of the model (method.md section 2), validated by the host.
struct GlintParameters {
  vec2 alpha;                  // roughness alpha_x, alpha_y of the target Beckmann distribution
  float rho;                   // its slope correlation, in (-1, 1) (glint_antialiasing.h)
  float logDensity;            // D = ln(microfacets per unit uv area)
  float relativeArea;          // MRA, in (0, 1]: probability that a cell has microfacets (tree LOD: its coverage)
  float densityRandomisation;  // zeta: std of the per-cell dictionary level around log4(n)
  float maxAnisotropy;         // footprint ellipses are widened to at most this ratio
  uint patternSeed;            // selects an independent glint pattern for the same uv
  bool colouredCells;          // each cell reflects a random colour (car paint's coloured flakes)
  int ndf;                     // the smooth target: GLINT_NDF_BECKMANN (the paper's) or GLINT_NDF_GGX (microfacet_targets.h)
  int masking;                 // GLINT_MASKING_VCAVITY (the paper's) or GLINT_MASKING_SMITH
  int lod;                     // GLINT_LOD_PAPER, GLINT_LOD_CONSISTENT or GLINT_LOD_TREE (method.md 2.7, 2.8)
  // Adds the smooth target's multiple-scattering compensation lobe (multiple_scattering.h); the
  // BRDF's users add it (the host's BSDFs, the renderer), the P-SDF does not see it.
  bool multipleScattering;
  GlintFootprintPolicy footprintPolicy;  // the renderer's, not the material's: zero is the paper's
};

// The pixel footprint as an ellipse in uv space with its continuous level of detail.
struct GlintFootprint {
  vec2 majorAxis;    // uv units, after the anisotropy and size clamps
  vec2 minorAxis;
  float lod;         // in [0, L - 1]; level floor(lod) blended with the next one
  float logDensity;  // the material's, plus the area taken off by the size clamp
  bool degenerate;   // no area: the smooth Beckmann limit applies
};

// uv period of the pattern: 2^16 level-0 cells of 2^(L-1) per uv unit (2 uv units for L = 16).
GLINT_FN float glintFootprintPeriod(int numLevels) {
  return exp2(float(17 - numLevels));
}

// Footprint ellipse and continuous LOD (method.md 2.2-2.3), after pbrt-v3 MIPMap::Lookup: the
// pixel's footprint is the ellipse duvdx cos t + duvdy sin t, its minor axis is widened so that
// the anisotropy is at most maxAnisotropy, and the LOD is the (widened) minor axis in cells.
// Going past the paper and pbrt-v3 in two ways:
//   - The two derivatives are conjugate semi-diameters of the ellipse, not its axes: they are
//     perpendicular only where the uv map is conformal along the screen axes. pbrt-v3 takes the
//     shorter one as the minor axis; as conjugate semi-diameters satisfy |duvdx|^2 + |duvdy|^2 =
//     major^2 + minor^2, the shorter can be up to sqrt((major^2 + minor^2) / 2), about the
//     anisotropy / sqrt 2 times the minor axis. The LOD then picks cells that many times longer
//     across the ellipse than the pixel, which neighbouring pixels share as streaks (at a UV
//     sphere's pole u's derivative is ten times v's, and the screen axes turn around the pole:
//     docs/renderer.md, "Footprint"). Here the axes are the ellipse's principal axes, from the
//     singular value decomposition of J = [duvdx duvdy], whichever way the screen axes turn.
//   - A footprint whose minor axis exceeds one uv unit is shrunk to one and the area it loses is
//     added to the density, so the LOD stays within the dictionary and the cost stays bounded,
//     while the number of microfacets seen is unchanged.
GLINT_FN GlintFootprint glintFootprint(vec2 duvdx, vec2 duvdy, float maxAnisotropy, float logDensity,
                                       int numLevels) {
  // Derivatives beyond 1e6 uv units (the pattern's period is 2) are scaled down together, so that
  // their squares stay finite in float (1e20 squared is not); such a footprint is in the smooth
  // limit either way. Below that, the scale is exactly 1.
  float longest = max(max(abs(duvdx.x), abs(duvdx.y)), max(abs(duvdy.x), abs(duvdy.y)));
  float fit = longest > 1e6f ? 1e6f / longest : 1.0f;
  vec2 dx = duvdx * fit;
  vec2 dy = duvdy * fit;
  // J J^T = [[a, b], [b, c]]: its eigenvalues are the squared semi-axes. The larger one,
  // (a + c) / 2 + sqrt(((a - c) / 2)^2 + b^2), is a sum of non-negative terms; the smaller is
  // taken as det(J)^2 over it (|det J| = the product of the semi-axes), which does not cancel
  // when the ellipse is thin.
  float a = dx.x * dx.x + dy.x * dy.x;
  float b = dx.x * dx.y + dy.x * dy.y;
  float c = dx.y * dx.y + dy.y * dy.y;
  float halfDifference = 0.5f * (a - c);
  float root = sqrt(halfDifference * halfDifference + b * b);
  float majorLength = sqrt(0.5f * (a + c) + root);
  float minorLength = majorLength > 0.0f ? abs(dx.x * dy.y - dx.y * dy.x) / majorLength : 0.0f;
  // The major axis's direction, the eigenvector of the larger eigenvalue: (lambda - c, b) or
  // (b, lambda - a), whichever sums non-negative terms (lambda - c = halfDifference + root). A
  // circle has no preferred direction: u.
  vec2 direction = halfDifference >= 0.0f ? vec2(halfDifference + root, b) : vec2(b, root - halfDifference);
  float directionLength = length(direction);
  direction = directionLength > 0.0f ? direction / directionLength : vec2(1.0f, 0.0f);
  // The anisotropy clamp: the minor axis at least majorLength / maxAnisotropy, set directly (a
  // ratio of the two lengths overflows for a thin enough ellipse). No area stays no area.
  if (minorLength > 0.0f) {
    minorLength = max(minorLength, majorLength / maxAnisotropy);
  }
  vec2 major = direction * majorLength;
  vec2 minor = vec2(-direction.y, direction.x) * minorLength;
  GlintFootprint footprint;
  footprint.logDensity = logDensity;
  if (minorLength > 1.0f) {
    float shrink = 1.0f / minorLength;
    major = major * shrink;
    minor = minor * shrink;
    footprint.logDensity = logDensity + 2.0f * log(minorLength);
    minorLength = 1.0f;
  }
  footprint.majorAxis = major;
  footprint.minorAxis = minor;
  footprint.degenerate = !(minorLength > 0.0f);
  footprint.lod = footprint.degenerate ? 0.0f : max(0.0f, float(numLevels - 1) + log2(minorLength));
  return footprint;
}

// A cell's random colour (the paper's "cheap iridescence"), as its offset from white in the
// chroma plane, the colours whose channels average 1: white + a U + b V, with U and V the plane's
// orthonormal axes (glintTintedP22). (a, b) is uniform on a square of half-width 0.85, so the
// expected colour is white and the mean appearance that of uncoloured glints; at two of the
// square's corners the weakest channel is 1 - 0.85 (1 / sqrt 6 + 1 / sqrt 2) = 0.05, never below 0.
// It reads the bits the model's draws leave (glintHashToUnitOpen takes the top 24 of a lane): the
// low 8 of the first two lanes, so the draws stay untouched and there is no second hash. Being
// linear in (a, b), a footprint's colour sums two numbers a slope, not three. With a second hash
// and a hue wheel, the coloured car paint's fragment shader ran 8% more instructions than the
// uncoloured one; now 3% (docs/benchmarks.md, "What made it fast, and why").
GLINT_FN vec2 glintCellChroma(uvec4 h) {
  return vec2(float(h.x & 0xFFu) - 127.5f, float(h.y & 0xFFu) - 127.5f) * (0.85f / 127.5f);
}

// The colour-weighted P22 of a footprint from its P22 sum and its chroma sum (the P22-weighted sum
// of its cells' glintCellChroma): white times the P22 plus the chroma along the plane's axes
// U = (2, -1, -1) / sqrt 6 and V = (0, 1, -1) / sqrt 2.
GLINT_FN vec3 glintTintedP22(float p22, vec2 chroma) {
  return glintSplat3(p22) + chroma.x * vec3(0.81649658f, -0.40824829f, -0.40824829f) +
         chroma.y * vec3(0.0f, 0.70710678f, -0.70710678f);
}

// The random properties of one cell (method.md 2.5), each drawn in exactly one place: the P-SDF
// below and the importance sampler of the host (src/glint/microfacet_sampling.cpp) both call these.
//
// Coherent index: the level-0 index of the cell's first child, so that a cell and its descendants
// draw the same random numbers (method.md 2.5). Masked to the period, the pair is a collision-free
// seed; glintPcg4d's four lanes are the cell's four draws.
GLINT_FN uvec4 glintCellHash(GlintParameters params, int cellX, int cellY, int level) {
  uint s = (uint(cellX) << uint(level)) & GLINT_CELL_INDEX_MASK;
  uint t = (uint(cellY) << uint(level)) & GLINT_CELL_INDEX_MASK;
  return glintPcg4d(uvec4(s, t, params.patternSeed, 0u));
}

// Microfacet relative area: the cell holds microfacets with probability MRA (method.md 2.5).
GLINT_FN bool glintCellHasMicrofacets(GlintParameters params, uvec4 h) {
  return !(glintHashToUnitOpen(h.x) > params.relativeArea);
}

// Number of microfacets n = cellArea * e^D, cellArea = 4^(level - (L-1)); the dictionary level is
// log4(n) randomised by a normal of std zeta (method.md 2.5), rounded, and the top level L means "so
// many microfacets that the smooth Beckmann limit holds": round(log4(n) + zeta N) clamped to [0, L],
// N = sqrt 2 erfinv(2 u - 1) the standard normal drawn from the cell's uniform u.
//
// The same draw without inverting the normal per cell: the level reaches j exactly when
// log4(n) + 1/2 + zeta N >= j, that is when u >= Phi((j - log4(n) - 1/2) / zeta). The L thresholds
// depend on the footprint level only, so glintLevelDraw computes them once per footprint and a
// cell's level is the number of thresholds its u passes, found by a binary search of five
// comparisons, instead of a logarithm and two polynomials per cell (the inverse error function was
// 19% of the glint shader's instructions). Thresholds past the dictionary's L are above every u,
// so the search has a fixed length.
GLINT_CONST int GLINT_MAX_DICTIONARY_LEVELS = 16;  // the largest L a Dictionary accepts

struct GlintLevelDraw {
  float threshold[GLINT_MAX_DICTIONARY_LEVELS];  // threshold[j - 1]: the u from which the level is >= j
};

// The threshold from which a cell of this footprint level reaches dictionary level j. The margin
// j - log4(n) - 1/2 is an exact integer minus a part that is the same at every level, so the
// thresholds of level + 1 are bit for bit those of level shifted by one (glintNextLevelDraw).
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

// glintLevelDraw(level + 1) from glintLevelDraw(level), with one glintNormalCdf instead of L: the next
// level's cells are 4 times larger, so log4(n) is one more and its threshold for j is this level's
// for j - 1.
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
  // The thresholds rise with j, so the count is a binary search over the GLINT_MAX_DICTIONARY_LEVELS
  // = 16 of them: four comparisons, each against a threshold chosen by the ones before (selects of
  // constant indices, no indexed read), and the last threshold's. Exact: the same count as 16
  // comparisons; the car's fragment shader runs 0.8% fewer instructions (docs/benchmarks.md, item 10 of
  // "What made it fast").
  bool b8 = u >= draw.threshold[7];
  bool b4 = u >= (b8 ? draw.threshold[11] : draw.threshold[3]);
  float t2 = b8 ? (b4 ? draw.threshold[13] : draw.threshold[9]) : (b4 ? draw.threshold[5] : draw.threshold[1]);
  bool b2 = u >= t2;
  float t1 = b8 ? (b4 ? (b2 ? draw.threshold[14] : draw.threshold[12]) : (b2 ? draw.threshold[10] : draw.threshold[8]))
                : (b4 ? (b2 ? draw.threshold[6] : draw.threshold[4]) : (b2 ? draw.threshold[2] : draw.threshold[0]));
  bool b1 = u >= t1;
  return (b8 ? 8 : 0) + (b4 ? 4 : 0) + (b2 ? 2 : 0) + (b1 ? 1 : 0) + (u >= draw.threshold[15] ? 1 : 0);
}

// The cell's random rotation theta = 2 pi hash (method.md 2.5), as (cos theta, sin theta). The
// angle is reduced to [-pi/4, pi/4] in quarter turns, exactly (hash * 4 and its rounding are exact),
// and cos and sin there are Cephes' single-precision minimax polynomials (cosf, sinf; error below
// 2e-7, GlintBrdf.CellRotationMatchesTheAngle). llvmpipe's sin and cos each reduce the angle on
// their own: the pair was 12% of the glint shader's instructions, this is about a third of that.
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

// The cell's two distributions (i, j) from the 16-bit halves of the last lane: exact integer
// arithmetic, the same in both languages.
GLINT_FN ivec2 glintCellDistributions(GlintDictionaryView dict, uvec4 h) {
  uint n = uint(dict.numDistributions);
  return ivec2(int(((h.w >> 16u) * n) >> 16u), int(((h.w & 0xFFFFu) * n) >> 16u));
}

// Into the dictionary's space, (x', y') = R(-theta) M^-1 slope (method.md 2.5), in two steps: undo
// the roughness scaling and correlation M (the same for every cell of a pixel; with rho = 0 the
// 2020 model's S = alpha / alpha_d) ...
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

// Jacobian of the scaling, det(M^-1) (method.md 2.5; with correlation, glintCorrelatedJacobian).
GLINT_FN float glintScalingJacobian(GlintDictionaryView dict, GlintParameters params) {
  return glintCorrelatedJacobian(params.alpha, params.rho, dict.alpha);
}

// Whether an unscaled slope (glintUnscaledSlope) lies beyond the circumradius of the dictionary's
// square support, 4 sigma_d sqrt 2: outside it at every cell rotation.
GLINT_FN bool glintBeyondEveryRotatedSupport(GlintDictionaryView dict, vec2 unscaled) {
  float fourSigma = glintDictionaryDomain(dict);
  return dot(unscaled, unscaled) >= 2.0f * fourSigma * fourSigma;
}

// The real-time renderer's one approximation (docs/renderer.md, "Cost"): beyond every rotated
// support no dictionary cell reflects, and the smooth cells' Beckmann P22 there is below exp(-16)
// = 1.1e-7 of its peak (|unscaled|^2 / (2 sigma_d^2) >= 16), so the renderer takes P22 = 0 for
// that light, and skips the walk of the footprint's cells when no light is left. The CPU BSDF
// keeps the exact value: its sampler can draw such a slope from a smooth cell and must find a
// non-zero pdf there. With the GGX target the widest cell reaches GLINT_GGX_WIDEST_CELL = 10 times
// further, a slope of 40 alpha, where the smooth GGX P22 (and its remainder) is below
// (1 + 1600)^-2 = 3.9e-7 of its peak.
GLINT_FN bool glintSlopeIsNegligible(GlintDictionaryView dict, GlintParameters params, vec2 slope) {
  return glintBeyondEveryRotatedSupport(dict, glintUnscaledSlope(dict, params, slope) / glintTargetWidestCell(params.ndf));
}

// One cell's contribution to P22 (method.md 2.5), split so that what is the same for every cell of
// the footprint is computed once per footprint (glintLevelP22), not once per cell, and what is the
// same for every slope once per cell: a cell is empty, in the smooth limit (its P22 is the Beckmann
// P22 at the slope), or reads the dictionary (its P22 is the tensor product of two marginals at its
// rotated slope, times the scaling Jacobian).
struct GlintCell {
  uvec4 hash;
  bool readsDictionary;
  bool smoothLimit;
  bool ggxTail;         // a GGX cell in the smooth remainder of the scale mixture (microfacet_targets.h)
  int dictionaryLevel;  // when it reads the dictionary: the level of the tables it reads (glintTreeTableLevel)
  // Its two distributions (i, j): glintCellDistributions of its hash, but under the tree LOD
  // construction those its descent from its own cell chose (glintLodCell).
  ivec2 distributions;
  // Consistent LOD (glintLodCell): 1 on an axis whose marginal is the lobes that dictionary level
  // dictionaryLevel + 1 adds to level dictionaryLevel (glintBlockMarginal), 0 where it is the level
  // itself. Always 0 under GLINT_LOD_PAPER and GLINT_LOD_TREE.
  ivec2 complement;
  // GGX: the cell's precision w of the scale mixture; its dictionary slopes are the unscaled
  // slope times sqrt(w) (unscale) and its P22 is multiplied by w (the Jacobian). 1 for Beckmann.
  float scalePrecision;
  float unscale;
  // The share of the cell's area its microfacets cover, which multiplies its P22 (so its P-NDF
  // integrates to it): 1 but under the tree LOD construction, which carries the relative area
  // down an own cell's subtree as coverage instead of drawing it (glintTreeOwnCell).
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
    // So many microfacets that the smooth limit holds: their colours average out to white too.
    cell.smoothLimit = cell.dictionaryLevel == dict.numLevels;
    cell.readsDictionary = !cell.smoothLimit;
    if (params.ndf == GLINT_NDF_GGX && cell.readsDictionary) {
      // The GGX scale mixture (microfacet_targets.h): glints of roughness alpha / sqrt(w), or the
      // smooth remainder below the cut.
      float w = glintCellPrecision(cell.hash);
      cell.ggxTail = w < GLINT_GGX_TAIL_PRECISION;
      cell.readsDictionary = !cell.ggxTail;
      cell.scalePrecision = w;
      cell.unscale = sqrt(w);
    }
  }
  return cell;
}

// Consistent LOD (method.md 2.7): whether the cell (cellX, cellY) of `level` holds a block of its
// parent's lobes instead of drawing its own. A cell whose marginals are both whole dictionary
// levels (an own cell: its own draws, as in the paper) hands its lobes to its four children: level
// l + 1 of a distribution is level l's lobes plus as many new ones, so its tensor product is four
// blocks of level-l size (prefix or complement on each axis); the first child (the coherent
// index's, whose draws are the parent's already) takes prefix x prefix, the three others the blocks
// with a complement. The nested dictionary tabulates prefixes only, so a block with a complement
// cannot be split again: its children are own cells. Whether a cell is a block therefore depends
// on where it sits in the cell tree alone: the top level's cells are own, and a cell below is a
// block when it is not its parent's first child and its parent is own. 4/7 of the cells deep in
// the tree are own. Bit j of the cell's level-0 corner (the coherent index) says whether its
// level-j ancestor is a first child (0) or not.
GLINT_FN bool glintCellIsBlock(int cellX, int cellY, int level, int numLevels) {
  uint corner = ((uint(cellX) << uint(level)) | (uint(cellY) << uint(level))) & GLINT_CELL_INDEX_MASK;
  bool parentOwn = true;  // the top level's cells are own
  for (int j = GLINT_MAX_DICTIONARY_LEVELS - 2; j >= 0; --j) {
    if (j > level && j < numLevels - 1) {
      bool notFirstChild = ((corner >> uint(j)) & 1u) != 0u;
      parentOwn = !(notFirstChild && parentOwn);  // own(j) from own(j + 1)
    }
  }
  bool notFirstChild = ((corner >> uint(level)) & 1u) != 0u;
  return level < numLevels - 1 && notFirstChild && parentOwn;
}

// Tree LOD (method.md 2.8). The dictionary's tree levels: tree level 0 is dictionary level 0; tree
// level k >= 1 of distribution i, stored after the L levels (table level L - 1 + k), is the mean of
// tree level k - 1 of i and of its partner glintTreePartner(k, i). The host builds them from level 0
// (glint::Dictionary), so that tree level k of i holds the single lobes of level 0's distributions
// i, i + 1, ..., i + 2^k - 1 (mod N): distinct while 2^k <= N, and beyond, each of the N as often
// as the others within one.
GLINT_FN int glintTreeTableLevel(GlintDictionaryView dict, int treeLevel) {
  return treeLevel == 0 ? 0 : dict.numLevels - 1 + treeLevel;
}

// The partner of distribution i at tree level k >= 1: i + 2^(k - 1) (mod N), the window of the level
// below that follows i's. Each level's pairing is a permutation, so every distribution of the level
// below is some distribution's partner exactly once and every tree level's mean marginal is level
// 0's, whose lobes stratify the target (partners drawn at random would weigh some lobes three times
// and others not at all, and the levels' means would drift from the target). Level 0's lobes are
// dealt to the distributions at random (dictionary_generator.cpp), so a window of them is a random
// draw without repetition. Where N divides 2^(k - 1) the partner is i itself: the level
// below already holds every distribution equally often.
// In float, without integer division, which llvmpipe does one lane at a time: every value is an
// integer below 2^24, so exact, and the quotient's rounding is undone by the correction.
GLINT_FN int glintTreePartner(GlintDictionaryView dict, int treeLevel, int distribution) {
  float n = float(dict.numDistributions);
  float shift = exp2(float(treeLevel - 1));
  shift -= n * floor(shift / n);
  shift += shift < 0.0f ? n : (shift >= n ? -n : 0.0f);
  float partner = float(distribution) + shift;
  return int(partner >= n ? partner - n : partner);
}

// The log density the layer's cells draw their microfacets at: D, but under the tree LOD
// construction D + ln MRA, so that the microfacets the paper puts in a share MRA of the cells are
// spread over all of them, as many a unit area and each as bright (glintTreeOwnCell).
GLINT_FN float glintLayerLogDensity(GlintParameters params) {
#if GLINT_TREE_LOD_COMPILED
  if (params.lod == GLINT_LOD_TREE) {
    return params.logDensity + log(params.relativeArea);
  }
#endif
  return params.logDensity;
}

// The footprint level of the tree's own cells: the level at which a cell's dictionary level,
// round(log4(n)), n = e^D 4^(level - (L - 1)) (glintLevelThreshold), is expected to be
// floor(log2 N) - 1, so that an own cell's marginals (2^k of level 0's N lobes) rarely repeat a
// lobe, and a subtree that shares its own cell's rotation holds about N^2 / 4 microfacets.
GLINT_FN int glintTreeOwnLevel(GlintDictionaryView dict, float logDensity) {
  float ownDictionaryLevel = floor(log2(float(dict.numDistributions))) - 1.0f;
  float level = floor(ownDictionaryLevel + float(dict.numLevels - 1) - logDensity * GLINT_INV_LN4 + 0.5f);
  return int(clamp(level, 0.0f, float(dict.numLevels - 1)));
}

// The level draws a footprint level's cells need under the material's LOD construction.
struct GlintLodDraws {
  GlintLevelDraw draw;     // the footprint level's own (glintLevelDraw)
  GlintLevelDraw related;  // consistent: the parent level's; tree: the own level's; paper: unused
  int relatedLevel;        // the level `related` draws for
};

GLINT_FN GlintLodDraws glintLodDraws(GlintDictionaryView dict, GlintParameters params, float logDensity, int level,
                                     GlintLevelDraw draw) {
  GlintLodDraws draws;
  draws.draw = draw;
  draws.related = draw;
  draws.relatedLevel = level;
#if GLINT_CONSISTENT_LOD_COMPILED
  if (params.lod == GLINT_LOD_CONSISTENT) {
    draws.related = glintNextLevelDraw(dict, params, logDensity, level, draw);
    draws.relatedLevel = level + 1;
  }
#endif
#if GLINT_TREE_LOD_COMPILED
  if (params.lod == GLINT_LOD_TREE) {
    draws.relatedLevel = glintTreeOwnLevel(dict, logDensity);
    // The own level's thresholds, one level at a time: one glintNormalCdf a level instead of L
    // (glintNextLevelDraw is glintLevelDraw of the next level bit for bit).
    for (int k = level; k < draws.relatedLevel; ++k) {
      draws.related = glintNextLevelDraw(dict, params, logDensity, k, draws.related);
    }
  }
#endif
  return draws;
}

// Tree LOD: a cell at or above the own level (method.md 2.8) always holds microfacets, drawn at
// the density e^D MRA (glintLayerLogDensity, with `ownDraw`), and they cover the relative area of
// it: the relative area is not drawn per cell, which at the own level would leave an own cell's
// whole subtree dark and share all of another's microfacets out (the snow of a layer of relative
// area 1/4 sparkling in squares, three in four dark), but carried down as coverage and drawn only
// below a single lobe (glintTreeBlockCell), so that every cell stays the mean of its children and
// the cells a few levels below a single lobe are lit as often as the relative area says (above
// them, as on a dense layer's footprints, the relative area scales every cell's P22 alike).
GLINT_FN GlintCell glintTreeOwnCell(GlintDictionaryView dict, GlintParameters params, GlintLevelDraw ownDraw, int cellX,
                                    int cellY, int ownLevel) {
  GlintParameters covered = params;
  covered.relativeArea = 1.0f;
  GlintCell cell = glintCell(dict, covered, ownDraw, cellX, cellY, ownLevel);
  cell.coverage = params.relativeArea;
  return cell;
}

// Tree LOD: the cell (cellX, cellY) of `level`, below the own level, is a block of its parent, down
// from its ancestor at the own level: that own cell's draws (microfacets, rotation, GGX scale,
// colour) with, at each step down, one tree level less and on each axis the distribution or its
// partner as the child's position in its parent says, so that every cell is the mean of its four
// children. Which child takes which block is one of the 2 x 2 square's eight symmetries, hashed from
// the parent: with the position alone a column of cells would share its x marginal all the way
// down and the glints would line up in rows and columns. Below tree level 0 a child keeps its
// parent's single lobe, and the four share out its coverage f: 4 f of cell area, each child taking
// as much as it can hold (min(1, 4 f - r) for the child of rank r in an order hashed from the
// parent), so that a lobe covering a quarter of its cell is one lit child of four, and one
// covering all of it four lit children; the lobe is the same, so the mean stays exact. An own
// cell in the smooth limit or in the GGX tail gives its whole subtree its own P22 and coverage.
GLINT_FN GlintCell glintTreeBlockCell(GlintDictionaryView dict, GlintParameters params, GlintLevelDraw ownDraw,
                                      int ownLevel, int cellX, int cellY, int level) {
  int depth = ownLevel - level;
  GlintCell cell = glintTreeOwnCell(dict, params, ownDraw, cellX >> depth, cellY >> depth, ownLevel);
  if (cell.readsDictionary) {
    int treeLevel = cell.dictionaryLevel;
    ivec2 distributions = cell.distributions;
    float coverage = cell.coverage;
    for (int step = depth - 1; step >= 0; --step) {
      bool sharesCoverage = treeLevel == 0 && coverage > 0.0f && coverage < 1.0f;
      if (treeLevel >= 1 || sharesCoverage) {
        // The parent at this step by its coherent index (so that the symmetry repeats with the
        // pattern's period), one 32-bit word, collision-free (glintCellHash), hashed with a mask
        // of the pattern seed and its level (a parent and its first child share the index).
        int parentLevel = level + step + 1;
        uint s = (uint(cellX >> (step + 1)) << uint(parentLevel)) & GLINT_CELL_INDEX_MASK;
        uint t = (uint(cellY >> (step + 1)) << uint(parentLevel)) & GLINT_CELL_INDEX_MASK;
        uint h = glintPcg((s | (t << 16u)) ^ glintPcg(params.patternSeed + uint(parentLevel) * 2654435769u));
        int childX = (cellX >> step) & 1;
        int childY = (cellY >> step) & 1;
        if (treeLevel >= 1) {
          bool swapAxes = (h & 4u) != 0u;
          int blockX = (swapAxes ? childY : childX) ^ int(h & 1u);
          int blockY = (swapAxes ? childX : childY) ^ int((h >> 1u) & 1u);
          if (blockX != 0) {
            distributions.x = glintTreePartner(dict, treeLevel, distributions.x);
          }
          if (blockY != 0) {
            distributions.y = glintTreePartner(dict, treeLevel, distributions.y);
          }
          treeLevel -= 1;
        } else {
          // The child's rank: its index through an xor and a rotation hashed from the parent, a
          // permutation of the four that puts the lit ones side by side or across the diagonal.
          int rank = (((childX + 2 * childY) ^ int((h >> 3u) & 3u)) + int((h >> 5u) & 3u)) & 3;
          coverage = clamp(4.0f * coverage - float(rank), 0.0f, 1.0f);
        }
      }
    }
    cell.distributions = distributions;
    cell.dictionaryLevel = glintTreeTableLevel(dict, treeLevel);
    cell.coverage = coverage;
    cell.readsDictionary = coverage > 0.0f;
  }
  return cell;
}

// The cell (cellX, cellY) of `level` under the material's LOD construction, with the level draws
// of glintLodDraws. Consistent: a block takes its parent's draws (relative area, dictionary level,
// distributions, rotation, GGX scale, colour), one dictionary level lower, with the complement on
// each axis where its position in the parent is odd; so the mean of the four children's P22 is the
// parent's, to float rounding. A parent without microfacets or in the GGX tail gives its children
// its own (empty or smooth) P22, the same mean. A parent at dictionary level 0 (one lobe) or in the
// smooth limit (level L) has no blocks: its children draw their own, as in the paper. Tree: below
// the own level a block of its own ancestor (glintTreeBlockCell); at the own level, when there are
// blocks below it, an own cell that reads the tree levels, so that it is the mean of its blocks;
// above it, or at level 0, a cell of the paper's, reading the dictionary's own levels (whose
// lobes stay distinct at every level: the tree's hold at most N, which would ripple the dense
// layers' P-SDF about the smooth target). At and above the own level a cell holds microfacets
// at the relative area's coverage instead of drawing it (glintTreeOwnCell).
GLINT_FN GlintCell glintLodCell(GlintDictionaryView dict, GlintParameters params, GlintLodDraws draws, int cellX,
                                int cellY, int level) {
#if GLINT_TREE_LOD_COMPILED
  if (params.lod == GLINT_LOD_TREE) {
    if (draws.relatedLevel > level) {
      return glintTreeBlockCell(dict, params, draws.related, draws.relatedLevel, cellX, cellY, level);
    }
    GlintCell own = glintTreeOwnCell(dict, params, draws.draw, cellX, cellY, level);
    if (own.readsDictionary && level == draws.relatedLevel && level > 0) {
      own.dictionaryLevel = glintTreeTableLevel(dict, own.dictionaryLevel);
    }
    return own;
  }
#endif
  GlintCell cell = glintCell(dict, params, draws.draw, cellX, cellY, level);
#if GLINT_CONSISTENT_LOD_COMPILED
  if (params.lod == GLINT_LOD_CONSISTENT && glintCellIsBlock(cellX, cellY, level, dict.numLevels)) {
    GlintCell parent = glintCell(dict, params, draws.related, cellX >> 1, cellY >> 1, level + 1);
    bool sameForEveryChild = !parent.readsDictionary && !parent.smoothLimit;  // empty, or the GGX tail
    if (sameForEveryChild) {
      cell = parent;
    } else if (parent.readsDictionary && parent.dictionaryLevel >= 1) {
      cell = parent;
      cell.dictionaryLevel = parent.dictionaryLevel - 1;
      cell.complement = ivec2(cellX & 1, cellY & 1);
    }
  }
#endif
  return cell;
}

// One axis's marginal of a cell at |slope| (< 4 sigma_d): dictionary level `level` of the
// distribution, or with `complement` the lobes that level + 1 adds to it, 2 p_{level+1} - p_level
// (method.md 2.7; level + 1 holds level's 2^level lobes and as many new ones, each table their
// mean). Both tables integrate to 1, so the complement does too. Its texels are those of two
// binary16 tables normalised apart, so where level + 1 adds no lobe it can dip below zero, by at
// most 4e-4 of the level's peak in the default dictionary.
GLINT_FN float glintBlockMarginal(GlintDictionaryView dict, int level, int distribution, int complement, float absSlope) {
  float prefix = glintMarginal(dict, level, distribution, absSlope);
#if GLINT_CONSISTENT_LOD_COMPILED
  if (complement != 0) {
    return 2.0f * glintMarginal(dict, level + 1, distribution, absSlope) - prefix;
  }
#endif
  return prefix;
}

// The same filtered by the anti-aliasing kernel: the filter is linear, so the complement's filtered
// value is the difference of the filtered tables'.
GLINT_FN float glintFilteredBlockMarginal(GlintDictionaryView dict, GlintMarginalFilter marginalFilter, int level,
                                          int distribution, int complement, float absSlope) {
  float prefix = glintFilteredMarginal(dict, marginalFilter, level, distribution, absSlope);
#if GLINT_CONSISTENT_LOD_COMPILED
  if (complement != 0) {
    return 2.0f * glintFilteredMarginal(dict, marginalFilter, level + 1, distribution, absSlope) - prefix;
  }
#endif
  return prefix;
}

// The product of a dictionary cell's two marginals at an unscaled slope (glintUnscaledSlope),
// without the scaling Jacobian; 0 outside the cell's rotated support.
GLINT_FN float glintCellMarginals(GlintDictionaryView dict, int dictionaryLevel, ivec2 distributions, ivec2 complement,
                                  vec2 rotation, vec2 unscaled) {
  float fourSigma = glintDictionaryDomain(dict);
  vec2 local = glintDictionarySlope(rotation, unscaled);
  // Written so that a NaN slope (a half vector on the horizon) is outside too.
  if (!(abs(local.x) < fourSigma && abs(local.y) < fourSigma)) {
    return 0.0f;
  }
  return glintBlockMarginal(dict, dictionaryLevel, distributions.x, complement.x, abs(local.x)) *
         glintBlockMarginal(dict, dictionaryLevel, distributions.y, complement.y, abs(local.y));
}

// The same product with both marginals filtered by the anti-aliasing kernel (glint_antialiasing.h)
// at the level of detail of its variance (glintKernelVariance, glintMarginalLod, glintMarginalFilter).
GLINT_FN float glintCellFilteredMarginals(GlintDictionaryView dict, int dictionaryLevel, ivec2 distributions,
                                          ivec2 complement, vec2 rotation, vec2 unscaled,
                                          GlintMarginalFilter marginalFilter) {
  float fourSigma = glintDictionaryDomain(dict);
  vec2 local = glintDictionarySlope(rotation, unscaled);
  // Written so that a NaN slope (a half vector on the horizon) is outside too.
  if (!(abs(local.x) < fourSigma && abs(local.y) < fourSigma)) {
    return 0.0f;
  }
  return glintFilteredBlockMarginal(dict, marginalFilter, dictionaryLevel, distributions.x, complement.x, abs(local.x)) *
         glintFilteredBlockMarginal(dict, marginalFilter, dictionaryLevel, distributions.y, complement.y, abs(local.y));
}

// The smooth target's P22 convolved with the anti-aliasing kernel of slope covariance K: for
// Beckmann exactly glintFilteredBeckmannP22; for GGX the Student t of scale covariance Sigma + K, an
// approximation (a t convolved with a Gaussian is no t), exact where there is no kernel.
GLINT_FN float glintFilteredTargetP22(GlintParameters params, vec2 slope, vec3 kernelCovariance) {
  if (params.ndf != GLINT_NDF_GGX) {
    return glintFilteredBeckmannP22(slope, params.alpha, params.rho, kernelCovariance);
  }
  return glintStudentSlopeP22(slope, glintBeckmannSlopeCovariance(params.alpha, params.rho) + kernelCovariance);
}

// The P-SDF at several slopes from one walk over the footprint's cells. The renderer shades all of
// a pixel's lights at once, one half vector each, so that a cell's hash, dictionary level, rotation
// and distributions are drawn once per pixel instead of once per light (docs/renderer.md, "Cost");
// each slope gets exactly the sums that a walk for it alone would make. The count is a compile-time
// constant: the renderer's programs define it as their scene's light count; the CPU library and
// its sampler evaluate one slope at a time.
#ifndef GLINT_SLOPE_COUNT
#define GLINT_SLOPE_COUNT 1
#endif

struct GlintSlopeSet {
  vec2 slope[GLINT_SLOPE_COUNT];
  // Each slope's screen-space derivatives (d/dx, d/dy) as (dx.x, dx.y, dy.x, dy.y), times the
  // anti-aliasing kernel's size: the filter's input (glint_antialiasing.h). Zero: no filtering.
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

// The cells of one footprint level (method.md 2.4): cells of 2^(L-1-level) per uv unit, weighted by
// pbrt-v3's EWA Gaussian over the footprint ellipse. The ellipse is walked line by line between its
// two boundary crossings (glintCellRow), so only cells inside it are visited (no bounding-box
// waste, no cap). Lines run along the ellipse's longer extent: a footprint long in v is walked in
// columns, not rows.
// The P-SDF and the host's sampler enumerate the cells and weigh them with these functions, so
// both see the same cells and weights.
struct GlintCellGrid {
  vec2 centre;      // the footprint's centre in walk coordinates: (along a line, across lines)
  float ea;         // implicit ellipse ea x^2 + eb x y + ec y^2 < 1 around the centre, same axes
  float eb;
  float ec;
  int t0;           // first and last line
  int t1;
  bool transposed;  // walk coordinates (x, y) are cell (t, s) when set, cell (s, t) otherwise
};

GLINT_FN GlintCellGrid glintCellGrid(GlintFootprint footprint, vec2 uv, int numLevels, int level) {
  float cellsPerUv = exp2(float(numLevels - 1 - level));
  vec2 centre = uv * cellsPerUv - glintSplat2(0.5f);  // cell (s, t) is centred on integer (s, t)
  vec2 a0 = footprint.majorAxis * cellsPerUv;
  vec2 a1 = footprint.minorAxis * cellsPerUv;
  // Implicit ellipse A x^2 + B x y + C y^2 < 1, with pbrt-v3's +1 so it covers at least a cell.
  float ea = a0.y * a0.y + a1.y * a1.y + 1.0f;
  float eb = -2.0f * (a0.x * a0.y + a1.x * a1.y);
  float ec = a0.x * a0.x + a1.x * a1.x + 1.0f;
  float invF = 1.0f / (ea * ec - 0.25f * eb * eb);
  GlintCellGrid grid;
  // The ellipse's extent in t over its extent in s is sqrt(ea / ec): taller than wide, walk columns.
  grid.transposed = ea > ec;
  grid.centre = grid.transposed ? vec2(centre.y, centre.x) : centre;
  grid.ea = (grid.transposed ? ec : ea) * invF;
  grid.eb = eb * invF;
  grid.ec = (grid.transposed ? ea : ec) * invF;
  float halfHeight = sqrt(4.0f * grid.ea / (4.0f * grid.ea * grid.ec - grid.eb * grid.eb));
  grid.t0 = int(ceil(grid.centre.y - halfHeight));
  grid.t1 = int(floor(grid.centre.y + halfHeight));
  return grid;
}

// The cells (s0, s1) of line t inside the ellipse, in walk coordinates; s1 < s0 when the line
// misses it.
GLINT_FN ivec2 glintCellRow(GlintCellGrid grid, int t) {
  float dy = float(t) - grid.centre.y;
  float discriminant = grid.eb * grid.eb * dy * dy - 4.0f * grid.ea * (grid.ec * dy * dy - 1.0f);
  if (discriminant <= 0.0f) {
    return ivec2(1, 0);
  }
  float root = sqrt(discriminant);
  return ivec2(int(ceil(grid.centre.x + (-grid.eb * dy - root) / (2.0f * grid.ea))),
               int(floor(grid.centre.x + (-grid.eb * dy + root) / (2.0f * grid.ea))));
}

// The cell (s, t) at walk coordinates (x, y).
GLINT_FN ivec2 glintCellAt(GlintCellGrid grid, int x, int y) {
  return grid.transposed ? ivec2(y, x) : ivec2(x, y);
}

// The walk over a level's cells, one step at a time: the cells of line t from row.x to row.y, then
// the next line. A line that misses the ellipse (row.y < row.x) still takes one step. The P-SDF
// (glintLevelP22) and the host's sampler walk with these, and the cost bound of the `cells`
// footprint policy (glintWalkBound) bounds the steps they take.
struct GlintCellWalk {
  int s;      // the current cell along the line, in walk coordinates
  int t;      // the current line
  ivec2 row;  // the line's first and last cell
};

GLINT_FN GlintCellWalk glintWalkStart(GlintCellGrid grid) {
  GlintCellWalk walk;
  walk.t = grid.t0;
  walk.row = glintCellRow(grid, walk.t);
  walk.s = walk.row.x;
  return walk;
}

GLINT_FN bool glintWalkGoing(GlintCellGrid grid, GlintCellWalk walk) {
  return walk.t <= grid.t1;
}

GLINT_FN GlintCellWalk glintWalkStep(GlintCellGrid grid, GlintCellWalk walk) {
  GlintCellWalk next = walk;
  next.s += 1;
  if (next.s > next.row.y) {
    next.t += 1;
    next.row = glintCellRow(grid, next.t);
    next.s = next.row.x;
  }
  return next;
}

// A bound on the steps of the walk of a footprint on cells of 1 / cellsPerUv uv units, from the
// ellipse that glintCellGrid walks (its axes a0, a1 in cells, pbrt-v3's +1 on the quadratic form's
// diagonal). That form's determinant is F = (|a0|^2 + 1)(|a1|^2 + 1), its area pi sqrt(F); lines
// run along its longer extent, P = min(A, C) the smaller diagonal entry, so the walk has at most
// 2 sqrt(P) + 1 lines (its half height is sqrt(P)), the longest is 2 sqrt(F / P) cells long, and a
// line of chord c holds at most c + 1 cells. The chords are a unimodal function of the line, so
// their sum over the lines is at most the area plus the longest chord:
//   steps <= pi sqrt(F) + 2 sqrt(F / P) + (2 sqrt(P) + 1 + 2 delta)(1 + 2 delta),
// each line and each end of a line allowed delta = 0.05 cells of rounding (the walk's float
// coordinates reach 2^16 cells, where a float's spacing is 2^-7). Increasing in cellsPerUv.
GLINT_FN float glintWalkBound(GlintFootprint footprint, float cellsPerUv) {
  vec2 a0 = footprint.majorAxis * cellsPerUv;
  vec2 a1 = footprint.minorAxis * cellsPerUv;
  float determinant = (dot(a0, a0) + 1.0f) * (dot(a1, a1) + 1.0f);
  float across = min(a0.y * a0.y + a1.y * a1.y, a0.x * a0.x + a1.x * a1.x) + 1.0f;
  return GLINT_PI * sqrt(determinant) + 2.0f * sqrt(determinant / across) + (2.0f * sqrt(across) + 1.1f) * 1.1f;
}

// The EWA weight of the cell at walk coordinates (s, t) (method.md 2.4): exp(-2 r^2) - exp(-2) for
// r^2 < 1, else 0. The quadratic form is symmetric in the transposition, so the weights are the
// cells'. Each cell takes its own exp: stepping the Gaussian along a line by forward differencing
// needs two exps at the start of every line, which the single-loop walk of glintLevelP22 would pay
// on every iteration (docs/benchmarks.md, "What made it fast, and why").
GLINT_FN float glintCellWeight(GlintCellGrid grid, int s, int t) {
  float dx = float(s) - grid.centre.x;
  float dy = float(t) - grid.centre.y;
  float r2 = grid.ea * dx * dx + grid.eb * dx * dy + grid.ec * dy * dy;
  return max(exp(-2.0f * r2) - GLINT_EWA_FILTER_FLOOR, 0.0f);
}

// The EWA weight of the walk's current step: its cell's, or 0 on a line that misses the ellipse.
GLINT_FN float glintWalkWeight(GlintCellGrid grid, GlintCellWalk walk) {
  return walk.s <= walk.row.y ? glintCellWeight(grid, walk.s, walk.t) : 0.0f;
}

// P22 over the footprint at one level (method.md 2.4), at each slope of the set: the EWA-weighted
// mean of its cells' P22, in .w; .rgb weighted by the cells' colours. The scaling Jacobian and the
// Beckmann P22 of the smooth cells are the same for every cell, so they multiply the weighted sums
// once. Uncoloured cells are white, so their .rgb is .w: only coloured ones sum colours.
GLINT_FN GlintP22Set glintLevelP22(GlintDictionaryView dict, GlintParameters params, GlintFootprint footprint, vec2 uv,
                                   int level, GlintLevelDraw draw, GlintSlopeSet slopes) {
  GlintCellGrid grid = glintCellGrid(footprint, uv, dict.numLevels, level);
  vec2 unscaled[GLINT_SLOPE_COUNT];
  float dictionarySum[GLINT_SLOPE_COUNT];
  vec2 chromaSum[GLINT_SLOPE_COUNT];
  // A slope beyond every rotated support reads no dictionary cell (glintCellMarginals' per-axis
  // test agrees but for the rotation's rounding, so the slope is gated as a walk for it alone
  // would be); when all are, the cells' rotations and texel reads are skipped.
  bool inSupport[GLINT_SLOPE_COUNT];
  bool anyInSupport = false;
  // The anti-aliasing kernel of each slope: its covariance in slope space (for the smooth cells)
  // and, from its covariance in the unscaled space, the level of detail of the dictionary cells'
  // filtered lookups.
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
  // The draws of the parent or own level, for the consistent and tree constructions (glintLodCell).
  GlintLodDraws draws = glintLodDraws(dict, params, footprint.logDensity, level, draw);
  float weightSum = 0.0f;
  float smoothWeightSum = 0.0f;
  float tailWeightSum = 0.0f;
  // One loop over the cells, moving to the next line when a line is done, rather than a loop over
  // lines around a loop over a line's cells: pixels shaded in lockstep (llvmpipe's SIMD lanes, GPU
  // warps) then pay for the most cells any of them visits, not for the longest line of any of them,
  // line after line. Where branches are predicated (llvmpipe) every iteration pays for the move to
  // the next line; measured, the single loop still costs less (docs/benchmarks.md, "What made it
  // fast, and why").
  // The cells, their weights and their order are those of the nested loops, bit for bit.
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
      vec3 colourWeighted = params.colouredCells ? glintTintedP22(dictionarySum[k], chromaSum[k]) : glintSplat3(dictionarySum[k]);
      p22.p22[k] = vec4(colourWeighted, dictionarySum[k]) * glintScalingJacobian(dict, params);
      if (smoothWeightSum > 0.0f) {
        float smoothP22 = filtering ? glintFilteredTargetP22(params, slopes.slope[k], slopeKernel[k])
                                 : glintTargetP22(params.ndf, slopes.slope[k], params.alpha, params.rho);
        p22.p22[k] += glintSplat4(smoothWeightSum * smoothP22);
      }
      if (tailWeightSum > 0.0f) {
        vec3 covariance = glintBeckmannSlopeCovariance(params.alpha, params.rho) + (filtering ? slopeKernel[k] : glintSplat3(0.0f));
        p22.p22[k] += glintSplat4(tailWeightSum * glintStudentTailSlopeP22(slopes.slope[k], covariance));
      }
      p22.p22[k] = p22.p22[k] / weightSum;
#if GLINT_CONSISTENT_LOD_COMPILED
      // A complement's few texels below zero (glintBlockMarginal) never make the P-SDF negative.
      if (params.lod == GLINT_LOD_CONSISTENT) {
        p22.p22[k] = max(p22.p22[k], glintSplat4(0.0f));
      }
#endif
    }
  }
  return p22;
}

// The pattern's uv, wrapped to its period (glintFootprintPeriod).
GLINT_FN vec2 glintWrapUv(vec2 uv, int numLevels) {
  float period = glintFootprintPeriod(numLevels);
  return uv - period * floor(uv / period);
}

// The continuous LOD's two levels (method.md 2.3): floor(lod), blended with the next one by
// glintLodBlend.
GLINT_FN int glintLodLevel(GlintFootprint footprint) {
  return int(floor(footprint.lod));
}

GLINT_FN float glintLodBlend(GlintFootprint footprint) {
  return footprint.lod - float(glintLodLevel(footprint));
}

// The `cells=K` policy's level of detail: the smallest continuous level x* at which the walk is
// bounded by K (glintWalkBound(x*) <= K, by bisection; the bound falls as the level rises), and the
// footprint's LOD raised to at least x* + 1, so that both walked levels, floor(lod) and the next,
// lie above x*. x* + 1 rather than ceil(x*): the LOD must vary continuously with the footprint, or
// the P-SDF would jump where x* crosses an integer. The cells are larger and each holds
// proportionally more microfacets (glintLevelThreshold), so the microfacets seen are unchanged.
// Past the top level, the footprint is shrunk instead, and the area it loses added to the density,
// as glintFootprint's size clamp does. The bound needs K >= 12 (the host's check): the walk of any
// footprint on cells much larger than it is still bounded by 8.6.
GLINT_FN GlintFootprint glintBoundedFootprint(GlintFootprint footprint, float maxCells, int numLevels) {
  float top = float(numLevels - 1);
  float low = footprint.lod - 1.0f;  // where the walk has at least twice the exact walk's cells across
  if (glintWalkBound(footprint, exp2(top - low)) <= maxCells) {
    return footprint;  // x* <= lod - 1: the LOD stays
  }
  float high = footprint.lod + 10.0f;  // an anisotropy of 64 spans 1/16 of a cell there: bound 8.6
  for (int i = 0; i < 12; ++i) {
    float middle = 0.5f * (low + high);
    if (glintWalkBound(footprint, exp2(top - middle)) <= maxCells) {
      high = middle;
    } else {
      low = middle;
    }
  }
  float lod = max(footprint.lod, high + 1.0f);
  if (lod > top) {
    float shrink = exp2(top - lod);
    footprint.majorAxis = footprint.majorAxis * shrink;
    footprint.minorAxis = footprint.minorAxis * shrink;
    footprint.logDensity = footprint.logDensity + 1.38629436f * (lod - top);  // 2 ln 2 per level
    lod = top;
  }
  footprint.lod = lod;
  return footprint;
}

// The words of the policy that glintPixelFootprint applies, as bits: 1 aniso, 2 cells, 4 drop. The
// renderer compiles each program with GLINT_FOOTPRINT_POLICY set to the words its policy uses
// (0 for exact), so that a policy pays for its own words only and the paper's footprint for none
// (llvmpipe runs both sides of a branch); C++ and programs that leave it undefined apply all three,
// each of which does nothing when its field of params.footprintPolicy is zero.
#if defined(__cplusplus) || !defined(GLINT_FOOTPRINT_POLICY)
#define GLINT_FOOTPRINT_WORDS 7
#else
#define GLINT_FOOTPRINT_WORDS GLINT_FOOTPRINT_POLICY
#endif

// The pixel's footprint under the renderer's footprint policy (GlintFootprintPolicy;
// docs/antialiasing.md, "Footprint policies"): aniso=A clamps the anisotropy at min(A, the
// material's), cells=K raises the LOD until each walked level has at most K cells
// (glintBoundedFootprint), drop=W rounds the LOD down to its level when the next level's blend
// weight is below W, so that level alone is walked. The P-SDF and the host's sampler both take
// their footprint from here. With the zero policy it is glintFootprint's, bit for bit.
GLINT_FN GlintFootprint glintPixelFootprint(vec2 duvdx, vec2 duvdy, GlintParameters params, int numLevels) {
  GlintFootprintPolicy policy = params.footprintPolicy;
  float maxAnisotropy = params.maxAnisotropy;
#if (GLINT_FOOTPRINT_WORDS & 1) != 0
  maxAnisotropy = policy.maxAnisotropy > 0.0f ? min(params.maxAnisotropy, policy.maxAnisotropy) : maxAnisotropy;
#endif
  GlintFootprint footprint = glintFootprint(duvdx, duvdy, maxAnisotropy, glintLayerLogDensity(params), numLevels);
  if (footprint.degenerate) {
    return footprint;
  }
#if (GLINT_FOOTPRINT_WORDS & 2) != 0
  if (policy.maxCells > 0.0f) {
    footprint = glintBoundedFootprint(footprint, policy.maxCells, numLevels);
  }
#endif
#if (GLINT_FOOTPRINT_WORDS & 4) != 0
  float blend = glintLodBlend(footprint);
  if (blend > 0.0f && blend < policy.minBlend) {
    footprint.lod = floor(footprint.lod);
  }
#endif
  return footprint;
}

// The P-SDF: P22 over the pixel footprint, blended between two levels (method.md 2.3), at each
// slope of the set, in .w; .rgb weighted by the cells' colours (equal to .w unless
// params.colouredCells).
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

// The anti-aliased P-SDF at one slope whose screen derivatives (times the kernel size) are
// `derivatives` (dx.x, dx.y, dy.x, dy.y) (glint_antialiasing.h); zero derivatives give glintP22.
GLINT_FN float glintFilteredP22(GlintDictionaryView dict, GlintParameters params, vec2 uv, vec2 duvdx, vec2 duvdy,
                                vec2 slope, vec4 derivatives) {
  GlintSlopeSet slopes = glintSingleSlope(slope);
  for (int k = 0; k < GLINT_SLOPE_COUNT; ++k) {
    slopes.derivatives[k] = derivatives;
  }
  return glintP22Set(dict, params, uv, duvdx, duvdy, slopes).p22[0].w;
}

// The P-NDF at a microfacet normal m (m.z > 0): D_P(m) = P22_P(slope(m)) / m.z^4.
GLINT_FN float glintNdf(GlintDictionaryView dict, GlintParameters params, vec2 uv, vec2 duvdx, vec2 duvdy, vec3 m) {
  return glintNdfFromP22(glintP22(dict, params, uv, duvdx, duvdy, glintSlopeFromNormal(m)), m.z);
}

// The Cook-Torrance frame around a P-NDF value with the material's masking (microfacet_targets.h):
// V-cavity is the paper's, Smith takes the smooth target's Lambda.
GLINT_FN float glintMaskedReflectance(GlintParameters params, vec3 wo, vec3 wi, vec3 wh, float ndf) {
  return glintMaskedMicrofacetReflectance(params.masking, params.ndf, params.alpha, params.rho, wo, wi, wh, ndf);
}

// The glint BRDF without Fresnel and colour (F = 1), without the cosine.
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
