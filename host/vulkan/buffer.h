#pragma once
// A buffer and its memory, usable as a storage buffer or (through makeTexelView) a storage texel
// buffer. Prefers memory that is both device-local and host-visible (all of lavapipe's memory,
// resizable-BAR GPUs) so uploads are a memcpy; otherwise device-local memory filled through a
// staging buffer.
#include <cstdint>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "shared/buffer_table.h"

namespace mixtrace {

// `words` rounded up to whole RGBA32UI texels: the length of a buffer read through a word view.
constexpr size_t wordsInWholeTexels(size_t words) {
  return (words + shared::kWordsPerTexel - 1) / shared::kWordsPerTexel * shared::kWordsPerTexel;
}

class VulkanContext;

class Buffer {
 public:
  Buffer() = default;
  // `name` appears in error messages ("out of memory allocating path state (12 MiB)").
  Buffer(VulkanContext& ctx, VkDeviceSize size, const std::string& name, bool hostReadback = false);
  ~Buffer();
  Buffer(Buffer&& o) noexcept { *this = std::move(o); }
  Buffer& operator=(Buffer&& o) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  VkBuffer handle() const { return buffer_; }
  VkDeviceSize size() const { return size_; }
  const std::string& name() const { return name_; }

  void upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);
  void download(void* data, VkDeviceSize bytes, VkDeviceSize offset = 0) const;
  template <class T> void upload(const std::vector<T>& v) { if (!v.empty()) upload(v.data(), v.size() * sizeof(T)); }
  template <class T> std::vector<T> downloadAll() const {
    std::vector<T> v(size_ / sizeof(T));
    download(v.data(), v.size() * sizeof(T));
    return v;
  }
  void fillZero(VkCommandBuffer cmd) const { vkCmdFillBuffer(cmd, buffer_, 0, VK_WHOLE_SIZE, 0); }

 private:
  void release();
  VulkanContext* ctx_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkDeviceSize size_ = 0;
  void* mapped_ = nullptr;
  std::string name_;
};

// A view of the whole of `buffer` as RGBA32UI texels (the words' bits, whatever they hold), for a
// storage texel buffer descriptor (a TEXELS row, shaders/shared/buffer_table.h); the caller
// destroys it. Throws mixtrace::Error when
// the device cannot view that many texels at once or cannot read RGBA32UI texel buffers.
VkBufferView makeTexelView(VulkanContext& ctx, const Buffer& buffer);

// A buffer holding `v` (at least one element's worth of bytes, so empty inputs stay bindable).
template <class T> Buffer makeBuffer(VulkanContext& ctx, const std::vector<T>& v, const std::string& name) {
  Buffer b(ctx, v.empty() ? sizeof(T) : v.size() * sizeof(T), name);
  b.upload(v);
  return b;
}

}  // namespace mixtrace
