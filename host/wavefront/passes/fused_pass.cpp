#include "wavefront/passes/fused_pass.h"

#include "vulkan/buffer.h"

namespace mixtrace {

FusedPass::FusedPass(VulkanContext& ctx, const std::vector<uint32_t>& specialization, const BufferBindings& buffers,
                     bool floatAtomics)
    : pass_(ctx, floatAtomics ? "fused_float_atomics" : "fused", BINDINGS_OF(FUSED_BUFFERS),
            sizeof(shared::FusedConstants), specialization, "fused") {
  pass_.bind(buffers);
}

void FusedPass::record(VkCommandBuffer cmd, PassTimer& timer, const shared::FusedConstants& constants) const {
  pass_.record(cmd, timer, constants, workgroupsFor(constants.pathCount), 1,
               constants.gatherStatistics ? "fused+statistics" : nullptr);
}

}  // namespace mixtrace
