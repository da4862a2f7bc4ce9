#pragma once
// Folds each path's radiance into its pixel (shaders/wavefront/accumulate.comp).
// Binds what wavefront/accumulate_interface.h lists, from the renderer's buffers.
#include <vulkan/vulkan.h>

#include "wavefront/accumulate_interface.h"
#include "vulkan/compute_pass.h"

namespace mixtrace {

class AccumulatePass {
 public:
  AccumulatePass(VulkanContext& ctx, const std::vector<uint32_t>& specialization, const BufferBindings& buffers);
  void record(VkCommandBuffer cmd, PassTimer& timer, const shared::AccumulateConstants& constants) const;

 private:
  ComputePass pass_;
};

}  // namespace mixtrace
