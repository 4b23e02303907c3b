// The WebGL2 half of the CPU-versus-GPU kernel test (tests/test_web.cpp): WebGL2 has no compute
// shaders, so each pixel of an RGBA32F target evaluates one case (kernel_eval.glsl), read from
// eight RGBA32F texels of the input texture, one case per pixel, row after row.
#include "kernel_eval.glsl"
#include "glint_dictionary_gl.glsl"

layout(location = 0) out vec4 outValues;  // f, D(wh), P22(wh), Cook-Torrance f
layout(binding = 1) uniform sampler2D uInputs;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  KernelInput data;
  data.uvAndDuvdx = texelFetch(uInputs, ivec2(8 * pixel.x, pixel.y), 0);
  data.duvdyAndAlpha = texelFetch(uInputs, ivec2(8 * pixel.x + 1, pixel.y), 0);
  data.woAndLogDensity = texelFetch(uInputs, ivec2(8 * pixel.x + 2, pixel.y), 0);
  data.wiAndRelativeArea = texelFetch(uInputs, ivec2(8 * pixel.x + 3, pixel.y), 0);
  data.randomisationEtc = texelFetch(uInputs, ivec2(8 * pixel.x + 4, pixel.y), 0);
  data.slopeDerivatives = texelFetch(uInputs, ivec2(8 * pixel.x + 5, pixel.y), 0);
  data.target = texelFetch(uInputs, ivec2(8 * pixel.x + 6, pixel.y), 0);
  data.footprintPolicy = texelFetch(uInputs, ivec2(8 * pixel.x + 7, pixel.y), 0);
  outValues = evaluateCase(glintDictionary(), data);
}
