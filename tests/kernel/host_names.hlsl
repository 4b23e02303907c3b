// A host shader (HLSL) with names of its own that an unprefixed kernel would collide with, findLSB
// among them (HLSL has no such intrinsic: its own is firstbitlow), and its own resources at
// registers t0 and t10, bindings 0 and 10 of set 0 in SPIR-V, where glint's renderer keeps its
// dictionary: the kernel must compile inside it (KernelHost.Hlsl).
#define PI 3.14159265f
static const float kPi = PI;
struct DictionaryView {
  int levels;
};
float3 fresnelSchlick(float3 f0, float cosThetaI) {
  return f0 + (1.0f - f0) * pow(1.0f - cosThetaI, 5.0f);
}
uint4 pcg4d(uint4 v) {
  return v * 747796405u + 2891336453u;
}
float smithG1(int ndf, float2 alpha, float rho, float3 w) {
  return 1.0f / (1.0f + alpha.x * length(w.xy) / w.z);
}
int findLSB(uint v) {
  return int(firstbitlow(v));
}
[[vk::binding(0, 0)]] Texture2D<float4> hostAlbedo : register(t0);
[[vk::binding(10, 0)]] Texture2D<float4> hostNormals : register(t10);

#define GLINT_HLSL 1
#include "glint_brdf.h"
#include "microfacet.h"
#include "microfacet_targets.h"
#include "random.h"
#include "lights.h"
#include "tonemap.h"
#include "zirr_kaplanyan.h"
// The host's side of the dictionary hook: t2, t3, b4.
#include "dictionary.hlsl"

[[vk::binding(1, 0)]] RWStructuredBuffer<float4> values : register(u1);

[numthreads(8, 8, 1)]
void main(uint3 id : SV_DispatchThreadID, uint index : SV_GroupIndex) {
  DictionaryView own;
  own.levels = 16;
  GlintParameters params;
  params.alpha = float2(0.5f, 0.5f);
  params.rho = 0.0f;
  params.logDensity = 20.0f;
  params.relativeArea = 1.0f;
  params.densityRandomisation = 2.0f;
  params.maxAnisotropy = 8.0f;
  params.patternSeed = pcg4d(uint4(id, 0u)).x;
  params.colouredCells = false;
  params.ndf = 0;
  params.masking = 0;
  params.lod = 0;
  params.multipleScattering = false;
  params.footprintPolicy.maxAnisotropy = 0.0f;
  params.footprintPolicy.maxCells = 0.0f;
  params.footprintPolicy.minBlend = 0.0f;
  float2 uv = float2(id.xy) / 64.0f;
  float3 wo = normalize(hostNormals.Load(int3(id.xy, 0)).xyz);
  float3 wi = normalize(float3(0.3f, 0.2f, 1.0f));
  float glint = glintReflectance(dictionaryView(), params, uv, float2(1e-3f, 0.0f), float2(0.0f, 1e-3f), wo, wi);
  float3 colour = hostAlbedo.Load(int3(id.xy, 0)).rgb;
  values[index] = float4(fresnelSchlick(colour, wo.z) * glint * smithG1(0, params.alpha, 0.0f, wi) / kPi,
                         float(own.levels + findLSB(id.x)));
}
