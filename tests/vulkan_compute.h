// A small Vulkan compute harness for the test suite: one instance and one device per process (the
// CPU device, Mesa lavapipe, when there is one), a SPIR-V module run as a compute shader over
// buffers the caller describes, and the shader's storage buffers read back. Every buffer is
// host-visible memory and every binding is in descriptor set 0; enough for tests, not for speed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <vulkan/vulkan.h>

namespace glint::test {

// One buffer a compute shader declares, at `binding` of descriptor set 0.
struct VulkanBuffer {
  enum class Kind {
    storage,       // GLSL buffer { }, HLSL (RW)StructuredBuffer: read back after the dispatch
    uniform,       // GLSL uniform { } (std140), HLSL cbuffer
    uniformTexel,  // GLSL textureBuffer / samplerBuffer, HLSL Buffer<T>: texels of texelFormat
  };
  std::uint32_t binding = 0;
  Kind kind = Kind::storage;
  std::vector<std::byte> bytes;  // the contents before the dispatch; a storage buffer's after it
  VkFormat texelFormat = VK_FORMAT_UNDEFINED;

  // The buffer's bytes as values of T (a storage buffer's, after the dispatch).
  template <typename T>
  std::vector<T> as() const {
    std::vector<T> values(bytes.size() / sizeof(T));
    std::memcpy(values.data(), bytes.data(), values.size() * sizeof(T));
    return values;
  }
};

// A buffer holding `values`' bytes; a storage buffer that the shader only writes may start as
// values of T{} of the size it needs.
template <typename T>
VulkanBuffer vulkanBuffer(std::uint32_t binding, VulkanBuffer::Kind kind, std::span<const T> values,
                          VkFormat texelFormat = VK_FORMAT_UNDEFINED) {
  VulkanBuffer buffer{binding, kind, std::vector<std::byte>(values.size_bytes()), texelFormat};
  std::memcpy(buffer.bytes.data(), values.data(), values.size_bytes());
  return buffer;
}

// The process's Vulkan instance and device, and compute dispatches on it.
class VulkanCompute {
 public:
  // The shared instance, created on first use; nullptr when no Vulkan device can be had (the
  // reason is then unavailableReason()).
  static VulkanCompute* shared();
  static const std::string& unavailableReason();

  ~VulkanCompute();
  VulkanCompute(const VulkanCompute&) = delete;
  VulkanCompute& operator=(const VulkanCompute&) = delete;

  const std::string& deviceName() const { return deviceName_; }

  // Runs `spirv`'s entry point `entryPoint` as a compute shader over groupCount x 1 x 1 workgroups
  // with `buffers` bound, waits for it, and copies every storage buffer's contents back into its
  // `bytes`. Throws glint::Error with one line on any Vulkan failure.
  void dispatch(std::span<const std::uint32_t> spirv, std::span<VulkanBuffer> buffers, std::uint32_t groupCount,
                const char* entryPoint = "main") const;

 private:
  VulkanCompute();  // throws glint::Error with one line when there is no device
  void create();
  void release();  // destroys what create() made, also after it threw
  std::uint32_t hostVisibleMemoryType(std::uint32_t allowedTypes) const;

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;  // GLINT_VULKAN_VALIDATION=1 only
  VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  std::uint32_t queueFamily_ = 0;
  VkCommandPool commandPool_ = VK_NULL_HANDLE;
  std::string deviceName_;
};

// A SPIR-V module written by glslangValidator (words in this machine's byte order); throws
// glint::Error naming the file when it cannot be read or is not SPIR-V.
std::vector<std::uint32_t> readSpirv(const std::filesystem::path& path);

// The suites that need Vulkan: each test skips, with one line, when there is no device.
class VulkanTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!VulkanCompute::shared()) GTEST_SKIP() << VulkanCompute::unavailableReason();
  }
  const VulkanCompute& vulkan() const { return *VulkanCompute::shared(); }
};

}  // namespace glint::test
