#include "vulkan/compute_pass.h"

#include "shared/layouts.h"
#include "util/error.h"
#include "vulkan/buffer.h"
#include "vulkan/pass_timer.h"

namespace mixtrace {

ComputePass::ComputePass(VulkanContext& ctx, const std::string& shader, const std::vector<uint32_t>& bindings,
                         uint32_t constantBytes, const std::vector<uint32_t>& specialization, const std::string& name)
    : set_(ctx, bindings, constantBytes), pipeline_(ctx, shader, set_.pipelineLayout(), specialization, name) {}

void ComputePass::bindAndPush(VkCommandBuffer cmd, const void* constants, uint32_t bytes) const {
  if (bytes != set_.pushConstantBytes())
    throw Error("internal: pass " + name() + " pushed " + std::to_string(bytes) + " bytes, its range holds " +
                std::to_string(set_.pushConstantBytes()));
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.handle());
  VkDescriptorSet set = set_.set();
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, set_.pipelineLayout(), 0, 1, &set, 0, nullptr);
  if (bytes) vkCmdPushConstants(cmd, set_.pipelineLayout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, bytes, constants);
}

void ComputePass::dispatch(VkCommandBuffer cmd, const void* constants, uint32_t bytes, uint32_t groupsX,
                           uint32_t groupsY) const {
  bindAndPush(cmd, constants, bytes);
  vkCmdDispatch(cmd, groupsX, groupsY, 1);
}

void ComputePass::dispatchIndirect(VkCommandBuffer cmd, const void* constants, uint32_t bytes, const Buffer& args,
                                   VkDeviceSize offset) const {
  bindAndPush(cmd, constants, bytes);
  vkCmdDispatchIndirect(cmd, args.handle(), offset);
}

void ComputePass::finish(VkCommandBuffer cmd, PassTimer& timer, const char* label) const {
  computeBarrier(cmd);
  timer.mark(cmd, label ? label : name().c_str());
}

uint32_t workgroupsFor(uint32_t n) { return (n + shared::kWorkgroupSize - 1) / shared::kWorkgroupSize; }

}  // namespace mixtrace
