#include "viewer/swapchain.h"

#include <algorithm>

#include "util/error.h"
#include "vulkan/buffer.h"
#include "vulkan/check.h"
#include "vulkan/context.h"

namespace mixtrace {

Swapchain::Swapchain(VulkanContext& ctx, uint32_t width, uint32_t height) : ctx_(ctx) {
  VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  vkCheck(vkCreateSemaphore(ctx.device(), &sci, nullptr, &acquired_), "vkCreateSemaphore");
  fence_ = ctx.createFence();
  cmd_ = ctx.allocateCommandBuffer();
  create(width, height);
}

Swapchain::~Swapchain() {
  vkDeviceWaitIdle(ctx_.device());
  destroy();
  vkFreeCommandBuffers(ctx_.device(), ctx_.commandPool(), 1, &cmd_);
  vkDestroyFence(ctx_.device(), fence_, nullptr);
  vkDestroySemaphore(ctx_.device(), acquired_, nullptr);
}

void Swapchain::create(uint32_t width, uint32_t height) {
  VkPhysicalDevice pd = ctx_.physicalDevice();
  VkSurfaceKHR surface = ctx_.surface();
  VkSurfaceCapabilitiesKHR caps;
  vkCheck(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(pd, surface, &caps), "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
  if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT))
    throw Error("the window's swapchain images cannot be copied to (no transfer-destination usage)");
  uint32_t n = 0;
  vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface, &n, nullptr);
  std::vector<VkSurfaceFormatKHR> formats(n);
  vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface, &n, formats.data());
  // The display pass writes sRGB-encoded bytes; any 8-bit RGBA/BGRA format carries them (a copy
  // does not convert, and an _SRGB format is displayed as sRGB-encoded too).
  VkSurfaceFormatKHR chosen{VK_FORMAT_UNDEFINED, VK_COLOR_SPACE_SRGB_NONLINEAR_KHR};
  for (VkFormat wanted : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_R8G8B8A8_SRGB})
    for (const VkSurfaceFormatKHR& f : formats)
      if (chosen.format == VK_FORMAT_UNDEFINED && f.format == wanted) chosen = f;
  if (chosen.format == VK_FORMAT_UNDEFINED) throw Error("the window offers no 8-bit RGBA or BGRA format");
  format_ = chosen.format;
  redFirst_ = format_ == VK_FORMAT_R8G8B8A8_UNORM || format_ == VK_FORMAT_R8G8B8A8_SRGB;

  extent_ = caps.currentExtent;
  if (extent_.width == UINT32_MAX) extent_ = {width, height};
  extent_.width = std::clamp(extent_.width, caps.minImageExtent.width, caps.maxImageExtent.width);
  extent_.height = std::clamp(extent_.height, caps.minImageExtent.height, caps.maxImageExtent.height);

  vkGetPhysicalDeviceSurfacePresentModesKHR(pd, surface, &n, nullptr);
  std::vector<VkPresentModeKHR> modes(n);
  vkGetPhysicalDeviceSurfacePresentModesKHR(pd, surface, &n, modes.data());
  // Mailbox where offered: presenting never waits for the display's refresh, the path tracer's
  // samples per second do not depend on it.
  VkPresentModeKHR mode = VK_PRESENT_MODE_FIFO_KHR;
  if (std::find(modes.begin(), modes.end(), VK_PRESENT_MODE_MAILBOX_KHR) != modes.end()) mode = VK_PRESENT_MODE_MAILBOX_KHR;

  VkSwapchainCreateInfoKHR ci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  ci.surface = surface;
  ci.minImageCount = std::max(caps.minImageCount, 2u);
  if (caps.maxImageCount) ci.minImageCount = std::min(ci.minImageCount, caps.maxImageCount);
  ci.imageFormat = chosen.format;
  ci.imageColorSpace = chosen.colorSpace;
  ci.imageExtent = extent_;
  ci.imageArrayLayers = 1;
  ci.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  ci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.preTransform = caps.currentTransform;
  ci.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                          ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                          : VkCompositeAlphaFlagBitsKHR(caps.supportedCompositeAlpha & -caps.supportedCompositeAlpha);
  ci.presentMode = mode;
  ci.clipped = VK_TRUE;
  vkCheck(vkCreateSwapchainKHR(ctx_.device(), &ci, nullptr, &swapchain_), "vkCreateSwapchainKHR");
  vkGetSwapchainImagesKHR(ctx_.device(), swapchain_, &n, nullptr);
  images_.resize(n);
  vkGetSwapchainImagesKHR(ctx_.device(), swapchain_, &n, images_.data());
  VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  rendered_.resize(n);
  for (VkSemaphore& s : rendered_) vkCheck(vkCreateSemaphore(ctx_.device(), &sci, nullptr, &s), "vkCreateSemaphore");
}

void Swapchain::destroy() {
  for (VkSemaphore s : rendered_) vkDestroySemaphore(ctx_.device(), s, nullptr);
  rendered_.clear();
  images_.clear();
  if (swapchain_) vkDestroySwapchainKHR(ctx_.device(), swapchain_, nullptr);
  swapchain_ = VK_NULL_HANDLE;
}

void Swapchain::recreate(uint32_t width, uint32_t height) {
  vkCheck(vkDeviceWaitIdle(ctx_.device()), "vkDeviceWaitIdle");
  destroy();
  // The acquire semaphore may be left signalled by an acquire whose frame was abandoned.
  vkDestroySemaphore(ctx_.device(), acquired_, nullptr);
  VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  vkCheck(vkCreateSemaphore(ctx_.device(), &sci, nullptr, &acquired_), "vkCreateSemaphore");
  create(width, height);
}

bool Swapchain::acquire(uint32_t* index) {
  VkResult r = vkAcquireNextImageKHR(ctx_.device(), swapchain_, UINT64_MAX, acquired_, VK_NULL_HANDLE, index);
  if (r == VK_ERROR_OUT_OF_DATE_KHR) return false;
  if (r != VK_SUBOPTIMAL_KHR) vkCheck(r, "vkAcquireNextImageKHR");
  return true;
}

bool Swapchain::submitAndPresent(const Buffer& pixels, uint32_t index) {
  VkImageMemoryBarrier toCopy{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  toCopy.srcAccessMask = 0;
  toCopy.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  toCopy.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;   // every pixel is overwritten
  toCopy.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  toCopy.srcQueueFamilyIndex = toCopy.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  toCopy.image = images_[index];
  toCopy.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  // The display passes' writes must land before the copy reads them.
  VkMemoryBarrier written{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  written.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  written.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  vkCmdPipelineBarrier(cmd_, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
                       VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &written, 0, nullptr, 1, &toCopy);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {extent_.width, extent_.height, 1};
  vkCmdCopyBufferToImage(cmd_, pixels.handle(), images_[index], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
  VkImageMemoryBarrier toPresent = toCopy;
  toPresent.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  toPresent.dstAccessMask = 0;
  toPresent.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  toPresent.newLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
  vkCmdPipelineBarrier(cmd_, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0, 0, nullptr, 0,
                       nullptr, 1, &toPresent);
  vkCheck(vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");

  VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_TRANSFER_BIT;
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.waitSemaphoreCount = 1;
  si.pWaitSemaphores = &acquired_;
  si.pWaitDstStageMask = &waitStage;
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd_;
  si.signalSemaphoreCount = 1;
  si.pSignalSemaphores = &rendered_[index];
  vkCheck(vkResetFences(ctx_.device(), 1, &fence_), "vkResetFences");
  vkCheck(vkQueueSubmit(ctx_.queue(), 1, &si, fence_), "vkQueueSubmit");
  VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  pi.waitSemaphoreCount = 1;
  pi.pWaitSemaphores = &rendered_[index];
  pi.swapchainCount = 1;
  pi.pSwapchains = &swapchain_;
  pi.pImageIndices = &index;
  VkResult r = vkQueuePresentKHR(ctx_.queue(), &pi);
  vkCheck(vkWaitForFences(ctx_.device(), 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) return false;
  vkCheck(r, "vkQueuePresentKHR");
  return true;
}

}  // namespace mixtrace
