// The Vulkan harness's own test (tests/test_vulkan_compute.cpp), in HLSL: outputs[i] =
// inputs[i]^2 + offsets[i % 4] for i < count, through every kind of binding the harness offers.
[[vk::binding(0)]] StructuredBuffer<float> inputs;
[[vk::binding(1)]] RWStructuredBuffer<float> outputs;
[[vk::binding(2)]] cbuffer Shape { uint count; };
[[vk::binding(3)]] Buffer<float> offsets;  // R32_SFLOAT texels

[numthreads(64, 1, 1)]
void main(uint3 id : SV_DispatchThreadID) {
  uint i = id.x;
  if (i >= count) {
    return;
  }
  outputs[i] = inputs[i] * inputs[i] + offsets[i % 4];
}
