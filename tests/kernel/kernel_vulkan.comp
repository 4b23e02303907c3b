// The whole kernel in a GLSL 4.50 compute shader for Vulkan (SPIR-V: no plain uniform, descriptor
// sets and bindings), with a Vulkan renderer's side of the dictionary hook (dictionary_vulkan.glsl):
// KernelLanguages.Vulkan.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "kernel_entry_points.glsl"
#include "dictionary_vulkan.glsl"

layout(local_size_x = 64) in;
layout(std430, set = 0, binding = 1) buffer Values { vec4 values[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i + 2u < dictionaryShape.caseCount) {
    values[i] = kernelEntryPoints(dictionaryView(), values[i], values[i + 1u], values[i + 2u]);
  }
}
