#pragma once
// Emission, one light sample and one BSDF sample at every queued hit, and with controlled mixture
// sampling its cell, selection, control variate and statistics (shaders/wavefront/shade.comp),
// sized by the counter of the queue it reads (constants.shadeQueued: the rays intersect queued for
// it, or the ray queue). Binds what wavefront/shade_interface.h lists, from the
// renderer's buffers.
#include <vulkan/vulkan.h>

#include "vulkan/compute_pass.h"
#include "wavefront/shade_interface.h"

namespace mixtrace {

class ShadePass {
 public:
  // floatAtomics: the module that adds the statistics with VK_EXT_shader_atomic_float
  // (shade_float_atomics) instead of compare-and-swap loops.
  ShadePass(VulkanContext& ctx, const std::vector<uint32_t>& specialization, const BufferBindings& buffers,
            bool floatAtomics);
  // `gathering`: the pass adds CMS statistics; it is then timed apart ("shade+statistics"), so the
  // statistics' cost shows (benchmarks/suite.py).
  void record(VkCommandBuffer cmd, PassTimer& timer, const shared::VertexConstants& constants, bool gathering) const;

 private:
  ComputePass pass_;
  const Buffer& queues_;   // the queue counters, holding the indirect arguments
};

}  // namespace mixtrace
