// The CPU-versus-GPU kernel cases (shaders/kernel_eval.glsl: eight vec4s a case in, (f, D(wh),
// P22(wh), Cook-Torrance f) out) as a Vulkan compute shader, for a harness that runs the kernel on
// a Vulkan implementation: KernelEval.Vulkan, and KernelEval.VulkanFiltered with GLINT_FILTERED 1.
// Descriptor set 0: binding 0 the cases (storage buffer, std430, 128 bytes a case), binding 1 the
// results (storage buffer, one vec4 a case), bindings 2 to 4 the dictionary and the case count,
// binding 5 the albedo tables (dictionary_vulkan.glsl). One invocation a case, 64 a workgroup.
#version 450
#extension GL_GOOGLE_include_directive : require
// The albedo tables from a buffer (binding 5), not the kernel's constant arrays: lavapipe's
// compile of those takes minutes (kernel/multiple_scattering.h).
#define GLINT_ALBEDO_TABLE_HOOK 1
#include "kernel_eval.glsl"
#include "dictionary_vulkan.glsl"

layout(local_size_x = 64) in;
layout(std430, set = 0, binding = 0) readonly buffer Inputs { KernelInput inputs[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Outputs { vec4 outputs[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < dictionaryShape.caseCount) {
    outputs[i] = evaluateCase(dictionaryView(), inputs[i]);
  }
}
