#pragma once
// The Vulkan instance, the chosen physical device, one compute queue and the objects every
// pass shares (command pool, descriptor pool). Headless unless a window asks for a surface (the
// viewer): then the queue must also present to it and VK_KHR_swapchain is enabled.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace mixtrace {

struct ContextOptions {
  std::string device;       // --device: index or name substring (vulkan/device_choice.h)
  bool validation = false;  // enable VK_LAYER_KHRONOS_validation and count its errors
  // Presentation: the instance extensions the window system needs, and what makes the window's
  // surface once the instance exists (the context owns and destroys it).
  std::vector<std::string> instanceExtensions;
  std::function<VkSurfaceKHR(VkInstance)> makeSurface;
  // false: do not enable VK_EXT_shader_atomic_float even where the device has it, as if it had
  // not (tests of that path; the environment variable MIXTRACE_DISABLE_FLOAT_ATOMICS=1 does the
  // same for the binary).
  bool floatAtomics = true;
};

// `mixtrace --list-devices`: per device its index, name, then type, driver, Vulkan version and
// whether mixtrace can run on it (and with float atomics). Needs a Vulkan driver, not a device.
std::string describeVulkanDevices();

class VulkanContext {
 public:
  explicit VulkanContext(const ContextOptions& options);
  ~VulkanContext();
  VulkanContext(const VulkanContext&) = delete;
  VulkanContext& operator=(const VulkanContext&) = delete;

  VkDevice device() const { return device_; }
  VkPhysicalDevice physicalDevice() const { return physical_; }
  VkSurfaceKHR surface() const { return surface_; }   // VK_NULL_HANDLE when headless
  VkQueue queue() const { return queue_; }
  uint32_t queueFamily() const { return queueFamily_; }
  VkCommandPool commandPool() const { return commandPool_; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  std::string deviceName() const { return properties_.deviceName; }
  double timestampPeriodNs() const { return properties_.limits.timestampPeriod; }
  bool timestampsSupported() const { return timestampValidBits_ > 0; }
  uint64_t maxStorageBufferRange() const { return properties_.limits.maxStorageBufferRange; }
  // VK_EXT_shader_atomic_float's shaderBufferFloat32AtomicAdd, enabled (when present and not
  // disabled by ContextOptions::floatAtomics); without it the pipelines that gather CMS
  // statistics add them with compare-and-swap loops, and no pipeline may use the capability.
  bool floatAtomics() const { return floatAtomics_; }

  // Validation messages of severity error seen so far (0 when validation is off).
  uint32_t validationErrors() const;

  // Records with `record`, submits, waits. For set-up copies and tests.
  template <class F> void submitAndWait(F&& record);
  VkCommandBuffer beginOneShot();
  // A primary command buffer from the shared pool, and an unsignalled fence (the caller frees them).
  VkCommandBuffer allocateCommandBuffer();
  VkFence createFence();
  void endOneShotAndWait(VkCommandBuffer cmd);

 private:
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t queueFamily_ = 0;
  uint32_t timestampValidBits_ = 0;
  bool floatAtomics_ = false;
  VkCommandPool commandPool_ = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties_{};
};

template <class F> void VulkanContext::submitAndWait(F&& record) {
  VkCommandBuffer cmd = beginOneShot();
  record(cmd);
  endOneShotAndWait(cmd);
}

}  // namespace mixtrace
