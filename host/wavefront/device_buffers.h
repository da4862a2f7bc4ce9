#pragma once
// The renderer's own buffers, allocated from their tables in one loop: the path state, queues and
// film (shaders/shared/path_state.h), the CMS state (shaders/shared/cms_state.h) and the per-triangle
// control variate's pair table (shaders/shared/cms_pair_state.h), sized by each
// row's extent. Rows the host uploads (extent UPLOADED: the clusters) are added by their owner;
// the scene's by GpuScene. Every buffer is found by its binding number.
#include <cstdint>
#include <map>
#include <string>

#include "vulkan/buffer.h"
#include "vulkan/pipeline.h"

namespace mixtrace {

class VulkanContext;

// What the extents of shaders/shared/buffer_table.h count, for one renderer.
struct BufferExtents {
  uint32_t paths = 0;        // paths per wavefront chunk
  uint32_t width = 0, height = 0;
  bool cms = false;          // the method learns: CMS_PATHS and CMS_PIXELS are per path / pixel
  uint32_t cellSlots = 1;    // CMS cell table slots (1: the placeholder)
  uint32_t clusters = 1;     // L, for the per-cell strides
  bool aovs = false;          // the render writes AOVs: AOV_PIXELS is kAovStride per pixel
  uint32_t pairSlots = 1;    // per-triangle CV: (cell, technique) pair table slots (1: the placeholder);
                             // more than 1 also doubles the shadow queue (SHADOW_SLOTS)
};

class DeviceBuffers {
 public:
  DeviceBuffers(VulkanContext& ctx, const BufferExtents& extents);

  void add(uint32_t binding, Buffer buffer);   // an uploaded row
  const Buffer& operator[](uint32_t binding) const;
  // Every buffer here, and the ones `others` holds (the scene's), by binding number.
  BufferBindings bindings(const BufferBindings& others = {}) const;

 private:
  std::map<uint32_t, Buffer> buffers_;
};

}  // namespace mixtrace
