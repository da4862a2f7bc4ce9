#include "wavefront/passes/shadow_pass.h"

#include <cstddef>

#include "vulkan/buffer.h"

namespace mixtrace {

ShadowPass::ShadowPass(VulkanContext& ctx, const std::vector<uint32_t>& specialization, const BufferBindings& buffers,
                     bool floatAtomics)
    : pass_(ctx, floatAtomics ? "shadow_float_atomics" : "shadow", BINDINGS_OF(SHADOW_BUFFERS),
            sizeof(shared::VertexConstants), specialization, "shadow"),
      queues_(*buffers.at(shared::BINDING_QUEUE_STATE)) {
  pass_.bind(buffers);
}

void ShadowPass::record(VkCommandBuffer cmd, PassTimer& timer, const shared::VertexConstants& constants,
                       bool gathering) const {
  pass_.recordIndirect(cmd, timer, constants, queues_, offsetof(shared::QueueState, shadowArgs),
                       gathering ? "shadow+statistics" : nullptr);
}

}  // namespace mixtrace
