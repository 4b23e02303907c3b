// The whole kernel in an HLSL compute shader (shader model 6 rules), with a Direct3D or Vulkan
// renderer's side of the dictionary hook (dictionary.hlsl): KernelLanguages.Hlsl. The host selects
// the kernel's HLSL branch by defining GLINT_HLSL (DXC's __HLSL_VERSION selects it too).
#define GLINT_HLSL 1
#include "kernel_entry_points.glsl"
#include "dictionary.hlsl"

[[vk::binding(1, 0)]] RWStructuredBuffer<float4> values : register(u1);

[numthreads(64, 1, 1)]
void main(uint3 id : SV_DispatchThreadID) {
  uint i = id.x;
  if (i + 2u < caseCount) {
    values[i] = kernelEntryPoints(dictionaryView(), values[i], values[i + 1u], values[i + 2u]);
  }
}
