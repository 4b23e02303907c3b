// The pixel footprint of the 2020 glint model (Chermain et al. 2020, Alg. 1, lines 3-7, and Alg. 2;
// method.md 2.2-2.4): the footprint ellipse in uv and its continuous level of detail, the cells of a
// level under it and their EWA weights, the walk over them, and the renderer's footprint policies
// that bound it (docs/antialiasing.md, "Footprint policies").
// Shared by the CPU library and the shading languages: see prelude.h for the rules.
#ifndef GLINT_KERNEL_GLINT_FOOTPRINT_H
#define GLINT_KERNEL_GLINT_FOOTPRINT_H

#include "prelude.h"
#include "glint_parameters.h"

GLINT_KERNEL_BEGIN

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

// Footprint ellipse and continuous LOD (Alg. 1, lines 3-6 of Chermain et al. 2020; method.md
// 2.2-2.3), after pbrt-v3 MIPMap::Lookup: the pixel's footprint is the ellipse duvdx cos t + duvdy
// sin t, its minor axis is widened so that the anisotropy is at most maxAnisotropy, and the LOD is
// the (widened) minor axis in cells.
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
  // The anisotropy clamp (Alg. 1, lines 4-5): the minor axis at least majorLength / maxAnisotropy,
  // set directly (a ratio of the two lengths overflows for a thin enough ellipse). No area stays no
  // area.
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
  // Alg. 1, line 6 of Chermain et al. 2020.
  footprint.lod = footprint.degenerate ? 0.0f : max(0.0f, float(numLevels - 1) + log2(minorLength));
  return footprint;
}

// The cells of one footprint level (Alg. 2 of Chermain et al. 2020; method.md 2.4): cells of
// 2^(L-1-level) per uv unit, weighted by pbrt-v3's EWA Gaussian over the footprint ellipse. The
// ellipse is walked line by line between its two boundary crossings (glintCellRow), so only cells
// inside it are visited (no bounding-box waste, no cap). Lines run along the ellipse's longer
// extent: a footprint long in v is walked in columns, not rows.
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

// The EWA weight of the cell at walk coordinates (s, t) (Alg. 2, line 3 of Chermain et al. 2020;
// method.md 2.4): exp(-2 r^2) - exp(-2) for r^2 < 1, else 0. The quadratic form is symmetric in the
// transposition, so the weights are the cells'. Each cell takes its own exp: stepping the Gaussian
// along a line by forward differencing needs two exps at the start of every line, which the
// single-loop walk of glintLevelP22 would pay on every iteration (docs/benchmarks.md, "What made it
// fast, and why").
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

// The pattern's uv, wrapped to its period (glintFootprintPeriod).
GLINT_FN vec2 glintWrapUv(vec2 uv, int numLevels) {
  float period = glintFootprintPeriod(numLevels);
  return uv - period * floor(uv / period);
}

// The continuous LOD's two levels (Alg. 1, lines 6-7 of Chermain et al. 2020; method.md 2.3):
// floor(lod), blended with the next one by glintLodBlend.
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

GLINT_KERNEL_END

#endif
