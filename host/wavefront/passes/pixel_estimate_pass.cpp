#include "wavefront/passes/pixel_estimate_pass.h"

#include <cstddef>

#include "vulkan/buffer.h"

namespace mixtrace {

PixelEstimatePass::PixelEstimatePass(VulkanContext& ctx, const std::vector<uint32_t>& specialization, const BufferBindings& buffers)
    : pass_(ctx, "pixel_estimate", BINDINGS_OF(PIXEL_ESTIMATE_BUFFERS), sizeof(shared::PixelEstimateConstants), specialization) {
  pass_.bind(buffers);
}

void PixelEstimatePass::record(VkCommandBuffer cmd, PassTimer& timer, const shared::PixelEstimateConstants& constants) const {
  pass_.record(cmd, timer, constants, workgroupsFor(constants.pixelCount));
}

}  // namespace mixtrace
