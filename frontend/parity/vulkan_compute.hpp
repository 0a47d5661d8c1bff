// vplkit::parity's Vulkan target (frontend/parity/vulkan_compute.cpp): GLSL compiled to SPIR-V
// by glslang at run time, run as a compute shader on the first Vulkan device with a compute
// queue (Mesa's lavapipe on a machine without a GPU), storage and uniform buffers in one
// descriptor set. The Vulkan loader is opened with dlopen, so that a program linked with
// vplkit::parity starts, and its GL targets run, on a machine without libvulkan1: the Vulkan
// target is then unavailable with a reason, not a failure to load.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <vplkit/gl/program.hpp>

namespace vplkit::parity::detail {

/// Empty when a Vulkan device with a compute queue is there; else why not, naming the Debian
/// package that brings what is missing (libvulkan1, mesa-vulkan-drivers).
std::string vulkan_unavailable();

/// The device the runs use: "llvmpipe (LLVM 15.0.6, 256 bits), Vulkan 1.3.230". Throws with
/// vulkan_unavailable's reason when there is none.
std::string vulkan_device_name();

/// The SPIR-V of an expanded `#version 450` compute shader (Vulkan 1.0 rules). A compile or link
/// error throws vplkit::error naming `name` and, per message, the file and line it came from.
std::vector<std::uint32_t> compile_vulkan_compute(const std::string& name, const expanded_source& source);

/// One binding of set 0, in binding order: a storage buffer or a uniform buffer holding `bytes`.
struct vulkan_binding {
  bool uniform = false;
  std::vector<std::byte> bytes;
  bool read_back = false;  ///< an output: its bytes after the dispatch come back
};

/// Dispatches `groups` work groups of the module's compute entry point `main` once and returns,
/// in binding order, the bytes of every binding marked read_back. Throws vplkit::error naming
/// `name` and the failing Vulkan call with its VkResult.
std::vector<std::vector<std::byte>> run_vulkan_compute(const std::string& name, const std::vector<std::uint32_t>& spirv,
                                                       const std::vector<vulkan_binding>& bindings, std::uint32_t groups);

/// The device's maxPerStageDescriptorStorageBuffers and maxComputeWorkGroupCount[0].
struct vulkan_limits {
  std::uint32_t storage_buffers = 0;
  std::uint32_t work_groups = 0;
};
vulkan_limits vulkan_device_limits();

}  // namespace vplkit::parity::detail
