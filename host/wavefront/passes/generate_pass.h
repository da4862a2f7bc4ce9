#pragma once
// One camera ray per path of the chunk (shaders/wavefront/generate.comp).
// Binds what wavefront/generate_interface.h lists, from the renderer's buffers.
#include <vulkan/vulkan.h>

#include "wavefront/generate_interface.h"
#include "vulkan/compute_pass.h"

namespace mixtrace {

class GeneratePass {
 public:
  GeneratePass(VulkanContext& ctx, const std::vector<uint32_t>& specialization, const BufferBindings& buffers);
  void record(VkCommandBuffer cmd, PassTimer& timer, const shared::GenerateConstants& constants) const;

 private:
  ComputePass pass_;
};

}  // namespace mixtrace
