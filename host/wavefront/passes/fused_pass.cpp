#include "wavefront/passes/fused_pass.h"

#include "vulkan/buffer.h"

namespace mixtrace {

FusedPass::FusedPass(VulkanContext& ctx, const std::vector<uint32_t>& specialization, const BufferBindings& buffers)
    : pass_(ctx, "fused", BINDINGS_OF(FUSED_BUFFERS), sizeof(shared::FusedConstants), specialization) {
  pass_.bind(buffers);
}

void FusedPass::record(VkCommandBuffer cmd, PassTimer& timer, const shared::FusedConstants& constants) const {
  pass_.record(cmd, timer, constants, workgroupsFor(constants.pathCount));
}

}  // namespace mixtrace
