#pragma once
// Turns a queue's counter into the next pass's indirect dispatch arguments
// (shaders/wavefront/prepare.comp): one invocation.
// Binds what wavefront/prepare_interface.h lists, from the renderer's buffers.
#include <vulkan/vulkan.h>

#include "wavefront/prepare_interface.h"
#include "vulkan/compute_pass.h"

namespace mixtrace {

class PreparePass {
 public:
  PreparePass(VulkanContext& ctx, const std::vector<uint32_t>& specialization, const BufferBindings& buffers);
  void record(VkCommandBuffer cmd, PassTimer& timer, const shared::PrepareConstants& constants) const;

 private:
  ComputePass pass_;
};

}  // namespace mixtrace
