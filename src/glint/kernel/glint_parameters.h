// The glint model's inputs (Chermain, Sauvage, Dischler & Dachsbacher 2020, "Procedural Physically
// based BRDF for Real-Time Rendering of Glints", Pacific Graphics; CGF 39(7)): the
// material's parameters (GlintParameters), the renderer's footprint policy, and which level-of-detail
// constructions a program compiles in.
// Shared by the CPU library and the shading languages: see prelude.h for the rules.
#ifndef GLINT_KERNEL_GLINT_PARAMETERS_H
#define GLINT_KERNEL_GLINT_PARAMETERS_H

#include "prelude.h"
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

GLINT_KERNEL_END

#endif
