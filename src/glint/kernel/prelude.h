// The kernel's language bridge: every file under kernel/ compiles from one text as C++20 (with glm)
// and as four shading languages (docs/conventions.md, "One model, five languages"):
//   - C++ (__cplusplus): namespace glint::kernel, over glm;
//   - GLSL 4.50 for OpenGL and for Vulkan (SPIR-V through glslang): the default;
//   - GLSL ES 3.00 (WebGL2): the compiler's own GL_ES;
//   - HLSL, shader model 6 rules: GLINT_HLSL, defined by the host before including the kernel, or
//     DXC's predefined __HLSL_VERSION (glslang's HLSL front end predefines no such macro).
//
// The kernel declares no resource and prefixes every name (glintXxx, GlintXxx, GLINT_XXX). It reads
// the dictionary through a hook, functions the host defines after including it (prototypes below;
// docs/integration.md, "The dictionary hook"):
//   glintDictionaryTexelPair: texels k and k + 1 of a marginal, the second 0 past its last texel
//     (docs/dictionary.md, "Texel convention");
//   glintDictionaryFilteredTexels: texel glintMipOffset(R, m) + k of a distribution's mip-chain row,
//     (p_m[k], p_m[k+1], q_m[k], q_m[k+1]) (docs/dictionary.md, "Mip chain"); read only with
//     GLINT_FILTERED 1, so a host without the chain may return (glintDictionaryTexelPair(...), 0, 0);
//   glintDictionaryCumulativeTexel, for glint_extended_lights.h only: (C[k], M[k], p[k], p[k+1]), the
//     marginal's and slope-weighted marginal's integrals from 0 to texel k and its pair, as 32-bit
//     floats (glint::Dictionary::cumulativeTexels(); docs/dictionary.md, "Cumulative tables").
// A shader that includes a header that reads the dictionary (dictionary_lookup.h and those including
// it) defines the first two even if it calls none: Mesa's GLSL linker resolves every function's calls.
// GlintDictionaryView is the host's dictionary: in shaders its shape, filled by the host; in C++
// pointers to host memory, with the hook defined here. Example hosts: shaders/glint_dictionary_gl.glsl,
// tests/kernel/dictionary_vulkan.glsl, dictionary.hlsl. A GLSL ES host declares highp float and int
// (the hashing needs 32-bit integers).
//
// Rules, so that one text is valid in every language (docs/conventions.md, "Kernel rules"): every
// input an argument (no uniforms, derivatives or globals); hashing on uint; literals with the f and u
// suffixes; no swizzle assignment, struct constructors or recursion; GLINT_FN, GLINT_CONST,
// GLINT_OUT(T), GLINT_INOUT(T); GLSL's built-ins, or the helpers below where HLSL spells one
// differently; glintSplat2/3/4 for vec3(x), GLINT_MUL for mul; no mod (GLSL's floors, HLSL's fmod
// truncates: x - y * floor(x / y)); no two-argument atan.
#ifndef GLINT_KERNEL_PRELUDE_H
#define GLINT_KERNEL_PRELUDE_H

#if defined(__cplusplus)

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>

#define GLINT_KERNEL_BEGIN \
  namespace glint::kernel {  \
  using namespace glm;       \
  using uint = std::uint32_t;
#define GLINT_KERNEL_END }
#define GLINT_FN inline
#define GLINT_CONST inline constexpr
#define GLINT_OUT(T) T&
#define GLINT_INOUT(T) T&
#define GLINT_MUL(m, v) ((m) * (v))

#elif defined(GLINT_HLSL) || defined(__HLSL_VERSION)

#ifndef GLINT_HLSL
#define GLINT_HLSL 1
#endif
#define GLINT_KERNEL_BEGIN
#define GLINT_KERNEL_END
#define GLINT_FN
#define GLINT_CONST static const
#define GLINT_OUT(T) out T
#define GLINT_INOUT(T) inout T
#define GLINT_MUL(m, v) mul(m, v)
// GLSL's vector names as HLSL's (unless the host already maps them).
#ifndef vec2
#define vec2 float2
#endif
#ifndef vec3
#define vec3 float3
#endif
#ifndef vec4
#define vec4 float4
#endif
#ifndef ivec2
#define ivec2 int2
#endif
#ifndef ivec3
#define ivec3 int3
#endif
#ifndef ivec4
#define ivec4 int4
#endif
#ifndef uvec2
#define uvec2 uint2
#endif
#ifndef uvec3
#define uvec3 uint3
#endif
#ifndef uvec4
#define uvec4 uint4
#endif

#else  // GLSL: 4.50 (OpenGL, Vulkan) or ES 3.00

#define GLINT_KERNEL_BEGIN
#define GLINT_KERNEL_END
#define GLINT_FN
#define GLINT_CONST const
#define GLINT_OUT(T) out T
#define GLINT_INOUT(T) inout T
#define GLINT_MUL(m, v) ((m) * (v))

#endif

// Compile-time configuration a host may define before including the kernel:
//   GLINT_FILTERED 1: the P-SDF's walk filters (glint_antialiasing.h; C++ decides per call);
//   GLINT_MULTIPLE_SCATTERING 1: the albedo tables and compensation lobe (multiple_scattering.h);
//   GLINT_ALBEDO_TABLES 1: the albedo tables alone (the clear coat's lobe, clearcoat.h);
//   GLINT_SLOPE_COUNT: slopes a walk (glint_brdf.h, 1 by default);
//   GLINT_FOOTPRINT_POLICY: the footprint policy's words the walk applies (glint_footprint.h, all).
#ifndef GLINT_FILTERED
#define GLINT_FILTERED 0
#endif
#ifndef GLINT_MULTIPLE_SCATTERING
#define GLINT_MULTIPLE_SCATTERING 0
#endif
#ifndef GLINT_ALBEDO_TABLES
#define GLINT_ALBEDO_TABLES 0
#endif

GLINT_KERNEL_BEGIN

// ---- Built-ins that the languages spell differently -------------------------------------------

GLINT_FN vec2 glintSplat2(float x) {
  return vec2(x, x);
}

GLINT_FN vec3 glintSplat3(float x) {
  return vec3(x, x, x);
}

GLINT_FN vec4 glintSplat4(float x) {
  return vec4(x, x, x, x);
}

#if defined(GLINT_HLSL)
GLINT_FN float glintMix(float a, float b, float t) {
  return lerp(a, b, t);
}
GLINT_FN vec3 glintMix(vec3 a, vec3 b, float t) {
  return lerp(a, b, t);
}
GLINT_FN float glintFract(float x) {
  return frac(x);
}
GLINT_FN float glintInverseSqrt(float x) {
  return rsqrt(x);
}
GLINT_FN int glintFloatBitsToInt(float x) {
  return asint(x);
}
GLINT_FN int glintFindLSB(uint v) {
  return int(firstbitlow(v));  // 0xFFFFFFFF, -1, for 0 as in GLSL
}
// x 2^e, exactly, for e in [-126, 127] (HLSL's ldexp is x * exp2(e), in floats).
GLINT_FN float glintLdexp(float x, int e) {
  return x * asfloat(uint(e + 127) << 23u);
}
#else
GLINT_FN float glintMix(float a, float b, float t) {
  return mix(a, b, t);
}
GLINT_FN vec3 glintMix(vec3 a, vec3 b, float t) {
  return mix(a, b, t);
}
GLINT_FN float glintFract(float x) {
  return fract(x);
}
GLINT_FN float glintInverseSqrt(float x) {
  return inversesqrt(x);
}
GLINT_FN int glintFloatBitsToInt(float x) {
  return floatBitsToInt(x);
}
#if defined(GL_ES)
// GLSL ES 3.00 lacks findLSB and ldexp: exact, through the float's bits (no exp2 or log2 rounding).
GLINT_FN int glintFindLSB(uint v) {
  return v == 0u ? -1 : (floatBitsToInt(float(v & (0u - v))) >> 23) - 127;
}
// x 2^e, exactly, for e in [-126, 127].
GLINT_FN float glintLdexp(float x, int e) {
  return x * intBitsToFloat((e + 127) << 23);
}
#else
GLINT_FN int glintFindLSB(uint v) {
  return findLSB(v);
}
GLINT_FN float glintLdexp(float x, int e) {
  return ldexp(x, e);
}
#endif
#endif

// ---- The dictionary hook ----------------------------------------------------------------------

#if defined(__cplusplus)

// Read-only view of a dictionary in host memory: texels[(level * numDistributions + distribution)
// * texelsPerDistribution + texel], each a float that is exactly representable as binary16, so the
// CPU reads the very values the GPU's R16F texture holds.
struct GlintDictionaryView {
  const float* texels;
  int numLevels;
  int numDistributions;
  int texelsPerDistribution;
  float alpha;  // alpha_d, the dictionary's roughness
  // The mip chain (docs/dictionary.md, "Mip chain"): numMips levels of each distribution, level m
  // of R / 2^m texels, one after the other in a row of mipRowLength texels per distribution; each
  // texel four floats, (p_m[k], p_m[k+1], q_m[k], q_m[k+1]), binary16 values, q_m the next level
  // interpolated at level m's texel positions.
  const float* filteredTexels;
  int numMips;
  int mipRowLength;
  // The cumulative tables (glintDictionaryCumulativeTexel), four floats a texel; null where the host has
  // none (then nothing may call glint_extended_lights.h).
  const float* cumulativeTexels;
};

// A single texel, for the host's own code (the kernel reads pairs).
GLINT_FN float glintDictionaryTexel(GlintDictionaryView dict, int level, int distribution, int texel) {
  return dict.texels[(level * dict.numDistributions + distribution) * dict.texelsPerDistribution + texel];
}

GLINT_FN vec2 glintDictionaryTexelPair(GlintDictionaryView dict, int level, int distribution, int texel) {
  const float* row = dict.texels + (level * dict.numDistributions + distribution) * dict.texelsPerDistribution;
  return vec2(row[texel], texel + 1 < dict.texelsPerDistribution ? row[texel + 1] : 0.0f);
}

GLINT_FN vec4 glintDictionaryFilteredTexels(GlintDictionaryView dict, int level, int distribution, int index) {
  const float* t = dict.filteredTexels + 4 * ((level * dict.numDistributions + distribution) * dict.mipRowLength + index);
  return vec4(t[0], t[1], t[2], t[3]);
}

GLINT_FN vec4 glintDictionaryCumulativeTexel(GlintDictionaryView dict, int level, int distribution, int texel) {
  const float* t = dict.cumulativeTexels + 4 * ((level * dict.numDistributions + distribution) * dict.texelsPerDistribution + texel);
  return vec4(t[0], t[1], t[2], t[3]);
}

#else

// The dictionary as the host describes it; the texels are the host's resources.
struct GlintDictionaryView {
  int numLevels;              // L
  int numDistributions;       // N
  int texelsPerDistribution;  // R
  float alpha;                // alpha_d, the dictionary's roughness
  int numMips;                // the mip chain's levels (1 without one)
  int mipRowLength;           // texels of all mip levels of one distribution
};

// The hook, defined by the host (top of this file).
vec2 glintDictionaryTexelPair(GlintDictionaryView view, int level, int distribution, int texel);
vec4 glintDictionaryFilteredTexels(GlintDictionaryView view, int level, int distribution, int index);
vec4 glintDictionaryCumulativeTexel(GlintDictionaryView view, int level, int distribution, int texel);

#endif

// Where level m of the mip chain starts in a distribution's row: R + R/2 + ... + R/2^(m-1) texels.
GLINT_FN int glintMipOffset(int texelsPerDistribution, int mip) {
  return 2 * texelsPerDistribution - ((2 * texelsPerDistribution) >> mip);
}

GLINT_KERNEL_END

#endif
