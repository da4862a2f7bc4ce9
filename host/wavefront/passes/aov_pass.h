#pragma once
// Folds each path's first hit into its pixel's AOVs (shaders/wavefront/aov.comp), when the render writes them.
// Binds what wavefront/aov_interface.h lists, from the renderer's buffers.
#include <vulkan/vulkan.h>

#include "wavefront/aov_interface.h"
#include "vulkan/compute_pass.h"

namespace mixtrace {

class AovPass {
 public:
  AovPass(VulkanContext& ctx, const std::vector<uint32_t>& specialization, const BufferBindings& buffers);
  void record(VkCommandBuffer cmd, PassTimer& timer, const shared::AovConstants& constants) const;

 private:
  ComputePass pass_;
};

}  // namespace mixtrace
