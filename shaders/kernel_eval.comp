// Evaluates the shared kernel for a buffer of inputs: the GPU half of the CPU-versus-GLSL test
// (tests/test_gl_kernel.cpp). Same functions, same argument order as glint::GlintBsdf.
#include "glint_brdf.h"

layout(local_size_x = 64) in;

struct KernelInput {
  vec4 uvAndDuvdx;           // uv.xy, duvdx.xy
  vec4 duvdyAndAlpha;        // duvdy.xy, alpha.xy
  vec4 woAndLogDensity;      // wo.xyz, log density
  vec4 wiAndRelativeArea;    // wi.xyz, relative area
  vec4 randomisationEtc;     // density randomisation, max anisotropy, pattern seed (as float), unused
};

layout(std430, binding = 0) readonly buffer Inputs { KernelInput inputs[]; };
layout(std430, binding = 1) writeonly buffer Outputs { vec4 outputs[]; };  // f, D(wh), P22(wh), Cook-Torrance f

uniform uint uCount;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uCount) {
    return;
  }
  KernelInput data = inputs[i];
  GlintParameters params;
  params.alpha = data.duvdyAndAlpha.zw;
  params.logDensity = data.woAndLogDensity.w;
  params.relativeArea = data.wiAndRelativeArea.w;
  params.densityRandomisation = data.randomisationEtc.x;
  params.maxAnisotropy = data.randomisationEtc.y;
  params.patternSeed = uint(data.randomisationEtc.z);
  params.colouredCells = false;
  vec2 uv = data.uvAndDuvdx.xy;
  vec2 duvdx = data.uvAndDuvdx.zw;
  vec2 duvdy = data.duvdyAndAlpha.xy;
  vec3 wo = data.woAndLogDensity.xyz;
  vec3 wi = data.wiAndRelativeArea.xyz;
  DictionaryView dict = glintDictionary();
  vec3 wh = normalize(wo + wi);
  float p22 = wh.z > 0.0f ? glintP22(dict, params, uv, duvdx, duvdy, slopeFromNormal(wh)) : 0.0f;
  float d = wh.z > 0.0f ? ndfFromP22(p22, wh.z) : 0.0f;
  outputs[i] = vec4(glintReflectance(dict, params, uv, duvdx, duvdy, wo, wi), d, p22,
                    cookTorranceReflectance(params.alpha, wo, wi));
}
