// How the cells of neighbouring levels of detail relate (method.md 2.7, 2.8): the paper's
// construction, each cell its own draws; glint's consistent construction, a cell's four children
// share out its lobes; glint's tree construction, every cell below the own level the mean of its
// four children (the dictionary's tree levels); and a cell's marginals under each.
// Shared by the CPU library and the shading languages: see prelude.h for the rules.
#ifndef GLINT_KERNEL_GLINT_LOD_H
#define GLINT_KERNEL_GLINT_LOD_H

#include "prelude.h"
#include "dictionary_lookup.h"
#include "glint_antialiasing.h"
#include "glint_parameters.h"
#include "glint_cell.h"

GLINT_KERNEL_BEGIN

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
// without the scaling Jacobian (Alg. 3, line 19 of Chermain et al. 2020; Eq. 15 of Chermain et al.
// 2021, I3D); 0 outside the cell's rotated support.
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

GLINT_KERNEL_END

#endif
