// Evaluates the shared kernel for a buffer of inputs: the GPU half of the CPU-versus-GLSL test
// (tests/test_gl_kernel.cpp). Each case as kernel_eval.glsl evaluates it; with SLOPE_SET defined
// it evaluates the renderer's several-slopes walk instead.
#include "kernel_eval.glsl"
#include "glint_dictionary_gl.glsl"

layout(local_size_x = 64) in;

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

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uCount) {
    return;
  }
#ifdef SLOPE_SET
  // The renderer's several-lights walk (glintP22Set): case i's footprint, with coloured cells, at
  // the half vectors of its wo with the wi of cases i, i + 1 and i + 2, each also walked alone;
  // 0 where a half vector is below the surface.
  GlintParameters params;
  vec2 uv, duvdx, duvdy;
  vec3 wo, wi;
  readCase(inputs[i], params, uv, duvdx, duvdy, wo, wi);
  GlintDictionaryView dict = glintDictionary();
  GlintSlopeSet slopes;
  bool above[GLINT_SLOPE_COUNT];
  params.colouredCells = true;
  for (int k = 0; k < GLINT_SLOPE_COUNT; ++k) {
    vec3 wh = normalize(wo + inputs[(i + uint(k)) % uCount].wiAndRelativeArea.xyz);
    above[k] = wh.z > 0.0f;
    slopes.slope[k] = above[k] ? glintSlopeFromNormal(wh) : vec2(0.0f);
    slopes.derivatives[k] = vec4(0.0f);
  }
  GlintP22Set together = glintP22Set(dict, params, uv, duvdx, duvdy, slopes);
  for (int k = 0; k < GLINT_SLOPE_COUNT; ++k) {
    vec4 alone = glintP22Coloured(dict, params, uv, duvdx, duvdy, slopes.slope[k]);
    slopeSetOutputs[i].together[k] = above[k] ? together.p22[k] : vec4(0.0f);
    slopeSetOutputs[i].alone[k] = above[k] ? alone : vec4(0.0f);
  }
#else
  outputs[i] = evaluateCase(glintDictionary(), inputs[i]);
#endif
}
