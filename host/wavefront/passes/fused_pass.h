#pragma once
// Traces whole paths in one dispatch per sample pass (shaders/wavefront/fused.comp): the Vulkan
// renderer's schedule for CPU devices. Binds what wavefront/fused_interface.h lists.
#include <vulkan/vulkan.h>

#include "wavefront/fused_interface.h"
#include "vulkan/compute_pass.h"

namespace mixtrace {

class FusedPass {
 public:
  FusedPass(VulkanContext& ctx, const std::vector<uint32_t>& specialization, const BufferBindings& buffers);
  void record(VkCommandBuffer cmd, PassTimer& timer, const shared::FusedConstants& constants) const;

 private:
  ComputePass pass_;
};

}  // namespace mixtrace
