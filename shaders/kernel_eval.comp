// Evaluates the shared kernel for a buffer of inputs: the GPU half of the CPU-versus-GLSL test
// (tests/test_gl_kernel.cpp). Same functions, same argument order as glint::GlintBsdf. With SLOPE_SET
// defined it evaluates the renderer's several-slopes walk instead.
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
  params.colouredCells = false;
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
  // The renderer's several-lights walk (glintP22Set, compiled with GLINT_SLOPE_COUNT = 3): case i's
  // footprint at the half vectors of its wo with the wi of cases i, i + 1 and i + 2; P22 in .xyz,
  // 0 where a half vector is below the surface.
  GlintSlopeSet slopes;
  bool above[GLINT_SLOPE_COUNT];
  for (int k = 0; k < GLINT_SLOPE_COUNT; ++k) {
    vec3 wh = normalize(wo + inputs[(i + uint(k)) % uCount].wiAndRelativeArea.xyz);
    above[k] = wh.z > 0.0f;
    slopes.slope[k] = above[k] ? slopeFromNormal(wh) : vec2(0.0f);
  }
  GlintP22Set p22 = glintP22Set(dict, params, uv, duvdx, duvdy, slopes);
  outputs[i] = vec4(above[0] ? p22.p22[0].w : 0.0f, above[1] ? p22.p22[1].w : 0.0f, above[2] ? p22.p22[2].w : 0.0f, 0.0f);
#else
  vec3 wh = normalize(wo + wi);
  float p22 = wh.z > 0.0f ? glintP22(dict, params, uv, duvdx, duvdy, slopeFromNormal(wh)) : 0.0f;
  float d = wh.z > 0.0f ? ndfFromP22(p22, wh.z) : 0.0f;
  outputs[i] = vec4(glintReflectance(dict, params, uv, duvdx, duvdy, wo, wi), d, p22,
                    cookTorranceReflectance(params.alpha, wo, wi));
#endif
}
