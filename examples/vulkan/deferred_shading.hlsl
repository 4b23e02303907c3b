// The lighting pass of examples/vulkan (main.cpp), in HLSL, compiled to SPIR-V at build time by
// glslangValidator from glint's installed shader folder: one thread a pixel reads the G-buffer,
// shades the glint layer with the kernel (glint_kernel.h) under one point light, and writes linear
// radiance. The anti-aliased model (GLINT_FILTERED 1) would also need each light's half-vector
// slope derivatives, which this G-buffer does not hold; this pass shades with the 2020 model.
//
// Bindings, descriptor set 0 (register numbers the same, for DXC):
//   0 (t0)  the G-buffer, one GBufferTexel a pixel, row by row, top row first;
//   1 (u1)  the radiance, one float4 a pixel;
//   2 (t2)  the dictionary, a uniform texel buffer of R16G16_SFLOAT: texel
//           (level * N + distribution) * R + k holds (p[k], p[k + 1]), p[R] = 0
//           (glint::Dictionary::halfTexelPairs);
//   3 (b3)  the frame's constants, Frame below (main.cpp fills the same layout).
#define GLINT_HLSL 1
#include "glint_kernel.h"

// What the geometry pass (here the CPU's ray casts) leaves per pixel. The glint footprint needs the
// mesh uv and its screen derivatives: they cannot be taken in this pass, whose neighbouring
// threads may be other surfaces, so the geometry pass stores them (docs/integration.md,
// "Deferred shading").
struct GBufferTexel {
  float4 positionAndCoverage;  // world position; w 1 where a surface covers the pixel, 0 elsewhere
  float4 normal;               // unit shading normal (w unused)
  float4 tangentAndSign;       // unit tangent along increasing u; w the bitangent's sign (glTF's)
  float4 uvAndDuvdx;           // mesh uv, d(uv)/dx (one pixel right)
  float4 duvdy;                // d(uv)/dy (one pixel down), zw unused
};

[[vk::binding(0, 0)]] StructuredBuffer<GBufferTexel> gBuffer : register(t0);
[[vk::binding(1, 0)]] RWStructuredBuffer<float4> radiance : register(u1);
[[vk::binding(2, 0)]] Buffer<float2> dictionaryPairs : register(t2);
[[vk::binding(3, 0)]] cbuffer Frame : register(b3) {
  GlintMaterial material;       // the glint layer (kernel/glint_material.h: the same layout in C++)
  float4 cameraPosition;        // xyz
  float4 lightPosition;         // xyz, a point light
  float4 lightIntensity;        // rgb, W/sr
  float4 baseColour;            // rgb; the material is a dielectric (F0 = 0.04)
  int4 dictionaryShape;         // L, N, R, numMips
  float dictionaryAlpha;        // alpha_d
  int dictionaryMipRowLength;
  uint width;
  uint height;
};

// The kernel's dictionary hook (prelude.h), this renderer's side: texels from the texel buffer.
float2 glintDictionaryTexelPair(GlintDictionaryView view, int level, int distribution, int texel) {
  return dictionaryPairs[uint((level * view.numDistributions + distribution) * view.texelsPerDistribution + texel)];
}

// Read only by the anti-aliased model, which this pass does not use: the prelude allows a host
// without the mip chain to answer with the plain pair.
float4 glintDictionaryFilteredTexels(GlintDictionaryView view, int level, int distribution, int index) {
  return float4(glintDictionaryTexelPair(view, level, distribution, index), 0.0f, 0.0f);
}

GlintDictionaryView dictionaryView() {
  GlintDictionaryView view;
  view.numLevels = dictionaryShape.x;
  view.numDistributions = dictionaryShape.y;
  view.texelsPerDistribution = dictionaryShape.z;
  view.numMips = dictionaryShape.w;
  view.alpha = dictionaryAlpha;
  view.mipRowLength = dictionaryMipRowLength;
  return view;
}

[numthreads(8, 8, 1)]
void main(uint3 id : SV_DispatchThreadID) {
  if (id.x >= width || id.y >= height) {
    return;
  }
  uint pixel = id.y * width + id.x;
  GBufferTexel g = gBuffer[pixel];
  if (g.positionAndCoverage.w == 0.0f) {
    radiance[pixel] = float4(0.0f, 0.0f, 0.0f, 1.0f);  // no surface, no environment
    return;
  }
  // The shading frame and the directions in it (z the normal, x the tangent: the frame the glint
  // uv's slopes are measured in).
  float3 position = g.positionAndCoverage.xyz;
  float3 n = g.normal.xyz;
  float3 t = g.tangentAndSign.xyz;
  float3 b = cross(n, t) * (g.tangentAndSign.w < 0.0f ? -1.0f : 1.0f);
  float3 view = normalize(cameraPosition.xyz - position);
  float3 toLight = lightPosition.xyz - position;
  float distance2 = dot(toLight, toLight);
  float3 l = toLight * rsqrt(distance2);
  float3 wo = float3(dot(view, t), dot(view, b), max(dot(view, n), 1e-4f));
  float3 wi = float3(dot(l, t), dot(l, b), dot(l, n));
  if (wi.z <= 0.0f) {
    radiance[pixel] = float4(0.0f, 0.0f, 0.0f, 1.0f);
    return;
  }

  // The glint footprint: the glint uv and its derivatives (the material's uv scale, a linear map).
  float2 uv = glintMaterialUv(material, g.uvAndDuvdx.xy);
  float2 duvdx = glintMaterialUv(material, g.uvAndDuvdx.zw);
  float2 duvdy = glintMaterialUv(material, g.duvdy.xy);
  GlintFootprintPolicy policy;  // the paper's footprint
  policy.maxAnisotropy = 0.0f;
  policy.maxCells = 0.0f;
  policy.minBlend = 0.0f;
  // No glint textures: their samples are 1.
  GlintParameters params = glintMaterialParameters(material, 1.0f, 1.0f, 1.0f, policy);

  float3 wh = normalize(wo + wi);
  float3 fresnel = glintFresnelSchlick(glintSplat3(0.04f), dot(wo, wh));
  float3 specular = fresnel * glintReflectance(dictionaryView(), params, uv, duvdx, duvdy, wo, wi);
  float3 diffuse = baseColour.rgb / GLINT_PI;
  radiance[pixel] = float4((diffuse + specular) * wi.z * lightIntensity.rgb / distance2, 1.0f);
}
