#version 300 es
// The whole kernel in a GLSL ES 3.00 fragment shader (WebGL2; ES 3.00 has no compute stage and no
// layout(binding)): KernelLanguages.GlslEs300. The dictionary hook reads two 2D textures laid out
// as glint's page lays its buffers (2048 texels a row).
precision highp float;
precision highp int;
precision highp sampler2D;
#include "kernel_entry_points.glsl"

uniform sampler2D dictionaryPairs;
uniform sampler2D dictionaryMips;
uniform sampler2D dictionaryCumulative;
uniform ivec4 dictionaryShape;  // L, N, R, numMips
uniform float dictionaryAlpha;
uniform int dictionaryMipRowLength;
uniform sampler2D inputs;

vec2 glintDictionaryTexelPair(GlintDictionaryView view, int level, int distribution, int texel) {
  int i = (level * view.numDistributions + distribution) * view.texelsPerDistribution + texel;
  return texelFetch(dictionaryPairs, ivec2(i & 2047, i >> 11), 0).xy;
}

vec4 glintDictionaryFilteredTexels(GlintDictionaryView view, int level, int distribution, int index) {
  int i = (level * view.numDistributions + distribution) * view.mipRowLength + index;
  return texelFetch(dictionaryMips, ivec2(i & 2047, i >> 11), 0);
}

vec4 glintDictionaryCumulativeTexel(GlintDictionaryView view, int level, int distribution, int texel) {
  int i = (level * view.numDistributions + distribution) * view.texelsPerDistribution + texel;
  return texelFetch(dictionaryCumulative, ivec2(i & 2047, i >> 11), 0);
}

layout(location = 0) out vec4 outValues;

void main() {
  GlintDictionaryView view;
  view.numLevels = dictionaryShape.x;
  view.numDistributions = dictionaryShape.y;
  view.texelsPerDistribution = dictionaryShape.z;
  view.numMips = dictionaryShape.w;
  view.alpha = dictionaryAlpha;
  view.mipRowLength = dictionaryMipRowLength;
  int x = int(gl_FragCoord.x);
  int y = int(gl_FragCoord.y);
  outValues = kernelEntryPoints(view, texelFetch(inputs, ivec2(3 * x, y), 0), texelFetch(inputs, ivec2(3 * x + 1, y), 0),
                                texelFetch(inputs, ivec2(3 * x + 2, y), 0));
}
