#include "wavefront/passes/accumulate_pass.h"

#include <cstddef>

#include "vulkan/buffer.h"

namespace mixtrace {

AccumulatePass::AccumulatePass(VulkanContext& ctx, const std::vector<uint32_t>& specialization, const BufferBindings& buffers)
    : pass_(ctx, "accumulate", BINDINGS_OF(ACCUMULATE_BUFFERS), sizeof(shared::AccumulateConstants), specialization) {
  pass_.bind(buffers);
}

void AccumulatePass::record(VkCommandBuffer cmd, PassTimer& timer, const shared::AccumulateConstants& constants) const {
  pass_.record(cmd, timer, constants, workgroupsFor(constants.pathCount));
}

}  // namespace mixtrace
