#pragma once
// A descriptor set of buffers at given binding numbers (the rows a pass's interface header lists,
// shaders/shared/buffer_table.h: storage buffers, and storage texel buffers for TEXELS rows) with
// its pipeline layout, and compute pipelines built from embedded SPIR-V with specialization
// constants. host/vulkan/compute_pass.h puts the
// two together for one pass.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace mixtrace {

class VulkanContext;
class Buffer;

// Buffers by binding number: what a renderer (or a test) offers the passes to bind from.
using BufferBindings = std::map<uint32_t, const Buffer*>;

// Throws mixtrace::Error, naming the limit, when one shader stage would bind more storage buffers
// or storage texel buffers (which count as storage images) than the device allows; Vulkan
// guarantees only 4 storage images per stage, and a pass may bind up to 7 texel rows.
void checkDescriptorLimits(uint32_t storageBuffers, uint32_t texelBuffers, const VkPhysicalDeviceLimits& limits);

class DescriptorSet {
 public:
  // One buffer at each of `bindings` (any numbers, each once; a TEXELS row's as a storage texel
  // buffer, the others as storage buffers), and a pipeline layout with this set and a
  // push-constant range of pushConstantBytes (0: none).
  DescriptorSet(VulkanContext& ctx, const std::vector<uint32_t>& bindings, uint32_t pushConstantBytes);
  ~DescriptorSet();
  DescriptorSet(const DescriptorSet&) = delete;
  DescriptorSet& operator=(const DescriptorSet&) = delete;

  // Throws mixtrace::Error for a binding the set does not have, or (bindAll) cannot find.
  void bind(uint32_t binding, const Buffer& buffer);
  void bindAll(const BufferBindings& buffers);   // every binding of the set, from `buffers`
  const std::vector<uint32_t>& bindings() const { return bindings_; }
  uint32_t pushConstantBytes() const { return pushConstantBytes_; }
  VkDescriptorSet set() const { return set_; }
  VkPipelineLayout pipelineLayout() const { return pipelineLayout_; }

 private:
  VulkanContext& ctx_;
  std::vector<uint32_t> bindings_;
  uint32_t pushConstantBytes_;
  VkDescriptorSetLayout layout_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  VkPipelineLayout pipelineLayout_ = VK_NULL_HANDLE;
  std::map<uint32_t, VkBufferView> views_;   // the texel views bound, by binding; owned
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

}  // namespace mixtrace
