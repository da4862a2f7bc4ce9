#include "wavefront/passes/prepare_pass.h"

#include <cstddef>

#include "vulkan/buffer.h"

namespace mixtrace {

PreparePass::PreparePass(VulkanContext& ctx, const std::vector<uint32_t>& specialization, const BufferBindings& buffers)
    : pass_(ctx, "prepare", BINDINGS_OF(PREPARE_BUFFERS), sizeof(shared::PrepareConstants), specialization) {
  pass_.bind(buffers);
}

void PreparePass::record(VkCommandBuffer cmd, PassTimer& timer, const shared::PrepareConstants& constants) const {
  pass_.record(cmd, timer, constants, 1);
}

}  // namespace mixtrace
