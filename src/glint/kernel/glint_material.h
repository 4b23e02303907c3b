// A material's glint layer as every renderer stores it (the rasteriser's uniform buffer, the page's,
// the path tracer's), and the one mapping from it and its textures' samples to the model's
// parameters, so that the rasteriser, the page and the path tracer apply the layer's textures by
// the same rules (docs/scenes.md, "Glint parameters in glTF extras"; docs/renderer.md, "The material block").
// Shared by the CPU library and the GLSL renderer: see prelude.h for the rules.
#ifndef GLINT_KERNEL_GLINT_MATERIAL_H
#define GLINT_KERNEL_GLINT_MATERIAL_H

#include "prelude.h"
#include "glint_brdf.h"

GLINT_KERNEL_BEGIN

// Every per-material input of the glint layer. The layout is the same in C++, in GLSL's std140
// (a uniform block holding one GlintMaterial) and std430, and in an HLSL constant buffer: 4-byte
// scalars, each vec2 on an 8-byte boundary within its 16 bytes (none straddles a 16-byte
// boundary), flags as uint (0 or 1: a GLSL bool is 4 bytes in a block, a C++ bool one), 80 bytes
// in all, a multiple of 16 (std140 rounds a struct up to one):
//   offset  0  vec2  alpha                  16  float relativeArea
//           8  float rho                    20  float densityRandomisation
//          12  float logDensity             24  float maxAnisotropy
//                                           28  uint  patternSeed
//          32  vec2  logDensityRange        48  int   ndf
//          40  float uvScale                52  int   masking
//          44  uint  hasLogDensityTexture   56  uint  colouredCells
//                                           60  uint  multipleScattering
//          64  uint  enabled                68  int   lod
//                                           72, 76  padding (zero)
// static_asserts below pin these offsets in C++; tests/test_gl_kernel.cpp checks that the GLSL
// compiler reports the same ones for the renderer's block (shaders/glint_material_block.glsl).
struct GlintMaterial {
  vec2 alpha;                  // roughness alpha_x, alpha_y (the roughness texture's R multiplies them)
  float rho;                   // slope correlation
  float logDensity;            // D, unless hasLogDensityTexture
  float relativeArea;          // MRA (the relative-area texture's R multiplies it)
  float densityRandomisation;  // zeta
  float maxAnisotropy;
  uint patternSeed;
  vec2 logDensityRange;        // D = mix(x, y, the log-density texture's R) when hasLogDensityTexture
  float uvScale;               // glint uv = mesh uv * uvScale (glintMaterialUv)
  uint hasLogDensityTexture;   // 1: D comes from the log-density texture
  int ndf;                     // GLINT_NDF_BECKMANN or GLINT_NDF_GGX (microfacet_targets.h)
  int masking;                 // GLINT_MASKING_VCAVITY or GLINT_MASKING_SMITH
  uint colouredCells;          // 1: each cell reflects a random colour
  uint multipleScattering;     // 1: the smooth target's compensation lobe is added
  uint enabled;                // 1: the material has a glint layer (0: Cook-Torrance of its own roughness)
  int lod;                     // GLINT_LOD_PAPER, GLINT_LOD_CONSISTENT or GLINT_LOD_TREE (glint_parameters.h)
  uint padding1;
  uint padding2;
};

#ifdef __cplusplus
// The layout of kernel/glint_material.h, which the renderers' buffers and shaders rely on.
static_assert(sizeof(GlintMaterial) == 80, "GlintMaterial: 80 bytes, five 16-byte rows");
static_assert(offsetof(GlintMaterial, alpha) == 0);
static_assert(offsetof(GlintMaterial, rho) == 8);
static_assert(offsetof(GlintMaterial, logDensity) == 12);
static_assert(offsetof(GlintMaterial, relativeArea) == 16);
static_assert(offsetof(GlintMaterial, densityRandomisation) == 20);
static_assert(offsetof(GlintMaterial, maxAnisotropy) == 24);
static_assert(offsetof(GlintMaterial, patternSeed) == 28);
static_assert(offsetof(GlintMaterial, logDensityRange) == 32);
static_assert(offsetof(GlintMaterial, uvScale) == 40);
static_assert(offsetof(GlintMaterial, hasLogDensityTexture) == 44);
static_assert(offsetof(GlintMaterial, ndf) == 48);
static_assert(offsetof(GlintMaterial, masking) == 52);
static_assert(offsetof(GlintMaterial, colouredCells) == 56);
static_assert(offsetof(GlintMaterial, multipleScattering) == 60);
static_assert(offsetof(GlintMaterial, enabled) == 64);
static_assert(offsetof(GlintMaterial, lod) == 68);
static_assert(offsetof(GlintMaterial, padding1) == 72);
#endif

// The glint uv of a mesh uv, or of its derivatives (the map is linear): the layer's density is per
// glint-uv area.
GLINT_FN vec2 glintMaterialUv(GlintMaterial material, vec2 uv) {
  return uv * material.uvScale;
}

// The material's parameters before its textures: its constants, as the host validates them.
GLINT_FN GlintParameters glintMaterialConstants(GlintMaterial material, GlintFootprintPolicy policy) {
  GlintParameters p;
  p.alpha = material.alpha;
  p.rho = material.rho;
  p.logDensity = material.logDensity;
  p.relativeArea = material.relativeArea;
  p.densityRandomisation = material.densityRandomisation;
  p.maxAnisotropy = material.maxAnisotropy;
  p.patternSeed = material.patternSeed;
  p.colouredCells = material.colouredCells != 0u;
  p.ndf = material.ndf;
  p.masking = material.masking;
  p.lod = material.lod;
  p.multipleScattering = material.multipleScattering != 0u;
  p.footprintPolicy = policy;
  return p;
}

// The parameters at a shading point, from the R channels of the layer's three textures there
// (1 where a texture is absent): the roughness texture multiplies alpha, clamped to the model's
// [0.01, 2]; the log-density texture maps linearly onto logDensityRange and replaces logDensity;
// the relative-area texture multiplies relativeArea, clamped to [1e-4, 1] (a cell must be able to
// have microfacets). The footprint policy is the renderer's, not the material's.
GLINT_FN GlintParameters glintMaterialParameters(GlintMaterial material, float roughnessSample, float logDensitySample,
                                                 float relativeAreaSample, GlintFootprintPolicy policy) {
  GlintParameters p = glintMaterialConstants(material, policy);
  p.alpha = clamp(material.alpha * roughnessSample, 0.01f, 2.0f);
  p.logDensity = material.hasLogDensityTexture != 0u
                     ? glintMix(material.logDensityRange.x, material.logDensityRange.y, logDensitySample)
                     : material.logDensity;
  p.relativeArea = clamp(material.relativeArea * relativeAreaSample, 1e-4f, 1.0f);
  return p;
}

GLINT_KERNEL_END

#endif
