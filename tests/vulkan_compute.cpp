#include "vulkan_compute.h"

#include <cstdlib>
#include <fstream>
#include <memory>
#include <optional>

#include "glint/error.h"

namespace glint::test {

namespace {

const char* resultName(VkResult result) {
  switch (result) {
    case VK_ERROR_OUT_OF_HOST_MEMORY: return "VK_ERROR_OUT_OF_HOST_MEMORY";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
    case VK_ERROR_INITIALIZATION_FAILED: return "VK_ERROR_INITIALIZATION_FAILED";
    case VK_ERROR_DEVICE_LOST: return "VK_ERROR_DEVICE_LOST";
    case VK_ERROR_LAYER_NOT_PRESENT: return "VK_ERROR_LAYER_NOT_PRESENT";
    case VK_ERROR_EXTENSION_NOT_PRESENT: return "VK_ERROR_EXTENSION_NOT_PRESENT";
    case VK_ERROR_FEATURE_NOT_PRESENT: return "VK_ERROR_FEATURE_NOT_PRESENT";
    case VK_ERROR_INCOMPATIBLE_DRIVER: return "VK_ERROR_INCOMPATIBLE_DRIVER";
    case VK_ERROR_INVALID_SHADER_NV: return "VK_ERROR_INVALID_SHADER_NV";
    case VK_TIMEOUT: return "VK_TIMEOUT";
    default: return "VkResult error";
  }
}

// Throws glint::Error "Vulkan: <what> failed (<result>)" unless `result` is VK_SUCCESS.
void check(VkResult result, const char* what) {
  if (result != VK_SUCCESS) {
    throw Error(std::string("Vulkan: ") + what + " failed (" + resultName(result) + " " + std::to_string(result) + ")");
  }
}

// With GLINT_VULKAN_VALIDATION=1 the Khronos validation layer checks every call
// (vulkan-validationlayers) and each error it reports fails the running test.
bool validationRequested() {
  const char* value = std::getenv("GLINT_VULKAN_VALIDATION");
  return value && std::string(value) == "1";
}

VKAPI_ATTR VkBool32 VKAPI_CALL reportValidation(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                VkDebugUtilsMessageTypeFlagsEXT,
                                                const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
  if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ADD_FAILURE() << "Vulkan validation: " << data->pMessage;
  return VK_FALSE;
}

// The CPU device when there is one (lavapipe: the same on every machine, like llvmpipe for the
// OpenGL tests), else the first device.
VkPhysicalDevice choosePhysicalDevice(VkInstance instance) {
  std::uint32_t count = 0;
  check(vkEnumeratePhysicalDevices(instance, &count, nullptr), "vkEnumeratePhysicalDevices");
  std::vector<VkPhysicalDevice> devices(count);
  check(vkEnumeratePhysicalDevices(instance, &count, devices.data()), "vkEnumeratePhysicalDevices");
  if (devices.empty()) {
    throw Error("Vulkan: no device (install mesa-vulkan-drivers for lavapipe, or point VK_ICD_FILENAMES at its "
                "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json)");
  }
  for (VkPhysicalDevice device : devices) {
    VkPhysicalDeviceProperties properties;
    vkGetPhysicalDeviceProperties(device, &properties);
    if (properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU) return device;
  }
  return devices.front();
}

std::optional<std::uint32_t> computeQueueFamily(VkPhysicalDevice device) {
  std::uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  for (std::uint32_t i = 0; i < count; ++i) {
    if (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) return i;
  }
  return std::nullopt;
}

VkDescriptorType descriptorType(VulkanBuffer::Kind kind) {
  switch (kind) {
    case VulkanBuffer::Kind::storage: return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    case VulkanBuffer::Kind::uniform: return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    case VulkanBuffer::Kind::uniformTexel: return VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
  }
  return VK_DESCRIPTOR_TYPE_MAX_ENUM;
}

VkBufferUsageFlags bufferUsage(VulkanBuffer::Kind kind) {
  switch (kind) {
    case VulkanBuffer::Kind::storage: return VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    case VulkanBuffer::Kind::uniform: return VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
    case VulkanBuffer::Kind::uniformTexel: return VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
  }
  return 0;
}

// Everything one dispatch creates, destroyed when it ends (also when it throws).
struct DispatchObjects {
  VkDevice device;
  std::vector<VkBuffer> buffers;
  std::vector<VkDeviceMemory> memories;
  std::vector<VkBufferView> views;
  VkShaderModule module = VK_NULL_HANDLE;
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  VkPipelineLayout pipelineLayout = VK_NULL_HANDLE;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkDescriptorPool descriptorPool = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  VkCommandPool commandPool;
  VkCommandBuffer commands = VK_NULL_HANDLE;

  DispatchObjects(VkDevice d, VkCommandPool pool) : device(d), commandPool(pool) {}
  DispatchObjects(const DispatchObjects&) = delete;
  DispatchObjects& operator=(const DispatchObjects&) = delete;
  ~DispatchObjects() {
    if (commands) vkFreeCommandBuffers(device, commandPool, 1, &commands);
    vkDestroyFence(device, fence, nullptr);
    vkDestroyDescriptorPool(device, descriptorPool, nullptr);
    vkDestroyPipeline(device, pipeline, nullptr);
    vkDestroyPipelineLayout(device, pipelineLayout, nullptr);
    vkDestroyDescriptorSetLayout(device, setLayout, nullptr);
    vkDestroyShaderModule(device, module, nullptr);
    for (VkBufferView view : views) vkDestroyBufferView(device, view, nullptr);
    for (VkBuffer buffer : buffers) vkDestroyBuffer(device, buffer, nullptr);
    for (VkDeviceMemory memory : memories) vkFreeMemory(device, memory, nullptr);
  }
};

std::string gUnavailableReason;

}  // namespace

VulkanCompute::VulkanCompute() {
  try {
    create();
  } catch (const Error&) {
    release();
    throw;
  }
}

void VulkanCompute::create() {
  VkApplicationInfo application{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  application.pApplicationName = "glint_tests";
  application.apiVersion = VK_API_VERSION_1_1;
  VkInstanceCreateInfo instanceInfo{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  instanceInfo.pApplicationInfo = &application;
  const char* validationLayer = "VK_LAYER_KHRONOS_validation";
  const char* debugUtils = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
  const bool validate = validationRequested();
  if (validate) {
    instanceInfo.enabledLayerCount = 1;
    instanceInfo.ppEnabledLayerNames = &validationLayer;
    instanceInfo.enabledExtensionCount = 1;
    instanceInfo.ppEnabledExtensionNames = &debugUtils;
  }
  const VkResult created = vkCreateInstance(&instanceInfo, nullptr, &instance_);
  if (created == VK_ERROR_INCOMPATIBLE_DRIVER) {
    throw Error("Vulkan: no driver (install mesa-vulkan-drivers for lavapipe, or point VK_ICD_FILENAMES at its "
                "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json)");
  }
  if (validate && created == VK_ERROR_LAYER_NOT_PRESENT) {
    throw Error("Vulkan: GLINT_VULKAN_VALIDATION=1 needs the validation layer (vulkan-validationlayers)");
  }
  check(created, "vkCreateInstance");
  if (validate) {
    VkDebugUtilsMessengerCreateInfoEXT messengerInfo{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messengerInfo.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
    messengerInfo.pfnUserCallback = reportValidation;
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    check(create(instance_, &messengerInfo, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
  }

  physicalDevice_ = choosePhysicalDevice(instance_);
  VkPhysicalDeviceProperties properties;
  vkGetPhysicalDeviceProperties(physicalDevice_, &properties);
  deviceName_ = properties.deviceName;
  const std::optional<std::uint32_t> family = computeQueueFamily(physicalDevice_);
  if (!family) throw Error("Vulkan: " + deviceName_ + " has no compute queue");
  queueFamily_ = *family;

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = queueFamily_;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;
  VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  deviceInfo.queueCreateInfoCount = 1;
  deviceInfo.pQueueCreateInfos = &queueInfo;
  check(vkCreateDevice(physicalDevice_, &deviceInfo, nullptr, &device_), "vkCreateDevice");
  vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);
  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.queueFamilyIndex = queueFamily_;
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  check(vkCreateCommandPool(device_, &poolInfo, nullptr, &commandPool_), "vkCreateCommandPool");
}

VulkanCompute::~VulkanCompute() { release(); }

void VulkanCompute::release() {
  if (device_) {
    vkDestroyCommandPool(device_, commandPool_, nullptr);
    vkDestroyDevice(device_, nullptr);
  }
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    destroy(instance_, messenger_, nullptr);
  }
  if (instance_) vkDestroyInstance(instance_, nullptr);
  device_ = VK_NULL_HANDLE;
  messenger_ = VK_NULL_HANDLE;
  instance_ = VK_NULL_HANDLE;
}

VulkanCompute* VulkanCompute::shared() {
  // Created once; a failure is remembered so that every test skips with the same line.
  static const std::unique_ptr<VulkanCompute> instance = []() -> std::unique_ptr<VulkanCompute> {
    try {
      return std::unique_ptr<VulkanCompute>(new VulkanCompute());
    } catch (const Error& error) {
      gUnavailableReason = error.what();
      return nullptr;
    }
  }();
  return instance.get();
}

const std::string& VulkanCompute::unavailableReason() { return gUnavailableReason; }

std::uint32_t VulkanCompute::hostVisibleMemoryType(std::uint32_t allowedTypes) const {
  VkPhysicalDeviceMemoryProperties memory;
  vkGetPhysicalDeviceMemoryProperties(physicalDevice_, &memory);
  const VkMemoryPropertyFlags wanted = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
    if ((allowedTypes & (1u << i)) && (memory.memoryTypes[i].propertyFlags & wanted) == wanted) return i;
  }
  throw Error("Vulkan: " + deviceName_ + " has no host-visible, coherent memory for a buffer");
}

void VulkanCompute::dispatch(std::span<const std::uint32_t> spirv, std::span<VulkanBuffer> buffers,
                             std::uint32_t groupCount, const char* entryPoint) const {
  DispatchObjects objects(device_, commandPool_);

  // The buffers, in host-visible memory, filled with their bytes; a view over each texel buffer.
  std::vector<VkDescriptorSetLayoutBinding> layoutBindings;
  for (const VulkanBuffer& buffer : buffers) {
    const std::string name = "binding " + std::to_string(buffer.binding);
    if (buffer.bytes.empty()) throw Error("Vulkan: " + name + " is empty (Vulkan buffers hold at least one byte)");
    if (buffer.kind == VulkanBuffer::Kind::uniformTexel) {
      VkFormatProperties format;
      vkGetPhysicalDeviceFormatProperties(physicalDevice_, buffer.texelFormat, &format);
      if (!(format.bufferFeatures & VK_FORMAT_FEATURE_UNIFORM_TEXEL_BUFFER_BIT)) {
        throw Error("Vulkan: " + name + ": " + deviceName_ + " has no uniform texel buffers of VkFormat " +
                    std::to_string(buffer.texelFormat));
      }
    }
    VkBufferCreateInfo bufferInfo{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bufferInfo.size = buffer.bytes.size();
    bufferInfo.usage = bufferUsage(buffer.kind);
    bufferInfo.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VkBuffer handle;
    check(vkCreateBuffer(device_, &bufferInfo, nullptr, &handle), "vkCreateBuffer");
    objects.buffers.push_back(handle);
    VkMemoryRequirements requirements;
    vkGetBufferMemoryRequirements(device_, handle, &requirements);
    VkMemoryAllocateInfo allocation{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    allocation.allocationSize = requirements.size;
    allocation.memoryTypeIndex = hostVisibleMemoryType(requirements.memoryTypeBits);
    VkDeviceMemory memory;
    check(vkAllocateMemory(device_, &allocation, nullptr, &memory), "vkAllocateMemory");
    objects.memories.push_back(memory);
    check(vkBindBufferMemory(device_, handle, memory, 0), "vkBindBufferMemory");
    void* mapped = nullptr;
    check(vkMapMemory(device_, memory, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
    std::memcpy(mapped, buffer.bytes.data(), buffer.bytes.size());
    vkUnmapMemory(device_, memory);
    if (buffer.kind == VulkanBuffer::Kind::uniformTexel) {
      VkBufferViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
      viewInfo.buffer = handle;
      viewInfo.format = buffer.texelFormat;
      viewInfo.range = VK_WHOLE_SIZE;
      VkBufferView view;
      check(vkCreateBufferView(device_, &viewInfo, nullptr, &view), "vkCreateBufferView");
      objects.views.push_back(view);
    } else {
      objects.views.push_back(VK_NULL_HANDLE);
    }
    layoutBindings.push_back({buffer.binding, descriptorType(buffer.kind), 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
  }

  // The pipeline: the module's entry point over descriptor set 0.
  VkShaderModuleCreateInfo moduleInfo{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  moduleInfo.codeSize = spirv.size_bytes();
  moduleInfo.pCode = spirv.data();
  check(vkCreateShaderModule(device_, &moduleInfo, nullptr, &objects.module), "vkCreateShaderModule");
  VkDescriptorSetLayoutCreateInfo setLayoutInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setLayoutInfo.bindingCount = static_cast<std::uint32_t>(layoutBindings.size());
  setLayoutInfo.pBindings = layoutBindings.data();
  check(vkCreateDescriptorSetLayout(device_, &setLayoutInfo, nullptr, &objects.setLayout), "vkCreateDescriptorSetLayout");
  VkPipelineLayoutCreateInfo pipelineLayoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pipelineLayoutInfo.setLayoutCount = 1;
  pipelineLayoutInfo.pSetLayouts = &objects.setLayout;
  check(vkCreatePipelineLayout(device_, &pipelineLayoutInfo, nullptr, &objects.pipelineLayout), "vkCreatePipelineLayout");
  VkComputePipelineCreateInfo pipelineInfo{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  pipelineInfo.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  pipelineInfo.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  pipelineInfo.stage.module = objects.module;
  pipelineInfo.stage.pName = entryPoint;
  pipelineInfo.layout = objects.pipelineLayout;
  check(vkCreateComputePipelines(device_, VK_NULL_HANDLE, 1, &pipelineInfo, nullptr, &objects.pipeline),
        "vkCreateComputePipelines");

  // One descriptor set pointing at every buffer.
  std::vector<VkDescriptorPoolSize> poolSizes;
  for (const VkDescriptorSetLayoutBinding& binding : layoutBindings) poolSizes.push_back({binding.descriptorType, 1});
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = 1;
  poolInfo.poolSizeCount = static_cast<std::uint32_t>(poolSizes.size());
  poolInfo.pPoolSizes = poolSizes.data();
  check(vkCreateDescriptorPool(device_, &poolInfo, nullptr, &objects.descriptorPool), "vkCreateDescriptorPool");
  VkDescriptorSetAllocateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  setInfo.descriptorPool = objects.descriptorPool;
  setInfo.descriptorSetCount = 1;
  setInfo.pSetLayouts = &objects.setLayout;
  VkDescriptorSet set;
  check(vkAllocateDescriptorSets(device_, &setInfo, &set), "vkAllocateDescriptorSets");
  std::vector<VkDescriptorBufferInfo> bufferInfos(buffers.size());
  std::vector<VkWriteDescriptorSet> writes;
  for (std::size_t i = 0; i < buffers.size(); ++i) {
    bufferInfos[i] = {objects.buffers[i], 0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = set;
    write.dstBinding = buffers[i].binding;
    write.descriptorCount = 1;
    write.descriptorType = layoutBindings[i].descriptorType;
    if (buffers[i].kind == VulkanBuffer::Kind::uniformTexel) {
      write.pTexelBufferView = &objects.views[i];
    } else {
      write.pBufferInfo = &bufferInfos[i];
    }
    writes.push_back(write);
  }
  vkUpdateDescriptorSets(device_, static_cast<std::uint32_t>(writes.size()), writes.data(), 0, nullptr);

  // Record, submit, wait; the barrier makes the shader's writes visible to the host's reads.
  VkCommandBufferAllocateInfo commandInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  commandInfo.commandPool = commandPool_;
  commandInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  commandInfo.commandBufferCount = 1;
  check(vkAllocateCommandBuffers(device_, &commandInfo, &objects.commands), "vkAllocateCommandBuffers");
  VkCommandBuffer commands = objects.commands;
  VkCommandBufferBeginInfo beginInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  beginInfo.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(commands, &beginInfo), "vkBeginCommandBuffer");
  vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, objects.pipeline);
  vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, objects.pipelineLayout, 0, 1, &set, 0, nullptr);
  vkCmdDispatch(commands, groupCount, 1, 1);
  VkMemoryBarrier toHost{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  toHost.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost, 0,
                       nullptr, 0, nullptr);
  check(vkEndCommandBuffer(commands), "vkEndCommandBuffer");
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  check(vkCreateFence(device_, &fenceInfo, nullptr, &objects.fence), "vkCreateFence");
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &commands;
  check(vkQueueSubmit(queue_, 1, &submit, objects.fence), "vkQueueSubmit");
  check(vkWaitForFences(device_, 1, &objects.fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");

  for (std::size_t i = 0; i < buffers.size(); ++i) {
    if (buffers[i].kind != VulkanBuffer::Kind::storage) continue;
    void* mapped = nullptr;
    check(vkMapMemory(device_, objects.memories[i], 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
    std::memcpy(buffers[i].bytes.data(), mapped, buffers[i].bytes.size());
    vkUnmapMemory(device_, objects.memories[i]);
  }
}

std::vector<std::uint32_t> readSpirv(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  if (!file) throw Error(path.string() + ": cannot read the SPIR-V module");
  const std::streamsize size = file.tellg();
  constexpr std::uint32_t kSpirvMagic = 0x07230203;
  std::vector<std::uint32_t> words(static_cast<std::size_t>(size) / 4);
  file.seekg(0);
  file.read(reinterpret_cast<char*>(words.data()), static_cast<std::streamsize>(words.size() * 4));
  if (size % 4 != 0 || words.empty() || words[0] != kSpirvMagic) throw Error(path.string() + ": not a SPIR-V module");
  return words;
}

}  // namespace glint::test
