// Evaluates the shared kernel for a buffer of inputs: the GPU half of the CPU-versus-GLSL test
// (tests/test_gl_kernel.cpp). Same functions, same argument order as glint::GlintBsdf. With SLOPE_SET
// defined it evaluates the renderer's several-slopes walk instead; with GLINT_FILTERED 1 the P-SDF
// is the anti-aliased one (glintFilteredP22) at the case's slope derivatives.
#define GLINT_MULTIPLE_SCATTERING 1
#include "glint_brdf.h"
#include "multiple_scattering.h"

layout(local_size_x = 64) in;

struct KernelInput {
  vec4 uvAndDuvdx;           // uv.xy, duvdx.xy
  vec4 duvdyAndAlpha;        // duvdy.xy, alpha.xy
  vec4 woAndLogDensity;      // wo.xyz, log density
  vec4 wiAndRelativeArea;    // wi.xyz, relative area
  vec4 randomisationEtc;     // density randomisation, max anisotropy, pattern seed (as float), rho
  vec4 slopeDerivatives;     // the half vector slope's (d/dx, d/dy), for GLINT_FILTERED
  vec4 target;               // ndf, masking (microfacet_targets.h), multiple scattering (0 or 1), as floats
};

layout(std430, binding = 0) readonly buffer Inputs { KernelInput inputs[]; };
#ifdef SLOPE_SET
#if GLINT_SLOPE_COUNT != 3
#error "SLOPE_SET expects GLINT_SLOPE_COUNT 3"
#endif
struct SlopeSetOutput {
  vec4 together[3];  // (colour-weighted P22, P22) of each slope from one walk
  vec4 alone[3];     // the same, each slope walked alone
};
layout(std430, binding = 1) writeonly buffer Outputs { SlopeSetOutput slopeSetOutputs[]; };
#else
layout(std430, binding = 1) writeonly buffer Outputs { vec4 outputs[]; };  // f, D(wh), P22(wh), Cook-Torrance f
#endif

uniform uint uCount;

// Case i's parameters, footprint and directions.
void readCase(uint i, out GlintParameters params, out vec2 uv, out vec2 duvdx, out vec2 duvdy, out vec3 wo,
              out vec3 wi) {
  KernelInput data = inputs[i];
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
  uv = data.uvAndDuvdx.xy;
  duvdx = data.uvAndDuvdx.zw;
  duvdy = data.duvdyAndAlpha.xy;
  wo = data.woAndLogDensity.xyz;
  wi = data.wiAndRelativeArea.xyz;
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uCount) {
    return;
  }
  GlintParameters params;
  vec2 uv, duvdx, duvdy;
  vec3 wo, wi;
  readCase(i, params, uv, duvdx, duvdy, wo, wi);
  DictionaryView dict = glintDictionary();
#ifdef SLOPE_SET
  // The renderer's several-lights walk (glintP22Set): case i's footprint, with coloured cells, at
  // the half vectors of its wo with the wi of cases i, i + 1 and i + 2, each also walked alone;
  // 0 where a half vector is below the surface.
  GlintSlopeSet slopes;
  bool above[GLINT_SLOPE_COUNT];
  params.colouredCells = true;
  for (int k = 0; k < GLINT_SLOPE_COUNT; ++k) {
    vec3 wh = normalize(wo + inputs[(i + uint(k)) % uCount].wiAndRelativeArea.xyz);
    above[k] = wh.z > 0.0f;
    slopes.slope[k] = above[k] ? slopeFromNormal(wh) : vec2(0.0f);
    slopes.derivatives[k] = vec4(0.0f);
  }
  GlintP22Set together = glintP22Set(dict, params, uv, duvdx, duvdy, slopes);
  for (int k = 0; k < GLINT_SLOPE_COUNT; ++k) {
    vec4 alone = glintP22Coloured(dict, params, uv, duvdx, duvdy, slopes.slope[k]);
    slopeSetOutputs[i].together[k] = above[k] ? together.p22[k] : vec4(0.0f);
    slopeSetOutputs[i].alone[k] = above[k] ? alone : vec4(0.0f);
  }
#else
  vec3 wh = normalize(wo + wi);
#if GLINT_FILTERED
  float p22 = wh.z > 0.0f ? glintFilteredP22(dict, params, uv, duvdx, duvdy, slopeFromNormal(wh),
                                             inputs[i].slopeDerivatives)
                          : 0.0f;
  float d = wh.z > 0.0f ? ndfFromP22(p22, wh.z) : 0.0f;
  float f = wo.z > 0.0f && wi.z > 0.0f ? glintMaskedReflectance(params, wo, wi, wh, d) : 0.0f;
#else
  float p22 = wh.z > 0.0f ? glintP22(dict, params, uv, duvdx, duvdy, slopeFromNormal(wh)) : 0.0f;
  float d = wh.z > 0.0f ? ndfFromP22(p22, wh.z) : 0.0f;
  float f = glintReflectance(dict, params, uv, duvdx, duvdy, wo, wi);
#endif
  // The compensation lobe with F = 1 (multiple_scattering.h), added to both BRDFs when the case has it.
  float multiple = params.multipleScattering ? multipleScatteringReflectance(params.ndf, params.masking, params.alpha, wo, wi) : 0.0f;
  outputs[i] = vec4(f + multiple, d, p22,
                    targetCookTorranceReflectance(params.ndf, params.masking, params.alpha, params.rho, wo, wi) + multiple);
#endif
}
