// Deferred shading with glint's kernel in a Vulkan compute shader written in HLSL, from an
// installed glint (find_package(glint)): the glinty sphere of `glint render sphere`.
//
//   glint_vulkan_deferred OUTPUT.{exr,png} --dictionary FILE.gdict [--size N] [--shader FILE.spv]
//
// 1. The geometry pass, here on the CPU: one ray a pixel meets the unit sphere analytically and the
//    hit is written to a G-buffer (GBufferTexel, the same layout in deferred_shading.hlsl): the
//    position, a coverage flag, the shading frame, the mesh uv and the uv's screen derivatives.
//    The derivatives are what a G-buffer must hold for glints: the kernel's footprint is the
//    pixel's area in glint uv (uv and duv/dx, duv/dy), and the lighting pass cannot take them,
//    since its neighbouring pixels may be other surfaces (or none). A rasteriser's geometry pass
//    writes dFdx(uv), dFdy(uv); a ray caster, as here, gets them from ray differentials (pbrt-v3
//    10.1.1): the rays through the next pixel right and down meet the tangent plane at
//    p + dp/dx and p + dp/dy, and dp = dp/du du + dp/dv dv is solved for du and dv. (A G-buffer
//    may instead hold dp/dx, dp/dy and the surface's dp/du, dp/dv, and solve the same in the
//    lighting pass.)
// 2. The lighting pass, deferred_shading.hlsl (glslangValidator -D to SPIR-V at build time,
//    including glint_kernel.h from glint_SHADER_DIR): one thread a pixel shades the G-buffer with
//    the glint BRDF under one point light. It defines the kernel's dictionary hook itself, reading
//    a uniform texel buffer that this program fills from a dictionary file (`glint dict -o FILE`).
// 3. The radiance is read back and written, linear, as EXR (or sRGB PNG, clamped).
//
// The scene is glint's built-in `sphere` (src/scene/builtin_scenes.cpp) with its environment off:
// `glint render sphere --aa none --shadows off --env-intensity 0 -o render.exr` renders the same
// image with the rasteriser (the install test compares the two: tests/install/run_install_test.cmake).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include <glint/dictionary.h>
#include <glint/error.h>
#include <glint/file_io.h>
#include <glint/image_io.h>
#include <glint/kernel/glint_material.h>

namespace {

using glm::vec2;
using glm::vec3;
using glm::vec4;
constexpr float kPi = 3.14159265358979f;

// glint's `sphere` scene: a unit sphere at the origin seen from +z, 45 degrees of vertical field
// of view, a point light of 60 W/sr up and to the right of the camera.
constexpr vec3 kCameraPosition{0.0f, 0.0f, 3.6f};
constexpr float kVerticalFovDegrees = 45.0f;
constexpr vec3 kLightPosition{3.0f, 3.0f, 5.0f};
constexpr vec3 kLightIntensity{60.0f};
constexpr vec3 kBaseColour{0.6f, 0.05f, 0.05f};  // a red dielectric under the glint layer

// Its glint layer (the scene's "red glint" material): alpha 0.5, e^13 microfacets per unit glint
// uv, glint uv = 4 x mesh uv; Beckmann with V-cavity masking, as the 2020 paper.
glint::kernel::GlintMaterial sphereMaterial() {
  glint::kernel::GlintMaterial m{};
  m.alpha = vec2(0.5f);
  m.rho = 0.0f;
  m.logDensity = 13.0f;
  m.relativeArea = 1.0f;
  m.densityRandomisation = 2.0f;
  m.maxAnisotropy = 8.0f;
  m.patternSeed = 0;
  m.logDensityRange = vec2(15.0f, 35.0f);  // unused: no log-density texture
  m.uvScale = 4.0f;
  m.ndf = glint::kernel::GLINT_NDF_BECKMANN;
  m.masking = glint::kernel::GLINT_MASKING_VCAVITY;
  m.lod = glint::kernel::GLINT_LOD_PAPER;
  m.enabled = 1;
  return m;
}

// deferred_shading.hlsl's GBufferTexel and Frame, byte for byte.
struct GBufferTexel {
  vec4 positionAndCoverage;  // w: 1 on the sphere, 0 elsewhere
  vec4 normal;
  vec4 tangentAndSign;  // w: the bitangent cross(n, t) * w's sign
  vec4 uvAndDuvdx;
  vec4 duvdy;
};
struct Frame {
  glint::kernel::GlintMaterial material;
  vec4 cameraPosition, lightPosition, lightIntensity, baseColour;
  glm::ivec4 dictionaryShape;  // L, N, R, numMips
  float dictionaryAlpha;
  std::int32_t dictionaryMipRowLength;
  std::uint32_t width, height;
};
static_assert(sizeof(GBufferTexel) == 80 && sizeof(glint::kernel::GlintMaterial) == 80);
static_assert(offsetof(Frame, cameraPosition) == 80 && offsetof(Frame, dictionaryShape) == 144 && sizeof(Frame) == 176);

struct Ray {
  vec3 origin, direction;
};

// The geometry pass: the sphere's hit at every pixel centre, with its uv (the built-in sphere's: u =
// phi / 2 pi around +y from +z towards +x, v = theta / pi from the north pole) and, from the rays
// through the next pixel right and down, the uv's derivatives.
std::vector<GBufferTexel> fillGBuffer(int width, int height) {
  const vec3 forward = glm::normalize(-kCameraPosition), right(1, 0, 0), up = glm::cross(right, forward);
  const float tanHalf = std::tan(0.5f * kVerticalFovDegrees * kPi / 180.0f);
  const float aspect = float(width) / float(height);
  auto rayThrough = [&](float x, float y) {  // film position in pixels, y down
    const float ndcX = 2.0f * x / float(width) - 1.0f, ndcY = 1.0f - 2.0f * y / float(height);
    return Ray{kCameraPosition, glm::normalize(forward + ndcX * tanHalf * aspect * right + ndcY * tanHalf * up)};
  };
  std::vector<GBufferTexel> gBuffer(static_cast<std::size_t>(width) * height, GBufferTexel{});
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const Ray ray = rayThrough(x + 0.5f, y + 0.5f);
      const float b = glm::dot(ray.origin, ray.direction);
      const float discriminant = b * b - (glm::dot(ray.origin, ray.origin) - 1.0f);
      if (discriminant < 0.0f) continue;  // coverage 0
      const vec3 p = ray.origin + (-b - std::sqrt(discriminant)) * ray.direction;
      const vec3 n = glm::normalize(p);
      const float phi = std::atan2(n.x, n.z), theta = std::acos(std::clamp(n.y, -1.0f, 1.0f));
      const vec2 uv((phi < 0.0f ? phi + 2.0f * kPi : phi) / (2.0f * kPi), theta / kPi);
      // dp/du = 2 pi sin(theta) t and dp/dv = pi (cos theta (sin phi, 0, cos phi) - sin theta y):
      // perpendicular, so dp projects on each alone. The bitangent cross(n, t) points to -v.
      const vec3 tangent(std::cos(phi), 0.0f, -std::sin(phi));
      const vec3 dpdvUnit(std::cos(theta) * std::sin(phi), -std::sin(theta), std::cos(theta) * std::cos(phi));
      const float dpduLength = 2.0f * kPi * std::max(std::sin(theta), 1e-3f), dpdvLength = kPi;
      auto duv = [&](const Ray& offset) {
        const float t = glm::dot(n, p - offset.origin) / glm::dot(n, offset.direction);
        const vec3 dp = offset.origin + t * offset.direction - p;
        return vec2(glm::dot(dp, tangent) / dpduLength, glm::dot(dp, dpdvUnit) / dpdvLength);
      };
      vec2 duvdx = duv(rayThrough(x + 1.5f, y + 0.5f)), duvdy = duv(rayThrough(x + 0.5f, y + 1.5f));
      if (!std::isfinite(duvdx.x + duvdx.y + duvdy.x + duvdy.y)) duvdx = duvdy = vec2(0.0f);  // grazing
      gBuffer[static_cast<std::size_t>(y) * width + x] = {vec4(p, 1.0f), vec4(n, 0.0f), vec4(tangent, 1.0f),
                                                          vec4(uv, duvdx), vec4(duvdy, 0.0f, 0.0f)};
    }
  }
  return gBuffer;
}

void check(VkResult result, const char* function) {
  if (result == VK_ERROR_INCOMPATIBLE_DRIVER) {
    throw glint::Error("Vulkan: no driver (Debian's mesa-vulkan-drivers has lavapipe, Vulkan on the CPU)");
  }
  if (result != VK_SUCCESS) {
    throw glint::Error(std::string("Vulkan: ") + function + " failed (VkResult " + std::to_string(result) + ")");
  }
}
// VK_CHECK(vkFunction, arguments...): calls it, and throws one line naming it when it fails.
#define VK_CHECK(function, ...) check(function(__VA_ARGS__), #function)

// One compute dispatch on the first Vulkan device with a compute queue (Mesa lavapipe on a machine
// without a GPU), every buffer in host-visible memory: enough for an example, not for speed.
class Vulkan {
 public:
  struct Buffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkBufferView view = VK_NULL_HANDLE;
    VkDeviceSize size = 0;
  };

  Vulkan() {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "glint_vulkan_deferred";
    app.apiVersion = VK_API_VERSION_1_1;
    VkInstanceCreateInfo instanceInfo{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    instanceInfo.pApplicationInfo = &app;
    VK_CHECK(vkCreateInstance, &instanceInfo, nullptr, &instance_);
    std::uint32_t count = 0;
    VK_CHECK(vkEnumeratePhysicalDevices, instance_, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    VK_CHECK(vkEnumeratePhysicalDevices, instance_, &count, devices.data());
    for (VkPhysicalDevice device : devices) {
      std::uint32_t familyCount = 0;
      vkGetPhysicalDeviceQueueFamilyProperties(device, &familyCount, nullptr);
      std::vector<VkQueueFamilyProperties> families(familyCount);
      vkGetPhysicalDeviceQueueFamilyProperties(device, &familyCount, families.data());
      for (std::uint32_t i = 0; i < familyCount && physical_ == VK_NULL_HANDLE; ++i) {
        if (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) physical_ = device, family_ = i;
      }
    }
    if (physical_ == VK_NULL_HANDLE) throw glint::Error("Vulkan: no device with a compute queue");
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queueInfo.queueFamilyIndex = family_;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;
    VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    deviceInfo.queueCreateInfoCount = 1;
    deviceInfo.pQueueCreateInfos = &queueInfo;
    VK_CHECK(vkCreateDevice, physical_, &deviceInfo, nullptr, &device_);
    vkGetDeviceQueue(device_, family_, 0, &queue_);
  }
  ~Vulkan() {
    if (device_) {
      for (Buffer& b : buffers_) {
        vkDestroyBufferView(device_, b.view, nullptr);
        vkDestroyBuffer(device_, b.buffer, nullptr);
        vkFreeMemory(device_, b.memory, nullptr);
      }
      vkDestroyDevice(device_, nullptr);
    }
    if (instance_) vkDestroyInstance(instance_, nullptr);
  }
  Vulkan(const Vulkan&) = delete;
  Vulkan& operator=(const Vulkan&) = delete;

  std::string deviceName() const {
    VkPhysicalDeviceProperties properties;
    vkGetPhysicalDeviceProperties(physical_, &properties);
    return properties.deviceName;
  }

  // A buffer holding `bytes` (or `size` zero bytes); a texel buffer gets a view of `format`.
  Buffer buffer(VkBufferUsageFlags usage, const void* bytes, VkDeviceSize size,
                VkFormat format = VK_FORMAT_UNDEFINED) {
    Buffer& b = buffers_.emplace_back();  // destroyed with the device, also if what follows throws
    b.size = size;
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage;
    VK_CHECK(vkCreateBuffer, device_, &info, nullptr, &b.buffer);
    VkMemoryRequirements needs;
    vkGetBufferMemoryRequirements(device_, b.buffer, &needs);
    VkPhysicalDeviceMemoryProperties memory;
    vkGetPhysicalDeviceMemoryProperties(physical_, &memory);
    const VkMemoryPropertyFlags wanted = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    VkMemoryAllocateInfo allocation{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    allocation.allocationSize = needs.size;
    allocation.memoryTypeIndex = memory.memoryTypeCount;
    for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
      if ((needs.memoryTypeBits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & wanted) == wanted) {
        allocation.memoryTypeIndex = i;
        break;
      }
    }
    if (allocation.memoryTypeIndex == memory.memoryTypeCount) throw glint::Error("Vulkan: no host-visible memory");
    VK_CHECK(vkAllocateMemory, device_, &allocation, nullptr, &b.memory);
    VK_CHECK(vkBindBufferMemory, device_, b.buffer, b.memory, 0);
    void* mapped = nullptr;
    VK_CHECK(vkMapMemory, device_, b.memory, 0, size, 0, &mapped);
    if (bytes) std::memcpy(mapped, bytes, size);
    else std::memset(mapped, 0, size);
    vkUnmapMemory(device_, b.memory);
    if (format != VK_FORMAT_UNDEFINED) {
      VkFormatProperties properties;
      vkGetPhysicalDeviceFormatProperties(physical_, format, &properties);
      if (!(properties.bufferFeatures & VK_FORMAT_FEATURE_UNIFORM_TEXEL_BUFFER_BIT)) {
        throw glint::Error("Vulkan: the device has no uniform texel buffers of format " + std::to_string(format));
      }
      VkBufferViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
      viewInfo.buffer = b.buffer;
      viewInfo.format = format;
      viewInfo.range = VK_WHOLE_SIZE;
      VK_CHECK(vkCreateBufferView, device_, &viewInfo, nullptr, &b.view);
    }
    return b;
  }

  std::vector<std::byte> read(const Buffer& b) const {
    std::vector<std::byte> bytes(b.size);
    void* mapped = nullptr;
    VK_CHECK(vkMapMemory, device_, b.memory, 0, b.size, 0, &mapped);
    std::memcpy(bytes.data(), mapped, b.size);
    vkUnmapMemory(device_, b.memory);
    return bytes;
  }

  // Runs `spirv`'s entry point main over groups workgroups with bindings[i] at binding i of set 0
  // (descriptor types[i]), and waits for it.
  void dispatch(const std::vector<std::uint32_t>& spirv, const std::vector<const Buffer*>& bindings,
                const std::vector<VkDescriptorType>& types, std::uint32_t groupsX, std::uint32_t groupsY) {
    std::vector<VkDescriptorSetLayoutBinding> layoutBindings;
    std::vector<VkDescriptorPoolSize> poolSizes;
    for (std::uint32_t i = 0; i < bindings.size(); ++i) {
      layoutBindings.push_back({i, types[i], 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
      poolSizes.push_back({types[i], 1});
    }
    VkDescriptorSetLayoutCreateInfo setLayoutInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    setLayoutInfo.bindingCount = static_cast<std::uint32_t>(layoutBindings.size());
    setLayoutInfo.pBindings = layoutBindings.data();
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VkPipelineLayout pipelineLayout = VK_NULL_HANDLE;
    VkShaderModule module = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkCommandPool commandPool = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    auto release = [&] {
      vkDestroyFence(device_, fence, nullptr);
      vkDestroyCommandPool(device_, commandPool, nullptr);
      vkDestroyDescriptorPool(device_, pool, nullptr);
      vkDestroyPipeline(device_, pipeline, nullptr);
      vkDestroyShaderModule(device_, module, nullptr);
      vkDestroyPipelineLayout(device_, pipelineLayout, nullptr);
      vkDestroyDescriptorSetLayout(device_, setLayout, nullptr);
    };
    try {
      VK_CHECK(vkCreateDescriptorSetLayout, device_, &setLayoutInfo, nullptr, &setLayout);
      VkPipelineLayoutCreateInfo pipelineLayoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
      pipelineLayoutInfo.setLayoutCount = 1;
      pipelineLayoutInfo.pSetLayouts = &setLayout;
      VK_CHECK(vkCreatePipelineLayout, device_, &pipelineLayoutInfo, nullptr, &pipelineLayout);
      VkShaderModuleCreateInfo moduleInfo{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
      moduleInfo.codeSize = spirv.size() * sizeof(std::uint32_t);
      moduleInfo.pCode = spirv.data();
      VK_CHECK(vkCreateShaderModule, device_, &moduleInfo, nullptr, &module);
      VkComputePipelineCreateInfo pipelineInfo{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
      pipelineInfo.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
      pipelineInfo.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
      pipelineInfo.stage.module = module;
      pipelineInfo.stage.pName = "main";
      pipelineInfo.layout = pipelineLayout;
      VK_CHECK(vkCreateComputePipelines, device_, VK_NULL_HANDLE, 1, &pipelineInfo, nullptr, &pipeline);

      VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
      poolInfo.maxSets = 1;
      poolInfo.poolSizeCount = static_cast<std::uint32_t>(poolSizes.size());
      poolInfo.pPoolSizes = poolSizes.data();
      VK_CHECK(vkCreateDescriptorPool, device_, &poolInfo, nullptr, &pool);
      VkDescriptorSetAllocateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
      setInfo.descriptorPool = pool;
      setInfo.descriptorSetCount = 1;
      setInfo.pSetLayouts = &setLayout;
      VkDescriptorSet set = VK_NULL_HANDLE;
      VK_CHECK(vkAllocateDescriptorSets, device_, &setInfo, &set);
      std::vector<VkDescriptorBufferInfo> bufferInfos(bindings.size());
      std::vector<VkWriteDescriptorSet> writes;
      for (std::uint32_t i = 0; i < bindings.size(); ++i) {
        VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        write.dstSet = set;
        write.dstBinding = i;
        write.descriptorCount = 1;
        write.descriptorType = types[i];
        bufferInfos[i] = {bindings[i]->buffer, 0, VK_WHOLE_SIZE};
        if (types[i] == VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER) write.pTexelBufferView = &bindings[i]->view;
        else write.pBufferInfo = &bufferInfos[i];
        writes.push_back(write);
      }
      vkUpdateDescriptorSets(device_, static_cast<std::uint32_t>(writes.size()), writes.data(), 0, nullptr);

      VkCommandPoolCreateInfo commandPoolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
      commandPoolInfo.queueFamilyIndex = family_;
      VK_CHECK(vkCreateCommandPool, device_, &commandPoolInfo, nullptr, &commandPool);
      VkCommandBufferAllocateInfo commandInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
      commandInfo.commandPool = commandPool;
      commandInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
      commandInfo.commandBufferCount = 1;
      VkCommandBuffer commands = VK_NULL_HANDLE;
      VK_CHECK(vkAllocateCommandBuffers, device_, &commandInfo, &commands);
      VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
      begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
      VK_CHECK(vkBeginCommandBuffer, commands, &begin);
      vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
      vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineLayout, 0, 1, &set, 0, nullptr);
      vkCmdDispatch(commands, groupsX, groupsY, 1);
      // The shader's writes made visible to the host's reads of the mapped memory.
      VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
      barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
      barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
      vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier,
                           0, nullptr, 0, nullptr);
      VK_CHECK(vkEndCommandBuffer, commands);
      VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
      VK_CHECK(vkCreateFence, device_, &fenceInfo, nullptr, &fence);
      VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
      submit.commandBufferCount = 1;
      submit.pCommandBuffers = &commands;
      VK_CHECK(vkQueueSubmit, queue_, 1, &submit, fence);
      VK_CHECK(vkWaitForFences, device_, 1, &fence, VK_TRUE, UINT64_MAX);
    } catch (...) {
      release();
      throw;
    }
    release();
  }

 private:
  VkInstance instance_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  std::uint32_t family_ = 0;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  std::deque<Buffer> buffers_;  // deque: references stay valid as it grows
};

// glint's file reader (a folder, a missing or unreadable file: one line naming it), then the
// module's shape: whole 32-bit words, SPIR-V's magic number and its five-word header.
std::vector<std::uint32_t> readSpirv(const std::string& path) {
  const std::vector<std::byte> bytes = glint::readFile(path);
  std::vector<std::uint32_t> words(bytes.size() / 4);
  std::memcpy(words.data(), bytes.data(), words.size() * 4);
  if (bytes.size() % 4 != 0 || words.size() < 5 || words[0] != 0x07230203u) {
    throw glint::Error(path + ": not a SPIR-V module");
  }
  return words;
}

struct Options {
  std::string output, dictionary, shader = GLINT_EXAMPLE_SPIRV;
  int size = 256;
};

int run(const Options& options) {
  const glint::Dictionary dictionary = glint::Dictionary::load(options.dictionary);
  const glint::DictionaryParameters& shape = dictionary.parameters();
  const std::vector<std::uint32_t> spirv = readSpirv(options.shader);
  const int size = options.size;
  const std::vector<GBufferTexel> gBuffer = fillGBuffer(size, size);
  const std::vector<std::uint16_t> pairs = dictionary.halfTexelPairs();  // (p[k], p[k + 1]), binary16
  Frame frame{};
  frame.material = sphereMaterial();
  frame.cameraPosition = vec4(kCameraPosition, 1.0f);
  frame.lightPosition = vec4(kLightPosition, 1.0f);
  frame.lightIntensity = vec4(kLightIntensity, 0.0f);
  frame.baseColour = vec4(kBaseColour, 0.0f);
  frame.dictionaryShape = {shape.numLevels, shape.numDistributions, shape.texelsPerDistribution, dictionary.numMips()};
  frame.dictionaryAlpha = shape.alpha;
  frame.dictionaryMipRowLength = dictionary.mipRowLength();
  frame.width = frame.height = static_cast<std::uint32_t>(size);

  Vulkan vulkan;
  std::printf("Vulkan device: %s\n", vulkan.deviceName().c_str());
  const Vulkan::Buffer gBufferBuffer =
      vulkan.buffer(VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gBuffer.data(), gBuffer.size() * sizeof(GBufferTexel));
  const Vulkan::Buffer radiance =
      vulkan.buffer(VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, nullptr, gBuffer.size() * sizeof(vec4));
  const Vulkan::Buffer dictionaryBuffer = vulkan.buffer(VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT, pairs.data(),
                                                        pairs.size() * sizeof(std::uint16_t), VK_FORMAT_R16G16_SFLOAT);
  const Vulkan::Buffer frameBuffer = vulkan.buffer(VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, &frame, sizeof frame);
  const std::uint32_t groups = static_cast<std::uint32_t>((size + 7) / 8);  // numthreads(8, 8, 1)
  try {
    vulkan.dispatch(spirv, {&gBufferBuffer, &radiance, &dictionaryBuffer, &frameBuffer},
                    {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                     VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                    groups, groups);
  } catch (const glint::Error& e) {
    // readSpirv checks the module's header only: a file cut short after it reaches the driver,
    // which refuses the module or its pipeline. Say which file.
    const std::string what = e.what();
    if (what.find("vkCreateShaderModule") != std::string::npos || what.find("vkCreateComputePipelines") != std::string::npos) {
      throw glint::Error(options.shader + ": the Vulkan driver refused the shader (" + what + ")");
    }
    throw;
  }

  const std::vector<std::byte> bytes = vulkan.read(radiance);
  glint::ImageRgbF image = glint::ImageRgbF::filled(size, size);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    vec4 value;
    std::memcpy(&value, bytes.data() + i * sizeof(vec4), sizeof(vec4));
    image.pixels[i] = vec3(value);
  }
  glint::writeImage(options.output, image);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const char* usage =
      "usage: glint_vulkan_deferred OUTPUT.{exr,png} --dictionary FILE.gdict [--size N] [--shader FILE.spv]";
  Options options;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string argument = argv[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw glint::Error(argument + " needs a value");
        return argv[++i];
      };
      if (argument == "-h" || argument == "--help") {
        std::printf("%s\n", usage);
        return 0;
      }
      if (argument == "--dictionary") options.dictionary = value();
      else if (argument == "--shader") options.shader = value();
      else if (argument == "--size") {
        const std::string text = value();
        char* end = nullptr;
        const long n = std::strtol(text.c_str(), &end, 10);
        if (text.empty() || *end != '\0' || n < 8 || n > 4096) {
          throw glint::Error("--size must be a whole number in [8, 4096], got '" + text + "'");
        }
        options.size = static_cast<int>(n);
      } else if (argument[0] != '-' && options.output.empty()) options.output = argument;
      else throw glint::Error("unknown argument '" + argument + "'");
    }
    if (options.output.empty() || options.dictionary.empty()) throw glint::Error(usage);
    glint::requireImageExtension(options.output);  // before the work, not after it
    return run(options);
  } catch (const glint::Error& e) {
    std::fprintf(stderr, "glint_vulkan_deferred: error: %s\n", e.what());
    return 1;
  }
}
