// The Vulkan compute harness (vulkan_compute.h) on its own: a shader that squares a buffer, in
// Vulkan GLSL and in HLSL (tests/vulkan/square.*, compiled to SPIR-V by the build), through a
// storage, a uniform and a uniform texel buffer; and its one-line errors.
#include <array>
#include <cstdint>
#include <fstream>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.h"
#include "vulkan_compute.h"

namespace glint::test {
namespace {

using ComputeVulkan = VulkanTest;

// outputs[i] = inputs[i]^2 + offsets[i % 4] for i < count (tests/vulkan/square.*), over a count that
// is not a multiple of the workgroup size, into a buffer longer than count: the entries past count
// keep their sentinel.
void expectSquares(const VulkanCompute& vulkan, const char* module) {
  constexpr std::uint32_t kCount = 1000;
  constexpr std::uint32_t kOutputs = 1024;
  constexpr float kSentinel = -1.0f;
  std::vector<float> inputs(kCount);
  for (std::uint32_t i = 0; i < kCount; ++i) inputs[i] = static_cast<float>(i) - 100.0f;
  const std::vector<float> outputs(kOutputs, kSentinel);
  const std::array<std::uint32_t, 4> shape{kCount, 0, 0, 0};  // std140: a uniform block is 16 bytes
  const std::array<float, 4> offsets{0.5f, 1.5f, 2.5f, 3.5f};
  std::vector<VulkanBuffer> buffers{
      vulkanBuffer<float>(0, VulkanBuffer::Kind::storage, inputs),
      vulkanBuffer<float>(1, VulkanBuffer::Kind::storage, outputs),
      vulkanBuffer<std::uint32_t>(2, VulkanBuffer::Kind::uniform, shape),
      vulkanBuffer<float>(3, VulkanBuffer::Kind::uniformTexel, offsets, VK_FORMAT_R32_SFLOAT),
  };
  vulkan.dispatch(readSpirv(std::string(GLINT_TEST_SPIRV_DIR) + "/" + module), buffers, (kCount + 63) / 64);
  const std::vector<float> result = buffers[1].as<float>();
  ASSERT_EQ(result.size(), kOutputs);
  for (std::uint32_t i = 0; i < kOutputs; ++i) {
    const float x = static_cast<float>(i) - 100.0f;
    const float expected = i < kCount ? x * x + 0.5f + static_cast<float>(i % 4) : kSentinel;  // exact in binary32
    ASSERT_EQ(result[i], expected) << module << ", entry " << i;
  }
  EXPECT_EQ(buffers[0].as<float>(), inputs);  // a read-only buffer comes back as it went
}

TEST_F(ComputeVulkan, GlslSquaresABuffer) { expectSquares(vulkan(), "square.comp.spv"); }

TEST_F(ComputeVulkan, HlslSquaresABuffer) { expectSquares(vulkan(), "square.hlsl.spv"); }

TEST_F(ComputeVulkan, RunsOnTheCpuDevice) {
  std::printf("Vulkan device: %s\n", vulkan().deviceName().c_str());
  EXPECT_NE(vulkan().deviceName().find("llvmpipe"), std::string::npos) << vulkan().deviceName();
}

TEST_F(ComputeVulkan, AnEmptyBufferIsAOneLineError) {
  std::vector<VulkanBuffer> buffers{{0, VulkanBuffer::Kind::storage, {}}};
  const std::string message = errorOf([&] { vulkan().dispatch(readSpirv(std::string(GLINT_TEST_SPIRV_DIR) + "/square.comp.spv"), buffers, 1); });
  EXPECT_NE(message.find("binding 0 is empty"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(SpirvFile, ABadModuleIsAOneLineErrorNamingTheFile) {
  const auto folder = temporaryFolder("spirv");
  const std::string missing = errorOf([&] { readSpirv(folder / "missing.spv"); });
  EXPECT_NE(missing.find("missing.spv: cannot read"), std::string::npos) << missing;
  std::ofstream(folder / "text.spv") << "not spir-v";
  const std::string text = errorOf([&] { readSpirv(folder / "text.spv"); });
  EXPECT_NE(text.find("text.spv: not a SPIR-V module"), std::string::npos) << text;
}

}  // namespace
}  // namespace glint::test
