#include "wavefront/passes/aov_pass.h"

#include <cstddef>

#include "vulkan/buffer.h"

namespace mixtrace {

AovPass::AovPass(VulkanContext& ctx, const std::vector<uint32_t>& specialization, const BufferBindings& buffers)
    : pass_(ctx, "aov", BINDINGS_OF(AOV_BUFFERS), sizeof(shared::AovConstants), specialization) {
  pass_.bind(buffers);
}

void AovPass::record(VkCommandBuffer cmd, PassTimer& timer, const shared::AovConstants& constants) const {
  pass_.record(cmd, timer, constants, workgroupsFor(constants.pathCount));
}

}  // namespace mixtrace
