#include "vulkan/context.h"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "util/error.h"
#include "util/log.h"
#include "vulkan/check.h"
#include "vulkan/denormal_mode.h"
#include "vulkan/device_choice.h"

namespace mixtrace {
namespace {

std::atomic<uint32_t> gValidationErrors{0};

VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                   VkDebugUtilsMessageTypeFlagsEXT,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                   void*) {
  if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
    // The first few in full; a broken recording repeats the same error thousands of times.
    if (gValidationErrors++ < 5) std::fprintf(stderr, "mixtrace: validation error: %s\n", data->pMessage);
  } else if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
    std::fprintf(stderr, "mixtrace: validation warning: %s\n", data->pMessage);
  }
  return VK_FALSE;
}

bool hasLayer(const char* name) {
  uint32_t n = 0;
  vkEnumerateInstanceLayerProperties(&n, nullptr);
  std::vector<VkLayerProperties> layers(n);
  vkEnumerateInstanceLayerProperties(&n, layers.data());
  for (auto& l : layers)
    if (std::strcmp(l.layerName, name) == 0) return true;
  return false;
}

// A queue family with compute and, given a surface, presentation to it.
int computeQueueFamily(VkPhysicalDevice pd, uint32_t* timestampBits, VkSurfaceKHR surface = VK_NULL_HANDLE) {
  uint32_t n = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, nullptr);
  std::vector<VkQueueFamilyProperties> families(n);
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, families.data());
  for (uint32_t i = 0; i < n; ++i) {
    VkBool32 presents = VK_TRUE;
    if (surface) vkGetPhysicalDeviceSurfaceSupportKHR(pd, i, surface, &presents);
    if ((families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) && presents) {
      *timestampBits = families[i].timestampValidBits;
      return int(i);
    }
  }
  return -1;
}

bool hasDeviceExtension(VkPhysicalDevice pd, const char* name) {
  uint32_t n = 0;
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> ext(n);
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, ext.data());
  for (auto& e : ext)
    if (std::strcmp(e.extensionName, name) == 0) return true;
  return false;
}

// Float atomics (VK_EXT_shader_atomic_float) for the CMS cell statistics: optional.
bool supportsFloatAtomics(VkPhysicalDevice pd) {
  if (!hasDeviceExtension(pd, VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME)) return false;
  VkPhysicalDeviceShaderAtomicFloatFeaturesEXT af{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT};
  VkPhysicalDeviceFeatures2 f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &af};
  vkGetPhysicalDeviceFeatures2(pd, &f);
  return af.shaderBufferFloat32AtomicAdd == VK_TRUE;
}

std::string versionText(uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
         std::to_string(VK_API_VERSION_PATCH(v));
}

// Why the device cannot run mixtrace (the features the shaders rely on, and presenting to the
// viewer's window when there is one); empty when it can.
std::string unusableReason(VkPhysicalDevice pd, VkSurfaceKHR surface) {
  VkPhysicalDeviceProperties p;
  vkGetPhysicalDeviceProperties(pd, &p);
  if (p.apiVersion < VK_API_VERSION_1_2) return "needs Vulkan 1.2, has " + versionText(p.apiVersion);
  uint32_t tsBits = 0;
  if (computeQueueFamily(pd, &tsBits, surface) < 0)
    return surface ? "no compute queue that presents to the window" : "no compute queue";
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceFeatures2 f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f12};
  vkGetPhysicalDeviceFeatures2(pd, &f);
  if (!f12.scalarBlockLayout) return "no scalarBlockLayout";
  if (!f.features.shaderInt64 || !f12.shaderBufferInt64Atomics) return "no 64-bit integer atomics";
  // Subgroup ballots and sums: the queues and the fused kernel's ray counters take one atomic per
  // subgroup (shaders/gpu/queue_append.glsl, shaders/wavefront/fused.comp).
  VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
  VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &subgroup};
  vkGetPhysicalDeviceProperties2(pd, &p2);
  const VkSubgroupFeatureFlags needed =
      VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_BALLOT_BIT | VK_SUBGROUP_FEATURE_ARITHMETIC_BIT;
  if (!(subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) || (subgroup.supportedOperations & needed) != needed)
    return "no subgroup ballots and sums in compute shaders";
  if (surface && !hasDeviceExtension(pd, VK_KHR_SWAPCHAIN_EXTENSION_NAME)) return "no VK_KHR_swapchain";
  return "";
}

DeviceCandidate describeCandidate(VkPhysicalDevice pd, VkSurfaceKHR surface) {
  VkPhysicalDeviceProperties p;
  vkGetPhysicalDeviceProperties(pd, &p);
  return {p.deviceName, p.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, unusableReason(pd, surface)};
}

const char* typeText(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
  }
}

// "llvmpipe (Mesa 22.3.6 (LLVM 15.0.6))": VkPhysicalDeviceDriverProperties, core in Vulkan 1.2.
std::string driverText(VkPhysicalDevice pd, const VkPhysicalDeviceProperties& p) {
  if (p.apiVersion < VK_API_VERSION_1_2 && !hasDeviceExtension(pd, VK_KHR_DRIVER_PROPERTIES_EXTENSION_NAME))
    return "unknown (driver version " + std::to_string(p.driverVersion) + ")";
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &driver};
  vkGetPhysicalDeviceProperties2(pd, &p2);
  std::string text = driver.driverName;
  if (driver.driverInfo[0]) text += std::string(" (") + driver.driverInfo + ")";
  return text;
}

// MIXTRACE_DISABLE_FLOAT_ATOMICS=1: behave as on a device without VK_EXT_shader_atomic_float (the
// extension is not enabled), so that path is tested on devices that have it.
bool floatAtomicsDisabledByEnvironment() {
  const char* value = std::getenv("MIXTRACE_DISABLE_FLOAT_ATOMICS");
  return value && std::strcmp(value, "") != 0 && std::strcmp(value, "0") != 0;
}

VkInstance createInstance(const std::vector<const char*>& layers, const std::vector<const char*>& extensions) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "mixtrace";
  app.apiVersion = VK_API_VERSION_1_2;
  VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ici.pApplicationInfo = &app;
  ici.enabledLayerCount = uint32_t(layers.size());
  ici.ppEnabledLayerNames = layers.data();
  ici.enabledExtensionCount = uint32_t(extensions.size());
  ici.ppEnabledExtensionNames = extensions.data();
  VkInstance instance = VK_NULL_HANDLE;
  VkResult r = vkCreateInstance(&ici, nullptr, &instance);
  if (r == VK_ERROR_INCOMPATIBLE_DRIVER || r == VK_ERROR_INITIALIZATION_FAILED)
    throw Error("no Vulkan driver found (install mesa-vulkan-drivers for the CPU driver lavapipe, or a GPU driver)");
  vkCheck(r, "vkCreateInstance");
  return instance;
}

std::vector<VkPhysicalDevice> physicalDevices(VkInstance instance) {
  uint32_t count = 0;
  VkResult r = vkEnumeratePhysicalDevices(instance, &count, nullptr);
  if (r != VK_SUCCESS || count == 0)
    throw Error("no Vulkan device found (install mesa-vulkan-drivers for the CPU driver lavapipe, or a GPU driver)");
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance, &count, devices.data());
  return devices;
}

}  // namespace

VulkanContext::VulkanContext(const ContextOptions& options) {
  // A CPU driver's worker threads, started from here, take this thread's floating-point mode
  // (vulkan/denormal_mode.h): they flush denormals; this thread keeps its own mode afterwards.
  FlushDenormalsInScope flushInDriverThreads;
  std::vector<const char*> layers, extensions;
  if (options.validation) {
    if (hasLayer("VK_LAYER_KHRONOS_validation")) {
      layers.push_back("VK_LAYER_KHRONOS_validation");
      extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    } else {
      warn("--validation: VK_LAYER_KHRONOS_validation is not installed (package vulkan-validationlayers)");
    }
  }
  for (const std::string& e : options.instanceExtensions) extensions.push_back(e.c_str());
  instance_ = createInstance(layers, extensions);

  if (!layers.empty()) {
    VkDebugUtilsMessengerCreateInfoEXT mci{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    mci.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT;
    mci.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                      VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    mci.pfnUserCallback = onValidationMessage;
    auto create = (PFN_vkCreateDebugUtilsMessengerEXT)vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT");
    if (create) vkCheck(create(instance_, &mci, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
  }

  if (options.makeSurface) surface_ = options.makeSurface(instance_);

  const std::vector<VkPhysicalDevice> devices = physicalDevices(instance_);

  // --device: an index or a name substring (vulkan/device_choice.h); otherwise prefer a discrete GPU.
  std::vector<DeviceCandidate> candidates;
  for (VkPhysicalDevice pd : devices) candidates.push_back(describeCandidate(pd, surface_));
  const size_t chosen = chooseDevice(options.device, candidates);
  physical_ = devices[chosen];
  vkGetPhysicalDeviceProperties(physical_, &properties_);
  queueFamily_ = uint32_t(computeQueueFamily(physical_, &timestampValidBits_, surface_));

  float priority = 1.0f;
  VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qci.queueFamilyIndex = queueFamily_;
  qci.queueCount = 1;
  qci.pQueuePriorities = &priority;
  // Scalar block layout: one struct layout for C++ and GLSL. 64-bit atomics: the CMS cell table.
  floatAtomics_ = options.floatAtomics && !floatAtomicsDisabledByEnvironment() && supportsFloatAtomics(physical_);
  VkPhysicalDeviceShaderAtomicFloatFeaturesEXT af{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT};
  af.shaderBufferFloat32AtomicAdd = VK_TRUE;
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, floatAtomics_ ? &af : nullptr};
  f12.scalarBlockLayout = VK_TRUE;
  f12.shaderBufferInt64Atomics = VK_TRUE;
  VkPhysicalDeviceFeatures2 f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f12};
  f.features.shaderInt64 = VK_TRUE;
  VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  dci.pNext = &f;
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qci;
  std::vector<const char*> deviceExtensions;
  if (floatAtomics_) deviceExtensions.push_back(VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME);
  if (surface_) deviceExtensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  dci.enabledExtensionCount = uint32_t(deviceExtensions.size());
  dci.ppEnabledExtensionNames = deviceExtensions.data();
  vkCheck(vkCreateDevice(physical_, &dci, nullptr, &device_), "vkCreateDevice");
  vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);

  VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pci.queueFamilyIndex = queueFamily_;
  vkCheck(vkCreateCommandPool(device_, &pci, nullptr, &commandPool_), "vkCreateCommandPool");
}

VulkanContext::~VulkanContext() {
  if (device_) {
    vkDeviceWaitIdle(device_);
    vkDestroyCommandPool(device_, commandPool_, nullptr);
    vkDestroyDevice(device_, nullptr);
  }
  if (surface_) vkDestroySurfaceKHR(instance_, surface_, nullptr);
  if (messenger_) {
    auto destroy = (PFN_vkDestroyDebugUtilsMessengerEXT)vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT");
    if (destroy) destroy(instance_, messenger_, nullptr);
  }
  if (instance_) vkDestroyInstance(instance_, nullptr);
}

std::string describeVulkanDevices() {
  const VkInstance instance = createInstance({}, {});
  std::string text;
  try {
    const std::vector<VkPhysicalDevice> devices = physicalDevices(instance);
    for (size_t i = 0; i < devices.size(); ++i) {
      VkPhysicalDeviceProperties p;
      vkGetPhysicalDeviceProperties(devices[i], &p);
      const std::string why = unusableReason(devices[i], VK_NULL_HANDLE);
      text += std::to_string(i) + ": " + p.deviceName + "\n   " + typeText(p.deviceType) + ", driver " +
              driverText(devices[i], p) + ", Vulkan " + versionText(p.apiVersion) + ", " +
              (why.empty() ? std::string("usable") : "cannot run mixtrace: " + why) +
              (why.empty() ? (supportsFloatAtomics(devices[i]) ? ", float atomics" : ", no float atomics") : "") + "\n";
    }
  } catch (...) {
    vkDestroyInstance(instance, nullptr);
    throw;
  }
  vkDestroyInstance(instance, nullptr);
  return text;
}

uint32_t VulkanContext::validationErrors() const { return gValidationErrors.load(); }

VkCommandBuffer VulkanContext::allocateCommandBuffer() {
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = commandPool_;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cmd;
  vkCheck(vkAllocateCommandBuffers(device_, &ai, &cmd), "vkAllocateCommandBuffers");
  return cmd;
}

VkFence VulkanContext::createFence() {
  VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence;
  vkCheck(vkCreateFence(device_, &fci, nullptr, &fence), "vkCreateFence");
  return fence;
}

VkCommandBuffer VulkanContext::beginOneShot() {
  VkCommandBuffer cmd = allocateCommandBuffer();
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkBeginCommandBuffer(cmd, &bi);
  return cmd;
}

void VulkanContext::endOneShotAndWait(VkCommandBuffer cmd) {
  vkEndCommandBuffer(cmd);
  VkFence fence = createFence();
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  VkResult r = vkQueueSubmit(queue_, 1, &si, fence);
  if (r == VK_SUCCESS) r = vkWaitForFences(device_, 1, &fence, VK_TRUE, UINT64_MAX);
  vkDestroyFence(device_, fence, nullptr);
  vkFreeCommandBuffers(device_, commandPool_, 1, &cmd);
  vkCheck(r, "vkQueueSubmit");
}

}  // namespace mixtrace
