// A Vulkan renderer's side of the kernel's dictionary hook (src/glint/kernel/prelude.h), in GLSL
// 4.50 for SPIR-V: the dictionary's texels in two uniform texel buffers and its shape in a uniform
// block, no plain uniform. Used by the Vulkan entries of tests/kernel (kernel_vulkan.comp,
// kernel_eval_vulkan.comp, host_names_vulkan.comp). Descriptor set 0:
//   binding 2: uniform texel buffer, two channels a texel (R16G16_SFLOAT or R32G32_SFLOAT): texel
//              (level * N + distribution) * R + k holds (p[k], p[k+1]), p[R] = 0;
//   binding 3: uniform texel buffer, four channels a texel: the mip chain, texel
//              (level * N + distribution) * mipRowLength + index (docs/dictionary.md, "Mip chain");
//   binding 4: uniform buffer GlintDictionaryShape (std140): ivec4 (L, N, R, numMips), float alpha_d,
//              int mipRowLength, uint caseCount (the number of cases kernel_eval_vulkan.comp reads);
//   binding 5, in a shader compiled with GLINT_ALBEDO_TABLE_HOOK 1 (kernel/multiple_scattering.h):
//              uniform texel buffer, one channel (R16_UNORM): GLINT_ALBEDO_WORDS' 4096 values, then
//              GLINT_AVERAGE_ALBEDO_WORDS' 128 (each word's low half first).
//   binding 6, in a shader that includes glint_extended_lights.h: uniform texel buffer, four
//   channels a texel (R32G32B32A32_SFLOAT): the cumulative tables, texel (level * N + distribution) * R
//   + k holds (C[k], M[k], p[k], p[k+1]) (glint::Dictionary::cumulativeTexels).
// The same bindings as tests/kernel/dictionary.hlsl.
#ifndef DICTIONARY_VULKAN_GLSL
#define DICTIONARY_VULKAN_GLSL

#include "prelude.h"

layout(set = 0, binding = 2) uniform samplerBuffer dictionaryPairs;
layout(set = 0, binding = 3) uniform samplerBuffer dictionaryMips;
layout(set = 0, binding = 4, std140) uniform GlintDictionaryShape {
  ivec4 levelsDistributionsTexelsMips;  // L, N, R, numMips
  float alpha;                          // alpha_d
  int mipRowLength;
  uint caseCount;
} dictionaryShape;

GlintDictionaryView dictionaryView() {
  GlintDictionaryView view;
  view.numLevels = dictionaryShape.levelsDistributionsTexelsMips.x;
  view.numDistributions = dictionaryShape.levelsDistributionsTexelsMips.y;
  view.texelsPerDistribution = dictionaryShape.levelsDistributionsTexelsMips.z;
  view.numMips = dictionaryShape.levelsDistributionsTexelsMips.w;
  view.alpha = dictionaryShape.alpha;
  view.mipRowLength = dictionaryShape.mipRowLength;
  return view;
}

vec2 glintDictionaryTexelPair(GlintDictionaryView view, int level, int distribution, int texel) {
  return texelFetch(dictionaryPairs, (level * view.numDistributions + distribution) * view.texelsPerDistribution + texel).xy;
}

vec4 glintDictionaryFilteredTexels(GlintDictionaryView view, int level, int distribution, int index) {
  return texelFetch(dictionaryMips, (level * view.numDistributions + distribution) * view.mipRowLength + index);
}

#ifdef GLINT_KERNEL_GLINT_EXTENDED_LIGHTS_H
// The cumulative tables (glint_extended_lights.h), four floats a texel laid out like the pairs.
layout(set = 0, binding = 6) uniform samplerBuffer dictionaryCumulative;

vec4 glintDictionaryCumulativeTexel(GlintDictionaryView view, int level, int distribution, int texel) {
  return texelFetch(dictionaryCumulative, (level * view.numDistributions + distribution) * view.texelsPerDistribution + texel);
}
#endif

#if defined(GLINT_ALBEDO_TABLE_HOOK) && GLINT_ALBEDO_TABLE_HOOK
layout(set = 0, binding = 5) uniform samplerBuffer albedoTables;

float glintAlbedoTableValue(int index) {
  return texelFetch(albedoTables, index).x;
}

float glintAverageAlbedoTableValue(int index) {
  return texelFetch(albedoTables, 4096 + index).x;
}
#endif

#endif
