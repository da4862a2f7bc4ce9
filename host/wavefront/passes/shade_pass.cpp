#include "wavefront/passes/shade_pass.h"

#include <cstddef>

#include "vulkan/buffer.h"

namespace mixtrace {

ShadePass::ShadePass(VulkanContext& ctx, const std::vector<uint32_t>& specialization, const BufferBindings& buffers,
                     bool floatAtomics)
    : pass_(ctx, floatAtomics ? "shade_float_atomics" : "shade", BINDINGS_OF(SHADE_BUFFERS),
            sizeof(shared::VertexConstants), specialization, "shade"),
      queues_(*buffers.at(shared::BINDING_QUEUE_STATE)) {
  pass_.bind(buffers);
}

void ShadePass::record(VkCommandBuffer cmd, PassTimer& timer, const shared::VertexConstants& constants,
                       bool gathering) const {
  pass_.recordIndirect(cmd, timer, constants, queues_,
                       constants.shadeQueued ? offsetof(shared::QueueState, shadeArgs) : offsetof(shared::QueueState, rayArgs),
                       gathering ? "shade+statistics" : nullptr);
}

}  // namespace mixtrace
