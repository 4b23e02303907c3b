// The CPU-versus-GPU kernel cases (shaders/kernel_eval.glsl: eight float4s a case in, (f, D(wh),
// P22(wh), Cook-Torrance f) out) as an HLSL compute shader, for a harness that runs the kernel
// through DXC or glslang's HLSL front end: KernelEval.Hlsl, and KernelEval.HlslFiltered with
// GLINT_FILTERED 1. Registers, and for SPIR-V the same numbers as bindings of descriptor set 0:
// t0 / binding 0 the cases (StructuredBuffer, 128 bytes a case), u1 / binding 1 the results
// (RWStructuredBuffer<float4>), t2, t3, b4 / bindings 2 to 4 the dictionary and the case count,
// t5 / binding 5 the albedo tables (dictionary.hlsl). One thread a case, 64 a group.
#define GLINT_HLSL 1
// The albedo tables from a buffer (binding 5), not the kernel's constant arrays: lavapipe's
// compile of those takes minutes (kernel/multiple_scattering.h).
#define GLINT_ALBEDO_TABLE_HOOK 1
#include "kernel_eval.glsl"
#include "dictionary.hlsl"

[[vk::binding(0, 0)]] StructuredBuffer<KernelInput> inputs : register(t0);
[[vk::binding(1, 0)]] RWStructuredBuffer<float4> outputs : register(u1);

[numthreads(64, 1, 1)]
void main(uint3 id : SV_DispatchThreadID) {
  uint i = id.x;
  if (i < caseCount) {
    outputs[i] = evaluateCase(dictionaryView(), inputs[i]);
  }
}
