// The kernel's language bridge: every file under kernel/ compiles both as C++20 (with glm) and as
// GLSL 4.50, so that the model's equations are written once (docs/conventions.md, "One model, two
// languages"). Rules for kernel code:
//   - every input is a function argument: no uniforms, no derivatives, no globals;
//   - integer hashing on uint (wrap-around is defined in both languages);
//   - float literals carry the f suffix, unsigned ones the u suffix;
//   - no swizzle assignment, no struct constructors (assign fields), no recursion;
//   - functions are declared with GLINT_FN, out-parameters with GLINT_OUT(T), in-out ones with
//     GLINT_INOUT(T).
// The kernel reaches the dictionary only through glintDictionaryTexelPair() (texels k and k+1 of a
// distribution, 0 past the last), which each language defines: below for C++ (a DictionaryView
// over host memory), in shaders/ for GLSL (a buffer texture of pairs). The host's own code reads
// single texels with glintDictionaryTexel().
#ifndef GLINT_KERNEL_PRELUDE_H
#define GLINT_KERNEL_PRELUDE_H

#ifdef __cplusplus

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

GLINT_KERNEL_BEGIN

// Read-only view of a dictionary in host memory: texels[(level * numDistributions + distribution)
// * texelsPerDistribution + texel], each a float that is exactly representable as binary16, so the
// CPU reads the very values the GPU's R16F texture holds.
struct DictionaryView {
  const float* texels;
  int numLevels;
  int numDistributions;
  int texelsPerDistribution;
  float alpha;  // alpha_d, the dictionary's roughness
};

GLINT_FN float glintDictionaryTexel(DictionaryView dict, int level, int distribution, int texel) {
  return dict.texels[(level * dict.numDistributions + distribution) * dict.texelsPerDistribution + texel];
}

GLINT_FN vec2 glintDictionaryTexelPair(DictionaryView dict, int level, int distribution, int texel) {
  const float* row = dict.texels + (level * dict.numDistributions + distribution) * dict.texelsPerDistribution;
  return vec2(row[texel], texel + 1 < dict.texelsPerDistribution ? row[texel + 1] : 0.0f);
}

GLINT_KERNEL_END

#else  // GLSL

#include "glint_dictionary.glsl"

#define GLINT_KERNEL_BEGIN
#define GLINT_KERNEL_END
#define GLINT_FN
#define GLINT_CONST const
#define GLINT_OUT(T) out T
#define GLINT_INOUT(T) inout T

#endif

#endif
