// CPU versus Vulkan: the kernel compiled as Vulkan GLSL and as HLSL (tests/kernel/kernel_eval_vulkan.comp,
// kernel_eval.hlsl, both by glslangValidator to SPIR-V at build time) and run as compute shaders on
// the Vulkan device (lavapipe) must agree with the CPU on the OpenGL test's cases, by its measure
// (kernel_cases.h; tests/test_gl_kernel.cpp). The dictionary reaches the kernel through the
// host's hook (tests/kernel/dictionary_vulkan.glsl, dictionary.hlsl): the GPU's binary16 pair
// buffer and mip chain as uniform texel buffers, its shape in a uniform buffer; the multiple-
// scattering albedo tables through the tables' hook (GLINT_ALBEDO_TABLE_HOOK), from a uniform texel
// buffer holding the kernel's C++ tables.
#include <cstdint>
#include <iterator>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "glint/kernel/albedo_tables.h"
#include "kernel_cases.h"
#include "test_support.h"
#include "vulkan_compute.h"

namespace glint::test {
namespace {

using KernelVulkan = VulkanTest;

// The uniform block GlintDictionaryShape of dictionary_vulkan.glsl and dictionary.hlsl, std140.
struct DictionaryShape {
  std::int32_t levelsDistributionsTexelsMips[4];  // L, N, R, numMips
  float alpha;                                     // alpha_d
  std::int32_t mipRowLength;
  std::uint32_t caseCount;
  std::uint32_t padding;  // std140 rounds the block to 16 bytes
};

// The kernel's values of `cases` from the SPIR-V module `module` (one of tests/CMakeLists.txt's
// glint_test_spirv outputs): descriptor set 0 as tests/kernel/kernel_eval_vulkan.comp lays it out.
std::vector<KernelValues> evaluateOnVulkan(const VulkanCompute& vulkan, const std::string& module,
                                           const std::vector<KernelCase>& cases) {
  const Dictionary& dictionary = defaultDictionary();
  const DictionaryParameters& p = dictionary.parameters();
  const DictionaryShape shape{{p.numLevels, p.numDistributions, p.texelsPerDistribution, dictionary.numMips()},
                              p.alpha,
                              dictionary.mipRowLength(),
                              static_cast<std::uint32_t>(cases.size()),
                              0};
  const std::vector<KernelInput> inputs = kernelInputs(cases);
  const std::vector<KernelValues> outputs(cases.size());
  const std::vector<std::uint16_t> pairs = dictionary.halfTexelPairs();
  // The tables' words as 16-bit unsigned normalised texels, the low half of each word first.
  std::vector<std::uint16_t> albedoTables;
  for (const std::span<const kernel::uint> words :
       {std::span<const kernel::uint>(kernel::GLINT_ALBEDO_WORDS), std::span<const kernel::uint>(kernel::GLINT_AVERAGE_ALBEDO_WORDS)}) {
    for (const kernel::uint word : words) {
      albedoTables.push_back(static_cast<std::uint16_t>(word & 0xffffu));
      albedoTables.push_back(static_cast<std::uint16_t>(word >> 16));
    }
  }
  using Kind = VulkanBuffer::Kind;
  std::vector<VulkanBuffer> buffers{
      vulkanBuffer<KernelInput>(0, Kind::storage, inputs),
      vulkanBuffer<KernelValues>(1, Kind::storage, outputs),
      vulkanBuffer<std::uint16_t>(2, Kind::uniformTexel, pairs, VK_FORMAT_R16G16_SFLOAT),
      vulkanBuffer<std::uint16_t>(3, Kind::uniformTexel, dictionary.filteredHalfTexels(), VK_FORMAT_R16G16B16A16_SFLOAT),
      vulkanBuffer<DictionaryShape>(4, Kind::uniform, std::span(&shape, 1)),
      vulkanBuffer<std::uint16_t>(5, Kind::uniformTexel, albedoTables, VK_FORMAT_R16_UNORM),
  };
  constexpr std::uint32_t kWorkgroupSize = 64;  // local_size_x, numthreads
  vulkan.dispatch(readSpirv(std::string(GLINT_TEST_SPIRV_DIR) + "/" + module), buffers,
                  static_cast<std::uint32_t>((cases.size() + kWorkgroupSize - 1) / kWorkgroupSize));
  return buffers[1].as<KernelValues>();
}

TEST_F(KernelVulkan, CpuAndVulkanGlslAgreeOnTenThousandRandomInputs) {
  const std::vector<KernelCase> cases = randomKernelCases(10000);
  expectCpuAndGpuAgree(cases, false, evaluateOnVulkan(vulkan(), "kernel_eval_vulkan.spv", cases), "Vulkan GLSL");
}

TEST_F(KernelVulkan, AntiAliasedCpuAndVulkanGlslAgreeOnTenThousandRandomInputs) {
  const std::vector<KernelCase> cases = randomFilteredKernelCases(10000);
  expectCpuAndGpuAgree(cases, true, evaluateOnVulkan(vulkan(), "kernel_eval_vulkan_filtered.spv", cases), "Vulkan GLSL");
}

TEST_F(KernelVulkan, CpuAndHlslAgreeOnTenThousandRandomInputs) {
  const std::vector<KernelCase> cases = randomKernelCases(10000);
  expectCpuAndGpuAgree(cases, false, evaluateOnVulkan(vulkan(), "kernel_eval_hlsl.spv", cases), "HLSL");
}

TEST_F(KernelVulkan, AntiAliasedCpuAndHlslAgreeOnTenThousandRandomInputs) {
  const std::vector<KernelCase> cases = randomFilteredKernelCases(10000);
  expectCpuAndGpuAgree(cases, true, evaluateOnVulkan(vulkan(), "kernel_eval_hlsl_filtered.spv", cases), "HLSL");
}

}  // namespace
}  // namespace glint::test
