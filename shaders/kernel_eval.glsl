// One case of the CPU-versus-GPU kernel test: its inputs as six vec4s and its evaluation, shared by
// the compute shader of the desktop test (kernel_eval.comp, tests/test_gl_kernel.cpp) and the
// fragment shader of the WebGL2 test (kernel_eval.frag, tests/test_web.cpp). Same functions, same
// argument order as glint::GlintBsdf; with GLINT_FILTERED 1 the P-SDF is the anti-aliased one
// (glintFilteredP22) at the case's slope derivatives.
#ifndef KERNEL_EVAL_GLSL
#define KERNEL_EVAL_GLSL

#include "glint_brdf.h"

struct KernelInput {
  vec4 uvAndDuvdx;           // uv.xy, duvdx.xy
  vec4 duvdyAndAlpha;        // duvdy.xy, alpha.xy
  vec4 woAndLogDensity;      // wo.xyz, log density
  vec4 wiAndRelativeArea;    // wi.xyz, relative area
  vec4 randomisationEtc;     // density randomisation, max anisotropy, pattern seed (as float), rho
  vec4 slopeDerivatives;     // the half vector slope's (d/dx, d/dy), for GLINT_FILTERED
};

// The case's parameters, footprint and directions.
void readCase(KernelInput data, out GlintParameters params, out vec2 uv, out vec2 duvdx, out vec2 duvdy, out vec3 wo,
              out vec3 wi) {
  params.alpha = data.duvdyAndAlpha.zw;
  params.logDensity = data.woAndLogDensity.w;
  params.relativeArea = data.wiAndRelativeArea.w;
  params.densityRandomisation = data.randomisationEtc.x;
  params.maxAnisotropy = data.randomisationEtc.y;
  params.patternSeed = uint(data.randomisationEtc.z);
  params.rho = data.randomisationEtc.w;
  params.colouredCells = false;
  uv = data.uvAndDuvdx.xy;
  duvdx = data.uvAndDuvdx.zw;
  duvdy = data.duvdyAndAlpha.xy;
  wo = data.woAndLogDensity.xyz;
  wi = data.wiAndRelativeArea.xyz;
}

// (f, D(wh), P22(wh), Cook-Torrance f) of one case.
vec4 evaluateCase(KernelInput data) {
  GlintParameters params;
  vec2 uv, duvdx, duvdy;
  vec3 wo, wi;
  readCase(data, params, uv, duvdx, duvdy, wo, wi);
  DictionaryView dict = glintDictionary();
  vec3 wh = normalize(wo + wi);
#if GLINT_FILTERED
  float p22 = wh.z > 0.0f ? glintFilteredP22(dict, params, uv, duvdx, duvdy, slopeFromNormal(wh),
                                             data.slopeDerivatives)
                          : 0.0f;
  float d = wh.z > 0.0f ? ndfFromP22(p22, wh.z) : 0.0f;
  float f = wo.z > 0.0f && wi.z > 0.0f ? microfacetReflectance(wo, wi, wh, d) : 0.0f;
#else
  float p22 = wh.z > 0.0f ? glintP22(dict, params, uv, duvdx, duvdy, slopeFromNormal(wh)) : 0.0f;
  float d = wh.z > 0.0f ? ndfFromP22(p22, wh.z) : 0.0f;
  float f = glintReflectance(dict, params, uv, duvdx, duvdy, wo, wi);
#endif
  return vec4(f, d, p22, cookTorranceReflectance(params.alpha, params.rho, wo, wi));
}

#endif
