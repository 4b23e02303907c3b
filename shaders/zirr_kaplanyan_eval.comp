// Evaluates the Zirr & Kaplanyan 2016 kernel for a buffer of inputs: the GPU half of the
// CPU-versus-GLSL test (tests/test_zirr_kaplanyan.cpp). Same entry points as the renderer's and
// glint::ZirrKaplanyanBsdf: glintZirrKaplanyanReflectance(uv, duvdx, duvdy, wo, wi, params), and
// glintZirrKaplanyanReferenceReflectance (the reference shader's schedule), which must match it bit for bit.
#include "zirr_kaplanyan.h"
// The dictionary hook: never called here, but zirr_kaplanyan.h includes glint_brdf.h, whose
// functions call it, and Mesa's linker resolves the calls of every function, called or not.
#include "glint_dictionary_gl.glsl"

layout(local_size_x = 64) in;

struct ZirrKaplanyanInput {
  vec4 uvAndDuvdx;                  // uv.xy, duvdx.xy
  vec4 duvdyAndRoughness;           // duvdy.xy, roughness.xy
  vec4 woAndLogDensity;             // wo.xyz, ln(rho_d)
  vec4 wiAndSearchCone;             // wi.xyz, search cone angle c
  vec4 microRoughnessEtc;           // mu.xy, variation, dynamic range
  vec4 anisotropyAndSeed;           // K_a, pattern seed (as float), unused, unused
};

layout(std430, binding = 0) readonly buffer Inputs { ZirrKaplanyanInput inputs[]; };
layout(std430, binding = 1) writeonly buffer Outputs { vec4 outputs[]; };  // f, glints(), cell visits, f (reference schedule)

uniform uint uCount;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uCount) {
    return;
  }
  ZirrKaplanyanInput data = inputs[i];
  GlintZirrKaplanyanParameters params;
  params.roughness = data.duvdyAndRoughness.zw;
  params.microRoughness = data.microRoughnessEtc.xy;
  params.searchConeAngle = data.wiAndSearchCone.w;
  params.variation = data.microRoughnessEtc.z;
  params.dynamicRange = data.microRoughnessEtc.w;
  params.logDensity = data.woAndLogDensity.w;
  params.maxAnisotropy = data.anisotropyAndSeed.x;
  params.patternSeed = uint(data.anisotropyAndSeed.y);
  vec2 uv = data.uvAndDuvdx.xy;
  vec2 duvdx = data.uvAndDuvdx.zw;
  vec2 duvdy = data.duvdyAndRoughness.xy;
  vec3 wo = data.woAndLogDensity.xyz;
  vec3 wi = data.wiAndSearchCone.xyz;
  int visits;
  float glints = glintZirrKaplanyanGlintsCounted(uv, duvdx, duvdy, wo, wi, params, visits);
  outputs[i] = vec4(glintZirrKaplanyanReflectance(uv, duvdx, duvdy, wo, wi, params), glints, float(visits),
                    glintZirrKaplanyanReferenceReflectance(uv, duvdx, duvdy, wo, wi, params));
}
