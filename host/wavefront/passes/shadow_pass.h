#pragma once
// The any-hit test of every queued shadow ray, and with controlled mixture sampling the terms its
// visibility decides (shaders/wavefront/shadow.comp), sized by the shadow queue's counter. Binds
// what wavefront/shadow_interface.h lists, from the renderer's buffers.
#include <vulkan/vulkan.h>

#include "vulkan/compute_pass.h"
#include "wavefront/shadow_interface.h"

namespace mixtrace {

class ShadowPass {
 public:
  // floatAtomics: the shadow_float_atomics module (see ShadePass).
  ShadowPass(VulkanContext& ctx, const std::vector<uint32_t>& specialization, const BufferBindings& buffers,
             bool floatAtomics);
  // `gathering`: timed apart as "shadow+statistics" (see ShadePass).
  void record(VkCommandBuffer cmd, PassTimer& timer, const shared::VertexConstants& constants, bool gathering) const;

 private:
  ComputePass pass_;
  const Buffer& queues_;   // the queue counters, holding the indirect arguments
};

}  // namespace mixtrace
