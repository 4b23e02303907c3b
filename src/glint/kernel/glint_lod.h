// How the cells of neighbouring levels of detail relate (method.md 2.7, 2.8): the paper's
// construction, each cell its own draws; the consistent one, a cell's four children share out its
// lobes; the tree one, every cell below the own level the mean of its four children (the
// dictionary's tree levels); and a cell's marginals under each.
#ifndef GLINT_KERNEL_GLINT_LOD_H
#define GLINT_KERNEL_GLINT_LOD_H

#include "prelude.h"
#include "dictionary_lookup.h"
#include "glint_antialiasing.h"
#include "glint_parameters.h"
#include "glint_cell.h"

GLINT_KERNEL_BEGIN

// Consistent LOD (method.md 2.7): whether the cell (cellX, cellY) of `level` is a block of its
// parent's lobes instead of drawing its own. Level l + 1 is level l's lobes plus as many new ones, so
// an own cell's tensor product (both marginals whole levels) is four level-l blocks for its children
// (prefix or complement per axis), the first child (the coherent index's) taking prefix x prefix.
// Only prefixes are tabulated, so a complement block cannot split again. So a cell is a block when it
// is not its parent's first child and its parent is own (the top level's cells are own); 4/7 of the
// cells deep in the tree are own. Bit j of the coherent index says whether the level-j ancestor is a
// first child (0) or not.
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

// Tree LOD (method.md 2.8; docs/dictionary.md, "Tree levels"): tree level 0 is dictionary level 0;
// tree level k >= 1 of distribution i, table level L - 1 + k, is the mean of tree level k - 1 of i
// and of glintTreePartner(k, i), built by the host (glint::Dictionary), so it holds level 0's lobes
// of distributions i, ..., i + 2^k - 1 (mod N).
GLINT_FN int glintTreeTableLevel(GlintDictionaryView dict, int treeLevel) {
  return treeLevel == 0 ? 0 : dict.numLevels - 1 + treeLevel;
}

// The partner of distribution i at tree level k >= 1: i + 2^(k - 1) (mod N). Each level's pairing is a
// permutation, so every tree level's mean marginal is level 0's, whose lobes stratify the target
// (random partners would weigh some lobes thrice and drop others, and the means would drift). Where N
// divides 2^(k - 1) the partner is i itself. In float, as llvmpipe divides integers one lane at a
// time: every value is an integer below 2^24, exact, and the correction undoes the quotient's rounding.
GLINT_FN int glintTreePartner(GlintDictionaryView dict, int treeLevel, int distribution) {
  float n = float(dict.numDistributions);
  float shift = exp2(float(treeLevel - 1));
  shift -= n * floor(shift / n);
  shift += shift < 0.0f ? n : (shift >= n ? -n : 0.0f);
  float partner = float(distribution) + shift;
  return int(partner >= n ? partner - n : partner);
}

// The tree's own level: where a cell's expected dictionary level, round(log4(n)) with
// n = e^D 4^(level - (L - 1)) (glintLevelThreshold), is floor(log2 N) - 1, so an own cell's marginals
// (2^k of level 0's N lobes) rarely repeat a lobe and a subtree sharing its rotation holds about
// N^2 / 4 microfacets.
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
    // The own level's thresholds, one glintNormalCdf a level instead of L (glintNextLevelDraw is
    // glintLevelDraw of the next level, bit for bit).
    for (int k = level; k < draws.relatedLevel; ++k) {
      draws.related = glintNextLevelDraw(dict, params, logDensity, k, draws.related);
    }
  }
#endif
  return draws;
}

// Tree LOD: a cell at or above the own level (method.md 2.8) always holds microfacets, at the density
// e^D MRA (glintLayerLogDensity, with `ownDraw`), covering the relative area of it. Drawn per cell
// here, the relative area would leave whole subtrees dark (1/4: snow sparkling in squares); carried
// down as coverage and drawn only below a single lobe (glintTreeBlockCell), every cell stays the mean
// of its children.
GLINT_FN GlintCell glintTreeOwnCell(GlintDictionaryView dict, GlintParameters params, GlintLevelDraw ownDraw, int cellX,
                                    int cellY, int ownLevel) {
  GlintParameters covered = params;
  covered.relativeArea = 1.0f;
  GlintCell cell = glintCell(dict, covered, ownDraw, cellX, cellY, ownLevel);
  cell.coverage = params.relativeArea;
  return cell;
}

// Tree LOD: the cell (cellX, cellY) of `level`, below the own level, a block of its ancestor at the
// own level: its draws (microfacets, rotation, GGX scale, colour) with, at each step down, one tree
// level less and on each axis the distribution or its partner as the child's position says, so every
// cell is the mean of its children. Which child takes which block is one of the 2 x 2 square's eight
// symmetries, hashed from the parent (by position alone glints would line up in rows and columns).
// Below tree level 0 the children keep the parent's lobe and share its coverage f, 4 f of cell area,
// the child of rank r (hashed order) taking min(1, 4 f - r): the mean stays exact. A smooth or
// GGX-tail own cell gives its whole subtree its own P22 and coverage.
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
        // The parent at this step by its coherent index (so the symmetry repeats with the pattern's
        // period), one collision-free 32-bit word (glintCellHash), hashed with a mask of the pattern seed
        // and its level (a parent and its first child share the index).
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
          // The child's rank: its index through an xor and a rotation hashed from the parent, a permutation
          // that puts the lit ones side by side or across the diagonal.
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

// The cell (cellX, cellY) of `level` under the material's LOD construction (method.md 2.7, 2.8).
// Consistent: a block takes its parent's draws one dictionary level lower, with the complement on
// each axis where its position is odd (the children's mean P22 is the parent's to float rounding);
// an empty or GGX-tail parent passes on its own P22; one at dictionary level 0 or smooth has no
// blocks. Tree: below the own level a block (glintTreeBlockCell); at it, with blocks below, an own
// cell reading the tree levels; above, or at level 0, a paper's cell reading the dictionary's levels
// (the tree's at most N distinct lobes would ripple a dense layer's P-SDF about the target).
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

// One axis's marginal at |slope| (< 4 sigma_d): dictionary level `level`, or with `complement` the
// lobes level + 1 adds, 2 p_{level+1} - p_level (method.md 2.7), which integrates to 1 too. Being two
// binary16 tables normalised apart, it can dip below zero where level + 1 adds no lobe, by at most
// 4e-4 of the level's peak in the default dictionary.
GLINT_FN float glintBlockMarginal(GlintDictionaryView dict, int level, int distribution, int complement, float absSlope) {
  float prefix = glintMarginal(dict, level, distribution, absSlope);
#if GLINT_CONSISTENT_LOD_COMPILED
  if (complement != 0) {
    return 2.0f * glintMarginal(dict, level + 1, distribution, absSlope) - prefix;
  }
#endif
  return prefix;
}

// The same, filtered: the filter is linear, so the complement's is the difference of the tables'.
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

// The product of a cell's two marginals at an unscaled slope, without the scaling Jacobian (Alg. 3,
// line 19 of Chermain et al. 2020; Eq. 15 of Chermain et al. 2021, I3D); 0 outside the rotated
// support.
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

// The same, both marginals filtered (glint_antialiasing.h) at the kernel's level of detail.
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

GLINT_KERNEL_END

#endif
