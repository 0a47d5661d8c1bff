// vplkit::parity's Vulkan target: see vulkan_compute.hpp.
#include "frontend/parity/vulkan_compute.hpp"

#define VK_NO_PROTOTYPES
#include <vulkan/vulkan.h>

#include <dlfcn.h>

#include <cstring>
#include <functional>
#include <memory>
#include <mutex>

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include "frontend/core/error.hpp"

namespace vplkit::parity::detail {

namespace {

// The entry points used, loaded through vkGetInstanceProcAddr (device functions too: the loader
// dispatches them).
#define VPLKIT_VULKAN_INSTANCE_FUNCTIONS(X)                                                                                           \
  X(vkDestroyInstance) X(vkEnumeratePhysicalDevices) X(vkGetPhysicalDeviceProperties) X(vkGetPhysicalDeviceQueueFamilyProperties)   \
  X(vkGetPhysicalDeviceMemoryProperties) X(vkCreateDevice) X(vkDestroyDevice) X(vkGetDeviceQueue) X(vkCreateBuffer) X(vkDestroyBuffer) \
  X(vkGetBufferMemoryRequirements) X(vkAllocateMemory) X(vkFreeMemory) X(vkBindBufferMemory) X(vkMapMemory) X(vkUnmapMemory)         \
  X(vkCreateShaderModule) X(vkDestroyShaderModule) X(vkCreateDescriptorSetLayout) X(vkDestroyDescriptorSetLayout)                    \
  X(vkCreatePipelineLayout) X(vkDestroyPipelineLayout) X(vkCreateComputePipelines) X(vkDestroyPipeline) X(vkCreateDescriptorPool)     \
  X(vkDestroyDescriptorPool) X(vkAllocateDescriptorSets) X(vkUpdateDescriptorSets) X(vkCreateCommandPool) X(vkDestroyCommandPool)     \
  X(vkAllocateCommandBuffers) X(vkBeginCommandBuffer) X(vkEndCommandBuffer) X(vkCmdBindPipeline) X(vkCmdBindDescriptorSets)           \
  X(vkCmdDispatch) X(vkCmdPipelineBarrier) X(vkQueueSubmit) X(vkCreateFence) X(vkDestroyFence) X(vkWaitForFences)

// A Vulkan info struct with its type set and every other member zero.
template <typename Info>
Info made(VkStructureType type) {
  Info info{};
  info.sType = type;
  return info;
}

std::string result_text(VkResult result) { return "VkResult " + std::to_string(static_cast<int>(result)); }

// The loader, the instance and the device, made once per process on first use and destroyed at
// exit. A failure is kept as the reason the target is unavailable.
class vulkan_device {
 public:
  static vulkan_device& get() {
    // Never destroyed, like the GL contexts: destroying the instance at exit makes the loader
    // unload the driver (lavapipe), and LeakSanitizer then cannot name the driver's own
    // process-lifetime caches (tests/sanitizer/lsan.supp: leak:libvulkan_lvp).
    static vulkan_device& device = *new vulkan_device;
    return device;
  }
  const std::string& unavailable() const { return unavailable_; }
  const std::string& name() const { return name_; }

#define VPLKIT_DECLARE(name) PFN_##name name = nullptr;
  VPLKIT_VULKAN_INSTANCE_FUNCTIONS(VPLKIT_DECLARE)
#undef VPLKIT_DECLARE

  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  std::uint32_t queue_family = 0;
  VkPhysicalDeviceMemoryProperties memory{};
  VkPhysicalDeviceLimits limits{};

  ~vulkan_device() {
    if (device) vkDestroyDevice(device, nullptr);
    if (instance_) vkDestroyInstance(instance_, nullptr);
    // The loader stays open: a driver's thread may still be ending at exit.
  }
  vulkan_device(const vulkan_device&) = delete;
  vulkan_device& operator=(const vulkan_device&) = delete;

 private:
  vulkan_device() {
    try {
      make();
    } catch (const error& failure) {
      unavailable_ = failure.what();
    }
  }

  void make() {
    loader_ = dlopen("libvulkan.so.1", RTLD_NOW | RTLD_LOCAL);
    if (!loader_) throw error("no Vulkan loader: dlopen(libvulkan.so.1) failed (Debian: libvulkan1)");
    auto get_instance_proc = reinterpret_cast<PFN_vkGetInstanceProcAddr>(dlsym(loader_, "vkGetInstanceProcAddr"));
    if (!get_instance_proc) throw error("libvulkan.so.1 has no vkGetInstanceProcAddr");
    auto create_instance = reinterpret_cast<PFN_vkCreateInstance>(get_instance_proc(VK_NULL_HANDLE, "vkCreateInstance"));
    auto application = made<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
    application.pApplicationName = "vplkit::parity";
    application.apiVersion = VK_API_VERSION_1_0;
    auto instance_info = made<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
    instance_info.pApplicationInfo = &application;
    if (const VkResult result = create_instance(&instance_info, nullptr, &instance_); result != VK_SUCCESS)
      throw error("vkCreateInstance failed (" + result_text(result) + (result == VK_ERROR_INCOMPATIBLE_DRIVER ? ": no Vulkan driver (ICD) is installed; Debian: mesa-vulkan-drivers for lavapipe)" : ")"));
#define VPLKIT_LOAD(name)                                                                 \
  name = reinterpret_cast<PFN_##name>(get_instance_proc(instance_, #name));               \
  if (!name) throw error("the Vulkan loader has no " #name);
    VPLKIT_VULKAN_INSTANCE_FUNCTIONS(VPLKIT_LOAD)
#undef VPLKIT_LOAD
    std::uint32_t count = 0;
    vkEnumeratePhysicalDevices(instance_, &count, nullptr);
    std::vector<VkPhysicalDevice> physical(count);
    if (count) vkEnumeratePhysicalDevices(instance_, &count, physical.data());
    // A GPU first, then any device (lavapipe is VK_PHYSICAL_DEVICE_TYPE_CPU), with a compute queue.
    VkPhysicalDevice chosen = VK_NULL_HANDLE;
    for (int pass = 0; pass < 2 && !chosen; ++pass)
      for (VkPhysicalDevice candidate : physical) {
        VkPhysicalDeviceProperties properties;
        vkGetPhysicalDeviceProperties(candidate, &properties);
        if (pass == 0 && properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU) continue;
        std::uint32_t families = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(candidate, &families, nullptr);
        std::vector<VkQueueFamilyProperties> family(families);
        vkGetPhysicalDeviceQueueFamilyProperties(candidate, &families, family.data());
        for (std::uint32_t f = 0; f < families && !chosen; ++f)
          if (family[f].queueFlags & VK_QUEUE_COMPUTE_BIT) {
            chosen = candidate;
            queue_family = f;
            limits = properties.limits;
            name_ = std::string(properties.deviceName) + ", Vulkan " + std::to_string(VK_API_VERSION_MAJOR(properties.apiVersion)) + "." +
                    std::to_string(VK_API_VERSION_MINOR(properties.apiVersion)) + "." + std::to_string(VK_API_VERSION_PATCH(properties.apiVersion));
          }
        if (chosen) break;
      }
    if (!chosen)
      throw error("no Vulkan device with a compute queue (" + std::to_string(count) +
                  " devices; Debian: mesa-vulkan-drivers brings lavapipe, a CPU device)");
    vkGetPhysicalDeviceMemoryProperties(chosen, &memory);
    const float priority = 1.0f;
    auto queue_info = made<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
    queue_info.queueFamilyIndex = queue_family;
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;
    auto device_info = made<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
    device_info.queueCreateInfoCount = 1;
    device_info.pQueueCreateInfos = &queue_info;
    if (const VkResult result = vkCreateDevice(chosen, &device_info, nullptr, &device); result != VK_SUCCESS)
      throw error("vkCreateDevice on " + name_ + " failed (" + result_text(result) + ")");
    vkGetDeviceQueue(device, queue_family, 0, &queue);
  }

  void* loader_ = nullptr;
  VkInstance instance_ = VK_NULL_HANDLE;
  std::string unavailable_;
  std::string name_;
};

vulkan_device& usable_device() {
  vulkan_device& vk = vulkan_device::get();
  if (!vk.unavailable().empty()) throw error("vplkit::parity target vulkan is unavailable: " + vk.unavailable());
  return vk;
}

// Cleanups run in reverse order of registration, also when a step throws.
class cleanups {
 public:
  ~cleanups() {
    for (auto at = steps_.rbegin(); at != steps_.rend(); ++at) (*at)();
  }
  void add(std::function<void()> step) { steps_.push_back(std::move(step)); }

 private:
  std::vector<std::function<void()>> steps_;
};

void check(VkResult result, const std::string& name, const char* call) {
  if (result != VK_SUCCESS) throw error("vplkit::parity vulkan run of " + name + ": " + call + " failed (" + result_text(result) + ")");
}

}  // namespace

std::string vulkan_unavailable() { return vulkan_device::get().unavailable(); }

std::string vulkan_device_name() { return usable_device().name(); }

vulkan_limits vulkan_device_limits() {
  const vulkan_device& vk = usable_device();
  return {vk.limits.maxPerStageDescriptorStorageBuffers, vk.limits.maxComputeWorkGroupCount[0]};
}

std::vector<std::uint32_t> compile_vulkan_compute(const std::string& name, const expanded_source& source) {
  // glslang's process-wide tables, made once (FinalizeProcess is not called: other glslang users
  // in the process may still need them).
  static const bool initialised = glslang::InitializeProcess();
  if (!initialised) throw error("vplkit::parity: glslang::InitializeProcess failed");
  // Numbered by place, as link_program numbers GL sources, so that map_compile_log finds the file
  // and line from the line glslang reports ("ERROR: 0:14: ...").
  const std::string text = compiled_text(source.text);
  const char* strings[] = {text.c_str()};
  glslang::TShader shader(EShLangCompute);
  shader.setStrings(strings, 1);
  shader.setEnvInput(glslang::EShSourceGlsl, EShLangCompute, glslang::EShClientVulkan, 100);
  shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_0);
  shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_0);
  const auto messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules);
  if (!shader.parse(GetDefaultResources(), 450, false, messages))
    throw error("vplkit::parity vulkan compute kernel " + name + ": GLSL compile error (glslang):\n" +
                map_compile_log(shader.getInfoLog(), source));
  glslang::TProgram program;
  program.addShader(&shader);
  if (!program.link(messages)) throw error("vplkit::parity vulkan compute kernel " + name + ": link error (glslang):\n" + std::string(program.getInfoLog()));
  std::vector<std::uint32_t> spirv;
  glslang::SpvOptions options;
  options.validate = true;
  glslang::GlslangToSpv(*program.getIntermediate(EShLangCompute), spirv, &options);
  if (spirv.empty()) throw error("vplkit::parity vulkan compute kernel " + name + ": glslang produced no SPIR-V");
  return spirv;
}

std::vector<std::vector<std::byte>> run_vulkan_compute(const std::string& name, const std::vector<std::uint32_t>& spirv,
                                                       const std::vector<vulkan_binding>& bindings, std::uint32_t groups) {
  vulkan_device& vk = usable_device();
  // One device, one queue: runs from several threads take turns.
  static std::mutex queue_mutex;
  const std::lock_guard<std::mutex> lock(queue_mutex);
  const VkDevice device = vk.device;
  cleanups cleanup;

  // Host-visible, coherent memory for every buffer: a parity run moves little data, and mapped
  // memory needs no staging copies (lavapipe's memory is all of this kind).
  std::vector<VkBuffer> buffers;
  std::vector<VkDeviceMemory> memories;
  std::vector<VkDescriptorSetLayoutBinding> layout_bindings;
  std::uint32_t storage_count = 0, uniform_count = 0;
  for (std::size_t i = 0; i < bindings.size(); ++i) {
    const vulkan_binding& binding = bindings[i];
    auto buffer_info = made<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    buffer_info.size = std::max<std::size_t>(binding.bytes.size(), 16);
    buffer_info.usage = binding.uniform ? VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT : VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    buffer_info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VkBuffer buffer = VK_NULL_HANDLE;
    check(vk.vkCreateBuffer(device, &buffer_info, nullptr, &buffer), name, "vkCreateBuffer");
    cleanup.add([&vk, device, buffer] { vk.vkDestroyBuffer(device, buffer, nullptr); });
    VkMemoryRequirements requirements;
    vk.vkGetBufferMemoryRequirements(device, buffer, &requirements);
    const VkMemoryPropertyFlags wanted = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    std::uint32_t type = vk.memory.memoryTypeCount;
    for (std::uint32_t t = 0; t < vk.memory.memoryTypeCount && type == vk.memory.memoryTypeCount; ++t)
      if ((requirements.memoryTypeBits & (1u << t)) && (vk.memory.memoryTypes[t].propertyFlags & wanted) == wanted) type = t;
    if (type == vk.memory.memoryTypeCount)
      throw error("vplkit::parity vulkan run of " + name + ": the device has no host-visible coherent memory for a buffer");
    auto allocate = made<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
    allocate.allocationSize = requirements.size;
    allocate.memoryTypeIndex = type;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    check(vk.vkAllocateMemory(device, &allocate, nullptr, &memory), name, "vkAllocateMemory");
    cleanup.add([&vk, device, memory] { vk.vkFreeMemory(device, memory, nullptr); });
    check(vk.vkBindBufferMemory(device, buffer, memory, 0), name, "vkBindBufferMemory");
    void* mapped = nullptr;
    check(vk.vkMapMemory(device, memory, 0, VK_WHOLE_SIZE, 0, &mapped), name, "vkMapMemory");
    std::memset(mapped, 0, static_cast<std::size_t>(requirements.size));
    if (!binding.bytes.empty()) std::memcpy(mapped, binding.bytes.data(), binding.bytes.size());
    vk.vkUnmapMemory(device, memory);
    buffers.push_back(buffer);
    memories.push_back(memory);
    const VkDescriptorType kind = binding.uniform ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    (binding.uniform ? uniform_count : storage_count) += 1;
    layout_bindings.push_back({static_cast<std::uint32_t>(i), kind, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
  }

  auto set_layout_info = made<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
  set_layout_info.bindingCount = static_cast<std::uint32_t>(layout_bindings.size());
  set_layout_info.pBindings = layout_bindings.data();
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  check(vk.vkCreateDescriptorSetLayout(device, &set_layout_info, nullptr, &set_layout), name, "vkCreateDescriptorSetLayout");
  cleanup.add([&vk, device, set_layout] { vk.vkDestroyDescriptorSetLayout(device, set_layout, nullptr); });
  auto pipeline_layout_info = made<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
  pipeline_layout_info.setLayoutCount = 1;
  pipeline_layout_info.pSetLayouts = &set_layout;
  VkPipelineLayout pipeline_layout = VK_NULL_HANDLE;
  check(vk.vkCreatePipelineLayout(device, &pipeline_layout_info, nullptr, &pipeline_layout), name, "vkCreatePipelineLayout");
  cleanup.add([&vk, device, pipeline_layout] { vk.vkDestroyPipelineLayout(device, pipeline_layout, nullptr); });

  auto module_info = made<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
  module_info.codeSize = spirv.size() * sizeof(std::uint32_t);
  module_info.pCode = spirv.data();
  VkShaderModule module = VK_NULL_HANDLE;
  check(vk.vkCreateShaderModule(device, &module_info, nullptr, &module), name, "vkCreateShaderModule");
  cleanup.add([&vk, device, module] { vk.vkDestroyShaderModule(device, module, nullptr); });
  auto pipeline_info = made<VkComputePipelineCreateInfo>(VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO);
  pipeline_info.stage = made<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO);
  pipeline_info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  pipeline_info.stage.module = module;
  pipeline_info.stage.pName = "main";
  pipeline_info.layout = pipeline_layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  check(vk.vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &pipeline_info, nullptr, &pipeline), name, "vkCreateComputePipelines");
  cleanup.add([&vk, device, pipeline] { vk.vkDestroyPipeline(device, pipeline, nullptr); });

  std::vector<VkDescriptorPoolSize> pool_sizes;
  if (storage_count) pool_sizes.push_back({VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, storage_count});
  if (uniform_count) pool_sizes.push_back({VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, uniform_count});
  auto pool_info = made<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
  pool_info.maxSets = 1;
  pool_info.poolSizeCount = static_cast<std::uint32_t>(pool_sizes.size());
  pool_info.pPoolSizes = pool_sizes.data();
  VkDescriptorPool pool = VK_NULL_HANDLE;
  check(vk.vkCreateDescriptorPool(device, &pool_info, nullptr, &pool), name, "vkCreateDescriptorPool");
  cleanup.add([&vk, device, pool] { vk.vkDestroyDescriptorPool(device, pool, nullptr); });
  auto set_info = made<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
  set_info.descriptorPool = pool;
  set_info.descriptorSetCount = 1;
  set_info.pSetLayouts = &set_layout;
  VkDescriptorSet set = VK_NULL_HANDLE;
  check(vk.vkAllocateDescriptorSets(device, &set_info, &set), name, "vkAllocateDescriptorSets");
  std::vector<VkDescriptorBufferInfo> buffer_infos(bindings.size());
  std::vector<VkWriteDescriptorSet> writes(bindings.size());
  for (std::size_t i = 0; i < bindings.size(); ++i) {
    buffer_infos[i] = {buffers[i], 0, VK_WHOLE_SIZE};
    writes[i] = made<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    writes[i].dstSet = set;
    writes[i].dstBinding = static_cast<std::uint32_t>(i);
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = layout_bindings[i].descriptorType;
    writes[i].pBufferInfo = &buffer_infos[i];
  }
  vk.vkUpdateDescriptorSets(device, static_cast<std::uint32_t>(writes.size()), writes.data(), 0, nullptr);

  auto command_pool_info = made<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
  command_pool_info.queueFamilyIndex = vk.queue_family;
  VkCommandPool command_pool = VK_NULL_HANDLE;
  check(vk.vkCreateCommandPool(device, &command_pool_info, nullptr, &command_pool), name, "vkCreateCommandPool");
  cleanup.add([&vk, device, command_pool] { vk.vkDestroyCommandPool(device, command_pool, nullptr); });
  auto command_info = made<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
  command_info.commandPool = command_pool;
  command_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  command_info.commandBufferCount = 1;
  VkCommandBuffer commands = VK_NULL_HANDLE;
  check(vk.vkAllocateCommandBuffers(device, &command_info, &commands), name, "vkAllocateCommandBuffers");
  auto begin = made<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vk.vkBeginCommandBuffer(commands, &begin), name, "vkBeginCommandBuffer");
  vk.vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
  vk.vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_layout, 0, 1, &set, 0, nullptr);
  vk.vkCmdDispatch(commands, groups, 1, 1);
  // The shader's writes made visible to the host's reads of the mapped memory.
  auto barrier = made<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vk.vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0, nullptr, 0, nullptr);
  check(vk.vkEndCommandBuffer(commands), name, "vkEndCommandBuffer");
  auto fence_info = made<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
  VkFence fence = VK_NULL_HANDLE;
  check(vk.vkCreateFence(device, &fence_info, nullptr, &fence), name, "vkCreateFence");
  cleanup.add([&vk, device, fence] { vk.vkDestroyFence(device, fence, nullptr); });
  auto submit = made<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &commands;
  check(vk.vkQueueSubmit(vk.queue, 1, &submit, fence), name, "vkQueueSubmit");
  check(vk.vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), name, "vkWaitForFences");

  std::vector<std::vector<std::byte>> results;
  for (std::size_t i = 0; i < bindings.size(); ++i) {
    if (!bindings[i].read_back) continue;
    void* mapped = nullptr;
    check(vk.vkMapMemory(device, memories[i], 0, VK_WHOLE_SIZE, 0, &mapped), name, "vkMapMemory");
    std::vector<std::byte> bytes(bindings[i].bytes.size());
    std::memcpy(bytes.data(), mapped, bytes.size());
    vk.vkUnmapMemory(device, memories[i]);
    results.push_back(std::move(bytes));
  }
  return results;
}

}  // namespace vplkit::parity::detail
