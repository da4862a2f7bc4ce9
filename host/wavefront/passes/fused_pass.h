#pragma once
// Traces whole paths in one dispatch per sample pass (shaders/wavefront/fused.comp): the Vulkan
// renderer's schedule for CPU devices. Binds what wavefront/fused_interface.h lists; with
// floatAtomics the module that adds CMS statistics with float atomics (VK_EXT_shader_atomic_float),
// as the shade and shadow passes choose theirs.
#include <vulkan/vulkan.h>

#include "wavefront/fused_interface.h"
#include "vulkan/compute_pass.h"

namespace mixtrace {

class FusedPass {
 public:
  FusedPass(VulkanContext& ctx, const std::vector<uint32_t>& specialization, const BufferBindings& buffers,
            bool floatAtomics);
  void record(VkCommandBuffer cmd, PassTimer& timer, const shared::FusedConstants& constants) const;

 private:
  ComputePass pass_;
};

}  // namespace mixtrace
