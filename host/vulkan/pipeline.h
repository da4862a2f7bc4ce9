#pragma once
// The descriptor set all passes share (shaders/shared/bindings.h) and compute pipelines built
// from embedded SPIR-V with specialization constants.
#include <cstdint>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace mixtrace {

class VulkanContext;
class Buffer;

class DescriptorSet {
 public:
  DescriptorSet(VulkanContext& ctx, uint32_t bindingCount, uint32_t pushConstantBytes);
  ~DescriptorSet();
  DescriptorSet(const DescriptorSet&) = delete;
  DescriptorSet& operator=(const DescriptorSet&) = delete;

  void bind(uint32_t binding, const Buffer& buffer);
  VkDescriptorSet set() const { return set_; }
  VkPipelineLayout pipelineLayout() const { return pipelineLayout_; }

 private:
  VulkanContext& ctx_;
  VkDescriptorSetLayout layout_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  VkPipelineLayout pipelineLayout_ = VK_NULL_HANDLE;
};

class ComputePipeline {
 public:
  // specialization: value of constant_id i at index i (as 32-bit words: bools are 0/1).
  // name: what timings call the pass (default: the shader's name; variants of one stage, e.g.
  // shade and shade_float_atomics, keep the stage's name).
  ComputePipeline(VulkanContext& ctx, const std::string& shader, VkPipelineLayout layout,
                  const std::vector<uint32_t>& specialization, const std::string& name = "");
  ~ComputePipeline();
  ComputePipeline(const ComputePipeline&) = delete;
  ComputePipeline& operator=(const ComputePipeline&) = delete;
  VkPipeline handle() const { return pipeline_; }
  const std::string& name() const { return name_; }

 private:
  VulkanContext& ctx_;
  std::string name_;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
};

// Makes every earlier compute write visible to later compute reads and indirect dispatches.
void computeBarrier(VkCommandBuffer cmd);

// Binds `pipeline` and `set`, pushes `constants` (any struct the layout's range holds) and
// dispatches groupsX x groupsY workgroups. For one-off passes (the solve, test kernels).
void recordDispatch(VkCommandBuffer cmd, const ComputePipeline& pipeline, const DescriptorSet& set,
                    const void* constants, uint32_t constantBytes, uint32_t groupsX, uint32_t groupsY = 1);

}  // namespace mixtrace
