#include "vulkan/buffer.h"

#include <cstring>
#include <utility>

#include "util/error.h"
#include "vulkan/check.h"
#include "vulkan/context.h"

namespace mixtrace {
namespace {

int findMemoryType(VkPhysicalDevice pd, uint32_t typeBits, VkMemoryPropertyFlags want) {
  VkPhysicalDeviceMemoryProperties mp;
  vkGetPhysicalDeviceMemoryProperties(pd, &mp);
  for (uint32_t i = 0; i < mp.memoryTypeCount; ++i)
    if ((typeBits & (1u << i)) && (mp.memoryTypes[i].propertyFlags & want) == want) return int(i);
  return -1;
}

std::string mib(VkDeviceSize bytes) { return std::to_string((bytes + (1 << 20) - 1) >> 20) + " MiB"; }

}  // namespace

Buffer::Buffer(VulkanContext& ctx, VkDeviceSize size, const std::string& name, bool hostReadback)
    : ctx_(&ctx), name_(name) {
  size_ = size < 16 ? 16 : (size + 15) & ~VkDeviceSize(15);
  if (size_ > ctx.maxStorageBufferRange())
    throw Error(name + " needs " + mib(size_) + " but the device's largest storage buffer is " +
                mib(ctx.maxStorageBufferRange()) + ": use a smaller image or scene");
  VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bci.size = size_;
  bci.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT |
              VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
              VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
  vkCheck(vkCreateBuffer(ctx.device(), &bci, nullptr, &buffer_), "vkCreateBuffer");
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(ctx.device(), buffer_, &req);
  const VkMemoryPropertyFlags mappable = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  // Staging/read-back buffers must be mappable; the rest prefer device-local memory.
  int type = -1;
  if (hostReadback) {
    type = findMemoryType(ctx.physicalDevice(), req.memoryTypeBits, mappable | VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
    if (type < 0) type = findMemoryType(ctx.physicalDevice(), req.memoryTypeBits, mappable);
  } else {
    type = findMemoryType(ctx.physicalDevice(), req.memoryTypeBits, mappable | VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (type < 0) type = findMemoryType(ctx.physicalDevice(), req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (type < 0) type = findMemoryType(ctx.physicalDevice(), req.memoryTypeBits, 0);
  }
  if (type < 0) throw Error("no suitable memory type for " + name);
  VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  mai.allocationSize = req.size;
  mai.memoryTypeIndex = uint32_t(type);
  VkResult r = vkAllocateMemory(ctx.device(), &mai, nullptr, &memory_);
  if (r != VK_SUCCESS) {
    vkDestroyBuffer(ctx.device(), buffer_, nullptr);
    buffer_ = VK_NULL_HANDLE;
    throw Error("out of device memory allocating " + name + " (" + mib(size_) + "): use a smaller image or scene");
  }
  vkCheck(vkBindBufferMemory(ctx.device(), buffer_, memory_, 0), "vkBindBufferMemory");
  VkPhysicalDeviceMemoryProperties mp;
  vkGetPhysicalDeviceMemoryProperties(ctx.physicalDevice(), &mp);
  if ((mp.memoryTypes[type].propertyFlags & mappable) == mappable)
    vkCheck(vkMapMemory(ctx.device(), memory_, 0, VK_WHOLE_SIZE, 0, &mapped_), "vkMapMemory");
}

Buffer::~Buffer() { release(); }

Buffer& Buffer::operator=(Buffer&& o) noexcept {
  if (this != &o) {
    release();
    std::swap(ctx_, o.ctx_);
    std::swap(buffer_, o.buffer_);
    std::swap(memory_, o.memory_);
    std::swap(size_, o.size_);
    std::swap(mapped_, o.mapped_);
    std::swap(name_, o.name_);
  }
  return *this;
}

void Buffer::release() {
  if (!ctx_) return;
  if (buffer_) vkDestroyBuffer(ctx_->device(), buffer_, nullptr);
  if (memory_) vkFreeMemory(ctx_->device(), memory_, nullptr);
  buffer_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
  mapped_ = nullptr;
  ctx_ = nullptr;
}

void Buffer::upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset) {
  if (bytes == 0) return;
  if (mapped_) {
    std::memcpy(static_cast<char*>(mapped_) + offset, data, bytes);
    return;
  }
  Buffer staging(*ctx_, bytes, "staging buffer", true);
  staging.upload(data, bytes);
  ctx_->submitAndWait([&](VkCommandBuffer cmd) {
    VkBufferCopy region{0, offset, bytes};
    vkCmdCopyBuffer(cmd, staging.handle(), buffer_, 1, &region);
  });
}

void Buffer::download(void* data, VkDeviceSize bytes, VkDeviceSize offset) const {
  if (bytes == 0) return;
  if (mapped_) {
    std::memcpy(data, static_cast<const char*>(mapped_) + offset, bytes);
    return;
  }
  Buffer staging(*ctx_, bytes, "staging buffer", true);
  ctx_->submitAndWait([&](VkCommandBuffer cmd) {
    VkBufferCopy region{offset, 0, bytes};
    vkCmdCopyBuffer(cmd, buffer_, staging.handle(), 1, &region);
  });
  staging.download(data, bytes);
}

VkBufferView makeTexelView(VulkanContext& ctx, const Buffer& buffer) {
  constexpr VkFormat kFormat = VK_FORMAT_R32G32B32A32_UINT;
  constexpr VkDeviceSize kTexelBytes = 16;
  VkFormatProperties fp;
  vkGetPhysicalDeviceFormatProperties(ctx.physicalDevice(), kFormat, &fp);
  if (!(fp.bufferFeatures & VK_FORMAT_FEATURE_STORAGE_TEXEL_BUFFER_BIT))
    throw Error("the Vulkan device cannot read RGBA32UI storage texel buffers, which " + buffer.name() + " needs");
  const VkDeviceSize texels = buffer.size() / kTexelBytes;
  if (texels > ctx.properties().limits.maxTexelBufferElements)
    throw Error(buffer.name() + " needs " + std::to_string(texels) + " texels but the device views at most " +
                std::to_string(ctx.properties().limits.maxTexelBufferElements) + ": use a smaller scene");
  VkBufferViewCreateInfo vci{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
  vci.buffer = buffer.handle();
  vci.format = kFormat;
  vci.offset = 0;
  vci.range = texels * kTexelBytes;
  VkBufferView view = VK_NULL_HANDLE;
  vkCheck(vkCreateBufferView(ctx.device(), &vci, nullptr, &view), "vkCreateBufferView");
  return view;
}

}  // namespace mixtrace
