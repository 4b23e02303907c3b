// A host shader (GLSL 4.50, OpenGL) with names of its own that an unprefixed kernel would collide
// with, and its own resources at bindings 0 and 10, where glint's renderer keeps its dictionary:
// the kernel must compile inside it (KernelHost.DesktopGl). findLSB is not defined here: it is a
// GLSL 4.50 built-in, which GLSL 1.30 and later forbid a shader to redefine.
#version 450
#extension GL_GOOGLE_include_directive : require
#define PI 3.14159265f
const float kPi = PI;
struct DictionaryView {
  int levels;
};
vec3 fresnelSchlick(vec3 f0, float cosThetaI) {
  return f0 + (vec3(1.0f) - f0) * pow(1.0f - cosThetaI, 5.0f);
}
uvec4 pcg4d(uvec4 v) {
  return v * 747796405u + 2891336453u;
}
float smithG1(int ndf, vec2 alpha, float rho, vec3 w) {
  return 1.0f / (1.0f + alpha.x * length(w.xy) / w.z);
}
layout(binding = 0) uniform sampler2D hostAlbedo;
layout(binding = 10) uniform sampler2D hostNormals;

#include "glint_brdf.h"
#include "microfacet.h"
#include "microfacet_targets.h"
#include "random.h"
#include "lights.h"
#include "tonemap.h"

// The host's side of the dictionary hook, on bindings of its choosing.
layout(binding = 2) uniform samplerBuffer hostDictionary;
layout(binding = 3) uniform samplerBuffer hostDictionaryMips;
layout(location = 0) uniform ivec4 hostDictionaryShape;  // L, N, R, numMips
layout(location = 1) uniform vec2 hostDictionaryAlphaAndRow;
vec2 glintDictionaryTexelPair(GlintDictionaryView view, int level, int distribution, int texel) {
  return texelFetch(hostDictionary, (level * view.numDistributions + distribution) * view.texelsPerDistribution + texel).xy;
}
vec4 glintDictionaryFilteredTexels(GlintDictionaryView view, int level, int distribution, int index) {
  return texelFetch(hostDictionaryMips, (level * view.numDistributions + distribution) * view.mipRowLength + index);
}

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 1) buffer Values { vec4 values[]; };

void main() {
  DictionaryView own;
  own.levels = 16;
  GlintDictionaryView view;
  view.numLevels = hostDictionaryShape.x;
  view.numDistributions = hostDictionaryShape.y;
  view.texelsPerDistribution = hostDictionaryShape.z;
  view.numMips = hostDictionaryShape.w;
  view.alpha = hostDictionaryAlphaAndRow.x;
  view.mipRowLength = int(hostDictionaryAlphaAndRow.y);
  GlintParameters params;
  params.alpha = vec2(0.5f);
  params.rho = 0.0f;
  params.logDensity = 20.0f;
  params.relativeArea = 1.0f;
  params.densityRandomisation = 2.0f;
  params.maxAnisotropy = 8.0f;
  params.patternSeed = pcg4d(uvec4(gl_GlobalInvocationID, 0u)).x;
  params.colouredCells = false;
  params.ndf = 0;
  params.masking = 0;
  params.lod = 0;
  params.multipleScattering = false;
  params.footprintPolicy.maxAnisotropy = 0.0f;
  params.footprintPolicy.maxCells = 0.0f;
  params.footprintPolicy.minBlend = 0.0f;
  vec2 uv = vec2(gl_GlobalInvocationID.xy) / 64.0f;
  vec3 wo = normalize(texelFetch(hostNormals, ivec2(gl_GlobalInvocationID.xy), 0).xyz);
  vec3 wi = normalize(vec3(0.3f, 0.2f, 1.0f));
  float glint = glintReflectance(view, params, uv, vec2(1e-3f, 0.0f), vec2(0.0f, 1e-3f), wo, wi);
  vec3 colour = texelFetch(hostAlbedo, ivec2(gl_GlobalInvocationID.xy), 0).rgb;
  values[gl_LocalInvocationIndex] =
      vec4(fresnelSchlick(colour, wo.z) * glint * smithG1(0, params.alpha, 0.0f, wi) / kPi, float(own.levels));
}
