#version 450
// The Vulkan harness's own test (tests/test_vulkan_compute.cpp), in Vulkan GLSL: outputs[i] =
// inputs[i]^2 + offsets[i % 4] for i < count, through every kind of binding the harness offers.
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Inputs { float inputs[]; };
layout(std430, binding = 1) writeonly buffer Outputs { float outputs[]; };
layout(std140, binding = 2) uniform Shape { uint count; };
layout(binding = 3) uniform samplerBuffer offsets;  // R32_SFLOAT texels

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= count) {
    return;
  }
  outputs[i] = inputs[i] * inputs[i] + texelFetch(offsets, int(i % 4u)).x;
}
