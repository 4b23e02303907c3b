#version 300 es
// A host shader (GLSL ES 3.00, WebGL2) with names of its own that an unprefixed kernel would
// collide with, findLSB among them (an ES 3.10 built-in, so an ES 3.00 shader may define it), and
// its own samplers on units 0 and 10, where glint's renderer keeps its dictionary (ES 3.00 has no
// layout(binding): the units are set through the API): the kernel must compile inside it
// (KernelHost.GlslEs300).
precision highp float;
precision highp int;
precision highp sampler2D;
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
int findLSB(uint v) {
  for (int i = 0; i < 32; ++i) {
    if ((v & (1u << uint(i))) != 0u) {
      return i;
    }
  }
  return -1;
}
uniform sampler2D hostAlbedo;   // unit 0
uniform sampler2D hostNormals;  // unit 10

#include "glint_brdf.h"
#include "microfacet.h"
#include "microfacet_targets.h"
#include "random.h"
#include "lights.h"
#include "tonemap.h"
#include "zirr_kaplanyan.h"

// The host's side of the dictionary hook: two textures of its own, 2048 texels a row.
uniform sampler2D hostDictionary;
uniform sampler2D hostDictionaryMips;
uniform ivec4 hostDictionaryShape;  // L, N, R, numMips
uniform vec2 hostDictionaryAlphaAndRow;
vec2 glintDictionaryTexelPair(GlintDictionaryView view, int level, int distribution, int texel) {
  int i = (level * view.numDistributions + distribution) * view.texelsPerDistribution + texel;
  return texelFetch(hostDictionary, ivec2(i & 2047, i >> 11), 0).xy;
}
vec4 glintDictionaryFilteredTexels(GlintDictionaryView view, int level, int distribution, int index) {
  int i = (level * view.numDistributions + distribution) * view.mipRowLength + index;
  return texelFetch(hostDictionaryMips, ivec2(i & 2047, i >> 11), 0);
}

layout(location = 0) out vec4 outColour;

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
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  GlintParameters params;
  params.alpha = vec2(0.5f);
  params.rho = 0.0f;
  params.logDensity = 20.0f;
  params.relativeArea = 1.0f;
  params.densityRandomisation = 2.0f;
  params.maxAnisotropy = 8.0f;
  params.patternSeed = pcg4d(uvec4(uvec2(pixel), 0u, 0u)).x;
  params.colouredCells = false;
  params.ndf = 0;
  params.masking = 0;
  params.lod = 0;
  params.multipleScattering = false;
  params.footprintPolicy.maxAnisotropy = 0.0f;
  params.footprintPolicy.maxCells = 0.0f;
  params.footprintPolicy.minBlend = 0.0f;
  vec2 uv = vec2(pixel) / 64.0f;
  vec3 wo = normalize(texelFetch(hostNormals, pixel, 0).xyz);
  vec3 wi = normalize(vec3(0.3f, 0.2f, 1.0f));
  float glint = glintReflectance(view, params, uv, dFdx(uv), dFdy(uv), wo, wi);
  vec3 colour = texelFetch(hostAlbedo, pixel, 0).rgb;
  outColour = vec4(fresnelSchlick(colour, wo.z) * glint * smithG1(0, params.alpha, 0.0f, wi) / kPi,
                   float(own.levels + findLSB(uint(pixel.x))));
}
