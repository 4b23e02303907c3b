// A Direct3D 12 or Vulkan renderer's side of the kernel's dictionary hook (src/glint/kernel/prelude.h),
// in HLSL (shader model 6 rules; DXC, or glslang's HLSL front end for SPIR-V): the dictionary's
// texels in two typed buffers and its shape in a constant buffer. Used by the HLSL entries of
// tests/kernel (kernel.hlsl, kernel_eval.hlsl, host_names.hlsl). Registers, and for SPIR-V the same
// numbers as bindings of descriptor set 0 (as tests/kernel/dictionary_vulkan.glsl):
//   t2 / binding 2: Buffer<float2>, texel (level * N + distribution) * R + k holds (p[k], p[k+1]),
//                   p[R] = 0 (a uniform texel buffer in Vulkan);
//   t3 / binding 3: Buffer<float4>, the mip chain, texel (level * N + distribution) * mipRowLength
//                   + index (docs/dictionary.md, "Mip chain");
//   b4 / binding 4: cbuffer GlintDictionaryShape: int4 (L, N, R, numMips), float alpha_d,
//                   int mipRowLength, uint caseCount (the number of cases kernel_eval.hlsl reads);
//   t6 / binding 6, in a shader that includes glint_extended_lights.h: Buffer<float4>, the
//   cumulative tables, texel (level * N + distribution) * R + k holds (C[k], M[k], p[k], p[k+1]);
//   t5 / binding 5, in a shader compiled with GLINT_ALBEDO_TABLE_HOOK 1 (kernel/multiple_scattering.h):
//                   Buffer<float> (R16_UNORM texels), GLINT_ALBEDO_WORDS' 4096 values, then
//                   GLINT_AVERAGE_ALBEDO_WORDS' 128 (each word's low half first).
#ifndef DICTIONARY_HLSL
#define DICTIONARY_HLSL

#ifndef GLINT_HLSL
#define GLINT_HLSL 1
#endif
#include "prelude.h"

[[vk::binding(2, 0)]] Buffer<float2> dictionaryPairs : register(t2);
[[vk::binding(3, 0)]] Buffer<float4> dictionaryMips : register(t3);
[[vk::binding(4, 0)]] cbuffer GlintDictionaryShape : register(b4) {
  int4 levelsDistributionsTexelsMips;  // L, N, R, numMips
  float dictionaryAlpha;               // alpha_d
  int dictionaryMipRowLength;
  uint caseCount;
};

GlintDictionaryView dictionaryView() {
  GlintDictionaryView view;
  view.numLevels = levelsDistributionsTexelsMips.x;
  view.numDistributions = levelsDistributionsTexelsMips.y;
  view.texelsPerDistribution = levelsDistributionsTexelsMips.z;
  view.numMips = levelsDistributionsTexelsMips.w;
  view.alpha = dictionaryAlpha;
  view.mipRowLength = dictionaryMipRowLength;
  return view;
}

float2 glintDictionaryTexelPair(GlintDictionaryView view, int level, int distribution, int texel) {
  return dictionaryPairs[uint((level * view.numDistributions + distribution) * view.texelsPerDistribution + texel)];
}

float4 glintDictionaryFilteredTexels(GlintDictionaryView view, int level, int distribution, int index) {
  return dictionaryMips[uint((level * view.numDistributions + distribution) * view.mipRowLength + index)];
}

#ifdef GLINT_KERNEL_GLINT_EXTENDED_LIGHTS_H
// The cumulative tables (glint_extended_lights.h), four floats a texel laid out like the pairs.
[[vk::binding(6, 0)]] Buffer<float4> dictionaryCumulative : register(t6);

float4 glintDictionaryCumulativeTexel(GlintDictionaryView view, int level, int distribution, int texel) {
  return dictionaryCumulative[uint((level * view.numDistributions + distribution) * view.texelsPerDistribution + texel)];
}
#endif

#if defined(GLINT_ALBEDO_TABLE_HOOK) && GLINT_ALBEDO_TABLE_HOOK
[[vk::binding(5, 0)]] Buffer<float> albedoTables : register(t5);

float glintAlbedoTableValue(int index) {
  return albedoTables[uint(index)];
}

float glintAverageAlbedoTableValue(int index) {
  return albedoTables[uint(4096 + index)];
}
#endif

#endif
