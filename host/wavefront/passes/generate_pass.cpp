#include "wavefront/passes/generate_pass.h"

#include <cstddef>

#include "vulkan/buffer.h"

namespace mixtrace {

GeneratePass::GeneratePass(VulkanContext& ctx, const std::vector<uint32_t>& specialization, const BufferBindings& buffers)
    : pass_(ctx, "generate", BINDINGS_OF(GENERATE_BUFFERS), sizeof(shared::GenerateConstants), specialization) {
  pass_.bind(buffers);
}

void GeneratePass::record(VkCommandBuffer cmd, PassTimer& timer, const shared::GenerateConstants& constants) const {
  pass_.record(cmd, timer, constants, workgroupsFor(constants.pathCount));
}

}  // namespace mixtrace
