// The pixel footprint of the 2020 glint model (Chermain et al. 2020, Alg. 1, lines 3-7, and Alg. 2;
// method.md 2.2-2.4): the ellipse in uv and its continuous LOD, a level's cells under it with their
// EWA weights and the walk over them, and the footprint policies that bound it (docs/antialiasing.md,
// "Footprint policies").
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
// 2.2-2.3), after pbrt-v3 MIPMap::Lookup: the ellipse duvdx cos t + duvdy sin t, its minor axis
// widened to an anisotropy of at most maxAnisotropy, the LOD the minor axis in cells. Past the paper
// and pbrt-v3 (docs/conventions.md, "Where glint goes past the reference implementation"):
//   - the ellipse's principal axes, from the SVD of J = [duvdx duvdy]: the derivatives are conjugate
//     semi-diameters, and pbrt-v3's shorter one, up to about anisotropy / sqrt 2 times the minor axis,
//     picks cells that many times too long (streaks at a UV sphere's pole: docs/renderer.md,
//     "Footprint");
//   - a minor axis over one uv unit is shrunk to one and the lost area added to the density: the LOD
//     stays in the dictionary and the cost bounded, the microfacets seen unchanged.
GLINT_FN GlintFootprint glintFootprint(vec2 duvdx, vec2 duvdy, float maxAnisotropy, float logDensity,
                                       int numLevels) {
  // Derivatives beyond 1e6 uv units (the period is 2) are scaled down together so that their squares
  // stay finite (such a footprint is in the smooth limit anyway); below, the scale is exactly 1.
  float longest = max(max(abs(duvdx.x), abs(duvdx.y)), max(abs(duvdy.x), abs(duvdy.y)));
  float fit = longest > 1e6f ? 1e6f / longest : 1.0f;
  vec2 dx = duvdx * fit;
  vec2 dy = duvdy * fit;
  // J J^T = [[a, b], [b, c]], eigenvalues the squared semi-axes. The larger, (a + c) / 2 +
  // sqrt(((a - c) / 2)^2 + b^2), sums non-negative terms; the smaller is taken as det(J)^2 over it,
  // which does not cancel for a thin ellipse.
  float a = dx.x * dx.x + dy.x * dy.x;
  float b = dx.x * dx.y + dy.x * dy.y;
  float c = dx.y * dx.y + dy.y * dy.y;
  float halfDifference = 0.5f * (a - c);
  float root = sqrt(halfDifference * halfDifference + b * b);
  float majorLength = sqrt(0.5f * (a + c) + root);
  float minorLength = majorLength > 0.0f ? abs(dx.x * dy.y - dx.y * dy.x) / majorLength : 0.0f;
  // The major axis: the larger eigenvalue's eigenvector, (lambda - c, b) or (b, lambda - a), whichever
  // sums non-negative terms (lambda - c = halfDifference + root). A circle's is u.
  vec2 direction = halfDifference >= 0.0f ? vec2(halfDifference + root, b) : vec2(b, root - halfDifference);
  float directionLength = length(direction);
  direction = directionLength > 0.0f ? direction / directionLength : vec2(1.0f, 0.0f);
  // The anisotropy clamp (Alg. 1, lines 4-5), set directly (a ratio of the lengths overflows for a thin
  // enough ellipse). No area stays no area.
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

// The cells of one footprint level (Alg. 2 of Chermain et al. 2020; method.md 2.4): 2^(L-1-level)
// per uv unit, weighted by pbrt-v3's EWA Gaussian. The ellipse is walked line by line between its
// boundary crossings (glintCellRow): only cells inside it, no bounding-box waste, no cap. Lines run
// along its longer extent (a footprint long in v is walked in columns). The P-SDF and the host's
// sampler both use these functions, so both see the same cells and weights.
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
  // A x^2 + B x y + C y^2 < 1, with pbrt-v3's +1 so that it covers at least a cell.
  float ea = a0.y * a0.y + a1.y * a1.y + 1.0f;
  float eb = -2.0f * (a0.x * a0.y + a1.x * a1.y);
  float ec = a0.x * a0.x + a1.x * a1.x + 1.0f;
  float invF = 1.0f / (ea * ec - 0.25f * eb * eb);
  GlintCellGrid grid;
  // Extent in t over extent in s is sqrt(ea / ec): taller than wide, walk columns.
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

// The walk over a level's cells, one step at a time: line t from row.x to row.y, then the next line;
// a line that misses the ellipse (row.y < row.x) still takes a step. The P-SDF (glintLevelP22) and
// the host's sampler walk with these; glintWalkBound bounds the steps.
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

// A bound on the walk's steps on cells of 1 / cellsPerUv uv units (axes a0, a1 in cells, pbrt-v3's +1
// on the quadratic form's diagonal). The form's determinant is F = (|a0|^2 + 1)(|a1|^2 + 1), its
// area pi sqrt(F); with P = min(A, C), the walk has at most 2 sqrt(P) + 1 lines, the longest
// 2 sqrt(F / P) cells, and a chord c holds at most c + 1 cells. The chords are unimodal in the line,
// so their sum is at most the area plus the longest:
//   steps <= pi sqrt(F) + 2 sqrt(F / P) + (2 sqrt(P) + 1 + 2 delta)(1 + 2 delta),
// with delta = 0.05 cells of rounding per line end (float coordinates reach 2^16 cells, spacing
// 2^-7). Increasing in cellsPerUv.
GLINT_FN float glintWalkBound(GlintFootprint footprint, float cellsPerUv) {
  vec2 a0 = footprint.majorAxis * cellsPerUv;
  vec2 a1 = footprint.minorAxis * cellsPerUv;
  float determinant = (dot(a0, a0) + 1.0f) * (dot(a1, a1) + 1.0f);
  float across = min(a0.y * a0.y + a1.y * a1.y, a0.x * a0.x + a1.x * a1.x) + 1.0f;
  return GLINT_PI * sqrt(determinant) + 2.0f * sqrt(determinant / across) + (2.0f * sqrt(across) + 1.1f) * 1.1f;
}

// The EWA weight of the cell at walk coordinates (s, t) (Alg. 2, line 3 of Chermain et al. 2020;
// method.md 2.4): exp(-2 r^2) - exp(-2) for r^2 < 1, else 0 (the form is symmetric in the
// transposition). Each cell takes its own exp: forward differencing along a line needs two exps per
// line start, which the single-loop walk would pay every iteration (docs/benchmarks.md, "What made it
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

// The continuous LOD's two levels (Alg. 1, lines 6-7 of Chermain et al. 2020; method.md 2.3).
GLINT_FN int glintLodLevel(GlintFootprint footprint) {
  return int(floor(footprint.lod));
}

GLINT_FN float glintLodBlend(GlintFootprint footprint) {
  return footprint.lod - float(glintLodLevel(footprint));
}

// The `cells=K` policy: the smallest continuous level x* with glintWalkBound(x*) <= K (bisection; the
// bound falls as the level rises), the LOD raised to at least x* + 1 so both walked levels lie above
// x*; not ceil(x*), as the LOD must vary continuously or the P-SDF would jump. Larger cells hold
// proportionally more microfacets (glintLevelThreshold): the microfacets seen are unchanged. Past the
// top level the footprint is shrunk and the lost area added to the density, as in glintFootprint.
// Needs K >= 12 (the host checks): any footprint's walk on cells much larger than it is bounded by 8.6.
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

// The policy words glintPixelFootprint applies, as bits: 1 aniso, 2 cells, 4 drop. The renderer sets
// GLINT_FOOTPRINT_POLICY to its policy's words (0 for exact), so a policy pays only for its own and
// the paper's footprint for none (llvmpipe runs both sides of a branch); C++ and programs without it
// apply all three, each a no-op where its field of params.footprintPolicy is zero.
#if defined(__cplusplus) || !defined(GLINT_FOOTPRINT_POLICY)
#define GLINT_FOOTPRINT_WORDS 7
#else
#define GLINT_FOOTPRINT_WORDS GLINT_FOOTPRINT_POLICY
#endif

// The pixel's footprint under the footprint policy (GlintFootprintPolicy; docs/antialiasing.md,
// "Footprint policies"): aniso=A clamps the anisotropy at min(A, the material's), cells=K raises the
// LOD until each walked level has at most K cells, drop=W walks floor(lod) alone when the next level's
// blend is below W. The P-SDF and the host's sampler both take it; the zero policy is glintFootprint's,
// bit for bit.
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
