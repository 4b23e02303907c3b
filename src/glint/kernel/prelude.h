// The kernel's language bridge. Every file under kernel/ compiles from the same text as C++20
// (with glm) and as four shading languages, so that the model's equations are written once
// (docs/conventions.md, "One model, five languages"):
//   - C++ (__cplusplus): namespace glint::kernel, over glm;
//   - GLSL 4.50 for OpenGL and GLSL 4.50 for Vulkan (SPIR-V through glslang): the default;
//   - GLSL ES 3.00 (WebGL2): selected by the compiler's own GL_ES;
//   - HLSL, shader model 6 rules (DXC; glslang's HLSL front end): selected by GLINT_HLSL, which the
//     host defines before including the kernel, or by __HLSL_VERSION, which DXC predefines
//     (glslang's HLSL front end predefines no such macro).
//
// Including the kernel in another renderer's shaders. The kernel declares no resource (no uniform,
// buffer, texture or binding) and every name it defines carries its prefix: functions glintXxx,
// types GlintXxx, constants and macros GLINT_XXX. It reads the glint dictionary through one hook,
// two functions that the host defines after including the kernel (GLSL and HLSL accept a
// prototype with a later definition); their prototypes are below:
//
//   vec2 glintDictionaryTexelPair(GlintDictionaryView view, int level, int distribution, int texel)
//     texels k = texel and k + 1 of the marginal `distribution` of dictionary level `level`, the
//     second 0 past the distribution's last texel (docs/dictionary.md, "Texel convention");
//   vec4 glintDictionaryFilteredTexels(GlintDictionaryView view, int level, int distribution, int index)
//     texel `index` of that distribution's row of the mip chain (docs/dictionary.md, "Mip chain"),
//     glintMipOffset(R, m) + k for texel k of mip m: (p_m[k], p_m[k+1], q_m[k], q_m[k+1]). Only the
//     anti-aliased P-SDF (GLINT_FILTERED 1) reads it; a host without the mip chain may return
//     (glintDictionaryTexelPair(...), 0, 0).
// A shader that includes a header whose functions read the dictionary (dictionary_lookup.h, and so
// glint_antialiasing.h, glint_brdf.h, zirr_kaplanyan.h) defines both, even if it calls none of
// those functions: some GLSL linkers (Mesa's) resolve the calls of every function. A shader that
// includes glint_extended_lights.h (glints under area lights and environments) defines a third:
//   vec4 glintDictionaryCumulativeTexel(GlintDictionaryView view, int level, int distribution, int texel)
//     (C[k], M[k], p[k], p[k+1]), k = texel: the integrals of that marginal and of the slope times it
//     from slope 0 to texel k's slope, then texel k's pair as glintDictionaryTexelPair returns it, as
//     glint::Dictionary::cumulativeTexels() holds them (docs/dictionary.md, "Cumulative tables"):
//     32-bit floats, as a difference of two binary16 values would lose the narrow regions' mass; the
//     pair beside them so that one read serves an integral.
//
// GlintDictionaryView is the host's description of its dictionary: in shaders its shape and
// roughness (which the host fills, from its own uniforms or constant buffer), in C++ pointers to
// host memory, for which this file defines the hook itself. The host decides where the texels
// live: glint's renderer reads two buffer textures (shaders/glint_dictionary_gl.glsl); the tests'
// Vulkan and HLSL hosts read texel and typed buffers (tests/kernel/dictionary_vulkan.glsl,
// dictionary.hlsl). A GLSL ES host declares high precision for floats and ints (the hashing needs
// 32-bit integers).
//
// Rules for kernel code, so that the same text is valid in every language:
//   - every input is a function argument: no uniforms, no derivatives, no globals;
//   - integer hashing on uint (wrap-around is defined in every language);
//   - float literals carry the f suffix, unsigned ones the u suffix;
//   - no swizzle assignment, no struct constructors (assign fields), no recursion;
//   - functions are declared with GLINT_FN, constants with GLINT_CONST, out-parameters with
//     GLINT_OUT(T), in-out ones with GLINT_INOUT(T);
//   - GLSL's vocabulary, except where HLSL spells a built-in differently: then a helper below
//     (glintMix for mix/lerp, glintFract for fract/frac, glintInverseSqrt for inversesqrt/rsqrt,
//     glintFloatBitsToInt for floatBitsToInt/asint, glintFindLSB for findLSB/firstbitlow,
//     glintLdexp); a vector of one repeated scalar through glintSplat2/3/4 (HLSL has no vec3(x));
//     a matrix times a vector through GLINT_MUL (HLSL's mul); no mod (GLSL's floors, HLSL's fmod
//     truncates): x - y * floor(x / y); no two-argument atan (HLSL's atan2).
#ifndef GLINT_KERNEL_PRELUDE_H
#define GLINT_KERNEL_PRELUDE_H

#if defined(__cplusplus)

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
// GLSL's vector type names, which the kernel is written in, as HLSL's (a host that maps them
// already keeps its own macros).
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

// The kernel's compile-time configuration, which the host may define before including it:
//   GLINT_FILTERED 1: the P-SDF's walk filters (glint_antialiasing.h; C++ decides per call);
//   GLINT_MULTIPLE_SCATTERING 1: the albedo tables and the compensation lobe (multiple_scattering.h);
//   GLINT_SLOPE_COUNT: the slopes of one walk (glint_brdf.h, 1 by default);
//   GLINT_FOOTPRINT_POLICY: the footprint policy's words the walk applies (glint_footprint.h, all).
#ifndef GLINT_FILTERED
#define GLINT_FILTERED 0
#endif
#ifndef GLINT_MULTIPLE_SCATTERING
#define GLINT_MULTIPLE_SCATTERING 0
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
// GLSL ES 3.00 (WebGL2) lacks findLSB and ldexp (ES 3.10 built-ins): written out exactly, through
// the float's bits (no exp2 or log2 rounding).
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

// The hook, defined by the host (see the top of this file).
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
