// One case of the CPU-versus-GPU kernel test: its inputs as eight vec4s and its evaluation, shared by
// the compute shader of the desktop test (kernel_eval.comp, tests/test_gl_kernel.cpp), the
// fragment shader of the WebGL2 test (kernel_eval.frag, tests/test_web.cpp) and the Vulkan GLSL and
// HLSL compute entries (tests/kernel/kernel_eval_vulkan.comp, kernel_eval.hlsl). Same functions,
// same argument order as glint::GlintBsdf; with GLINT_FILTERED 1 the P-SDF is the anti-aliased one
// (glintFilteredP22) at the case's slope derivatives. Written in the kernel's dialect
// (src/glint/kernel/prelude.h), so that it compiles in every language the kernel does; the
// dictionary comes from the caller, who defines the kernel's dictionary hook.
#ifndef KERNEL_EVAL_GLSL
#define KERNEL_EVAL_GLSL

#define GLINT_MULTIPLE_SCATTERING 1
#include "glint_brdf.h"
#include "multiple_scattering.h"

struct KernelInput {
  vec4 uvAndDuvdx;           // uv.xy, duvdx.xy
  vec4 duvdyAndAlpha;        // duvdy.xy, alpha.xy
  vec4 woAndLogDensity;      // wo.xyz, log density
  vec4 wiAndRelativeArea;    // wi.xyz, relative area
  vec4 randomisationEtc;     // density randomisation, max anisotropy, pattern seed (as float), rho
  vec4 slopeDerivatives;     // the half vector slope's (d/dx, d/dy), for GLINT_FILTERED
  vec4 target;               // ndf, masking (microfacet_targets.h), multiple scattering (0 or 1), as floats
  vec4 footprintPolicy;      // GlintFootprintPolicy: aniso, cells, drop (0: the paper's footprint); the LOD construction
};

// The case's parameters, footprint and directions.
void readCase(KernelInput data, GLINT_OUT(GlintParameters) params, GLINT_OUT(vec2) uv, GLINT_OUT(vec2) duvdx,
              GLINT_OUT(vec2) duvdy, GLINT_OUT(vec3) wo, GLINT_OUT(vec3) wi) {
  params.alpha = data.duvdyAndAlpha.zw;
  params.logDensity = data.woAndLogDensity.w;
  params.relativeArea = data.wiAndRelativeArea.w;
  params.densityRandomisation = data.randomisationEtc.x;
  params.maxAnisotropy = data.randomisationEtc.y;
  params.patternSeed = uint(data.randomisationEtc.z);
  params.rho = data.randomisationEtc.w;
  params.colouredCells = false;
  params.ndf = int(data.target.x);
  params.masking = int(data.target.y);
  params.multipleScattering = data.target.z > 0.5f;
  params.footprintPolicy.maxAnisotropy = data.footprintPolicy.x;
  params.footprintPolicy.maxCells = data.footprintPolicy.y;
  params.footprintPolicy.minBlend = data.footprintPolicy.z;
  params.lod = int(data.footprintPolicy.w);
  uv = data.uvAndDuvdx.xy;
  duvdx = data.uvAndDuvdx.zw;
  duvdy = data.duvdyAndAlpha.xy;
  wo = data.woAndLogDensity.xyz;
  wi = data.wiAndRelativeArea.xyz;
}

// (f, D(wh), P22(wh), Cook-Torrance f) of one case.
vec4 evaluateCase(GlintDictionaryView dict, KernelInput data) {
  GlintParameters params;
  vec2 uv, duvdx, duvdy;
  vec3 wo, wi;
  readCase(data, params, uv, duvdx, duvdy, wo, wi);
  vec3 wh = normalize(wo + wi);
#if GLINT_FILTERED
  float p22 = wh.z > 0.0f ? glintFilteredP22(dict, params, uv, duvdx, duvdy, glintSlopeFromNormal(wh),
                                             data.slopeDerivatives)
                          : 0.0f;
  float d = wh.z > 0.0f ? glintNdfFromP22(p22, wh.z) : 0.0f;
  float f = wo.z > 0.0f && wi.z > 0.0f ? glintMaskedReflectance(params, wo, wi, wh, d) : 0.0f;
#else
  float p22 = wh.z > 0.0f ? glintP22(dict, params, uv, duvdx, duvdy, glintSlopeFromNormal(wh)) : 0.0f;
  float d = wh.z > 0.0f ? glintNdfFromP22(p22, wh.z) : 0.0f;
  float f = glintReflectance(dict, params, uv, duvdx, duvdy, wo, wi);
#endif
  // The compensation lobe with F = 1 (multiple_scattering.h), added to both BRDFs when the case has it.
  float multiple = params.multipleScattering ? glintMultipleScatteringReflectance(params.ndf, params.masking, params.alpha, wo, wi) : 0.0f;
  return vec4(f + multiple, d, p22,
              glintTargetCookTorranceReflectance(params.ndf, params.masking, params.alpha, params.rho, wo, wi) + multiple);
}

#endif
