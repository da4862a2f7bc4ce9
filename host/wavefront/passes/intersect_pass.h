#pragma once
// The closest hit of every queued extension ray (shaders/wavefront/intersect.comp), sized by
// the ray queue's counter.
// Binds what wavefront/intersect_interface.h lists, from the renderer's buffers.
#include <vulkan/vulkan.h>

#include "wavefront/intersect_interface.h"
#include "vulkan/compute_pass.h"

namespace mixtrace {

class IntersectPass {
 public:
  IntersectPass(VulkanContext& ctx, const std::vector<uint32_t>& specialization, const BufferBindings& buffers);
  void record(VkCommandBuffer cmd, PassTimer& timer, const shared::IntersectConstants& constants) const;

 private:
  ComputePass pass_;
  const Buffer& queues_;   // the queue counters, holding the indirect arguments
};

}  // namespace mixtrace
