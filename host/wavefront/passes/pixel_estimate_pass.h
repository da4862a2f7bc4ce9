#pragma once
// CMS, at the start of every training iteration: the pixel estimate the statistics' relative
// weights divide by (shaders/cms/pixel_estimate.comp), from the film so far.
// Binds what cms/pixel_estimate_interface.h lists, from the renderer's buffers.
#include <vulkan/vulkan.h>

#include "cms/pixel_estimate_interface.h"
#include "vulkan/compute_pass.h"

namespace mixtrace {

class PixelEstimatePass {
 public:
  PixelEstimatePass(VulkanContext& ctx, const std::vector<uint32_t>& specialization, const BufferBindings& buffers);
  void record(VkCommandBuffer cmd, PassTimer& timer, const shared::PixelEstimateConstants& constants) const;

 private:
  ComputePass pass_;
};

}  // namespace mixtrace
