#pragma once
// The window's swapchain. The viewer never renders into it: the display pass writes packed 8-bit
// pixels into a storage buffer, and each frame that buffer is copied into the acquired image and
// presented (transfer usage only, which every presenting driver offers; no storage images).
// One frame in flight: simple, and the path tracing dominates a frame anyway.
#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

namespace mixtrace {

class Buffer;
class VulkanContext;

class Swapchain {
 public:
  Swapchain(VulkanContext& ctx, uint32_t width, uint32_t height);
  ~Swapchain();
  Swapchain(const Swapchain&) = delete;
  Swapchain& operator=(const Swapchain&) = delete;

  // After a resize (or an out-of-date swapchain): new images of the window's current size.
  void recreate(uint32_t width, uint32_t height);
  VkExtent2D extent() const { return extent_; }
  bool redFirst() const { return redFirst_; }   // R8G8B8A8 (else B8G8R8A8)

  // Runs `record` (which records the display passes into the command buffer), then copies
  // `pixels` into the next image and presents it. False when the swapchain must be recreated.
  template <class F> bool present(const Buffer& pixels, F&& record);

 private:
  bool acquire(uint32_t* index);
  bool submitAndPresent(const Buffer& pixels, uint32_t index);
  void create(uint32_t width, uint32_t height);
  void destroy();

  VulkanContext& ctx_;
  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  VkExtent2D extent_{0, 0};
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  bool redFirst_ = false;
  std::vector<VkImage> images_;
  std::vector<VkSemaphore> rendered_;   // per image: the copy is done, present may read it
  VkSemaphore acquired_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
};

template <class F> bool Swapchain::present(const Buffer& pixels, F&& record) {
  uint32_t index = 0;
  if (!acquire(&index)) return false;
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkResetCommandBuffer(cmd_, 0);
  vkBeginCommandBuffer(cmd_, &bi);
  record(cmd_);
  return submitAndPresent(pixels, index);
}

}  // namespace mixtrace
