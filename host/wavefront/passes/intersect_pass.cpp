#include "wavefront/passes/intersect_pass.h"

#include <cstddef>

#include "vulkan/buffer.h"

namespace mixtrace {

IntersectPass::IntersectPass(VulkanContext& ctx, const std::vector<uint32_t>& specialization, const BufferBindings& buffers)
    : pass_(ctx, "intersect", BINDINGS_OF(INTERSECT_BUFFERS), sizeof(shared::IntersectConstants), specialization),
      queues_(*buffers.at(shared::BINDING_QUEUE_STATE)) {
  pass_.bind(buffers);
}

void IntersectPass::record(VkCommandBuffer cmd, PassTimer& timer, const shared::IntersectConstants& constants) const {
  pass_.recordIndirect(cmd, timer, constants, queues_, offsetof(shared::QueueState, rayArgs));
}

}  // namespace mixtrace
