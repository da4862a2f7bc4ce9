#include "vulkan/pipeline.h"

#include <algorithm>
#include <string>

#include "util/error.h"
#include "vulkan/buffer.h"
#include "vulkan/buffer_rows.h"
#include "vulkan/check.h"
#include "vulkan/context.h"
#include "vulkan/embedded_shaders.h"

namespace mixtrace {
namespace {

VkDescriptorType descriptorTypeOf(uint32_t binding) {
  return isTexelBinding(binding) ? VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
}

}  // namespace

void checkDescriptorLimits(uint32_t storageBuffers, uint32_t texelBuffers, const VkPhysicalDeviceLimits& limits) {
  if (storageBuffers > limits.maxPerStageDescriptorStorageBuffers)
    throw Error("a GPU pass binds " + std::to_string(storageBuffers) + " storage buffers but the Vulkan device allows " +
                std::to_string(limits.maxPerStageDescriptorStorageBuffers) + " per shader stage");
  if (texelBuffers > limits.maxPerStageDescriptorStorageImages)
    throw Error("a GPU pass binds " + std::to_string(texelBuffers) + " storage texel buffers but the Vulkan device allows " +
                std::to_string(limits.maxPerStageDescriptorStorageImages) + " storage images per shader stage");
}

DescriptorSet::DescriptorSet(VulkanContext& ctx, const std::vector<uint32_t>& bindingNumbers,
                             uint32_t pushConstantBytes)
    : ctx_(ctx), bindings_(bindingNumbers), pushConstantBytes_(pushConstantBytes) {
  const uint32_t bindingCount = uint32_t(bindings_.size());
  std::vector<VkDescriptorSetLayoutBinding> bindings(bindingCount);
  uint32_t texelBindings = 0;
  for (uint32_t i = 0; i < bindingCount; ++i) {
    bindings[i] = {bindings_[i], descriptorTypeOf(bindings_[i]), 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
    texelBindings += isTexelBinding(bindings_[i]) ? 1 : 0;
  }
  checkDescriptorLimits(bindingCount - texelBindings, texelBindings, ctx.properties().limits);
  VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  lci.bindingCount = bindingCount;
  lci.pBindings = bindings.data();
  vkCheck(vkCreateDescriptorSetLayout(ctx.device(), &lci, nullptr, &layout_), "vkCreateDescriptorSetLayout");

  std::vector<VkDescriptorPoolSize> sizes;
  if (bindingCount > texelBindings) sizes.push_back({VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, bindingCount - texelBindings});
  if (texelBindings > 0) sizes.push_back({VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER, texelBindings});
  if (sizes.empty()) sizes.push_back({VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1});  // a pool needs one size
  VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pci.maxSets = 1;
  pci.poolSizeCount = uint32_t(sizes.size());
  pci.pPoolSizes = sizes.data();
  vkCheck(vkCreateDescriptorPool(ctx.device(), &pci, nullptr, &pool_), "vkCreateDescriptorPool");
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = pool_;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &layout_;
  vkCheck(vkAllocateDescriptorSets(ctx.device(), &ai, &set_), "vkAllocateDescriptorSets");

  VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, pushConstantBytes};
  VkPipelineLayoutCreateInfo plci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  plci.setLayoutCount = 1;
  plci.pSetLayouts = &layout_;
  plci.pushConstantRangeCount = pushConstantBytes ? 1 : 0;
  plci.pPushConstantRanges = &range;
  vkCheck(vkCreatePipelineLayout(ctx.device(), &plci, nullptr, &pipelineLayout_), "vkCreatePipelineLayout");
}

DescriptorSet::~DescriptorSet() {
  for (const auto& [binding, view] : views_) vkDestroyBufferView(ctx_.device(), view, nullptr);
  vkDestroyPipelineLayout(ctx_.device(), pipelineLayout_, nullptr);
  vkDestroyDescriptorPool(ctx_.device(), pool_, nullptr);
  vkDestroyDescriptorSetLayout(ctx_.device(), layout_, nullptr);
}

void DescriptorSet::bind(uint32_t binding, const Buffer& buffer) {
  if (std::find(bindings_.begin(), bindings_.end(), binding) == bindings_.end())
    throw Error("internal: binding " + std::to_string(binding) + " is not in this descriptor set");
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.dstSet = set_;
  w.dstBinding = binding;
  w.descriptorCount = 1;
  w.descriptorType = descriptorTypeOf(binding);
  VkDescriptorBufferInfo info{buffer.handle(), 0, VK_WHOLE_SIZE};
  VkBufferView view = VK_NULL_HANDLE;
  if (isTexelBinding(binding)) {
    view = makeTexelView(ctx_, buffer);
    w.pTexelBufferView = &view;
  } else {
    w.pBufferInfo = &info;
  }
  vkUpdateDescriptorSets(ctx_.device(), 1, &w, 0, nullptr);
  if (view != VK_NULL_HANDLE) {
    auto& slot = views_[binding];
    if (slot != VK_NULL_HANDLE) vkDestroyBufferView(ctx_.device(), slot, nullptr);
    slot = view;
  }
}

void DescriptorSet::bindAll(const BufferBindings& buffers) {
  for (uint32_t binding : bindings_) {
    const auto found = buffers.find(binding);
    if (found == buffers.end() || !found->second)
      throw Error("internal: no buffer offered for binding " + std::to_string(binding));
    bind(binding, *found->second);
  }
}

ComputePipeline::ComputePipeline(VulkanContext& ctx, const std::string& shader, VkPipelineLayout layout,
                                 const std::vector<uint32_t>& specialization, const std::string& name)
    : ctx_(ctx), name_(name.empty() ? shader : name) {
  const EmbeddedShader* spv = findEmbeddedShader(shader.c_str());
  if (!spv) throw Error("internal: shader '" + shader + "' was not built");
  VkShaderModuleCreateInfo mci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  mci.codeSize = spv->sizeBytes;
  mci.pCode = spv->code;
  VkShaderModule module;
  vkCheck(vkCreateShaderModule(ctx.device(), &mci, nullptr, &module), "vkCreateShaderModule");

  std::vector<VkSpecializationMapEntry> entries(specialization.size());
  for (uint32_t i = 0; i < entries.size(); ++i) entries[i] = {i, i * 4u, 4u};
  VkSpecializationInfo si{uint32_t(entries.size()), entries.data(), specialization.size() * 4u, specialization.data()};

  VkComputePipelineCreateInfo pci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  pci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  pci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  pci.stage.module = module;
  pci.stage.pName = "main";
  pci.stage.pSpecializationInfo = specialization.empty() ? nullptr : &si;
  pci.layout = layout;
  VkResult r = vkCreateComputePipelines(ctx.device(), VK_NULL_HANDLE, 1, &pci, nullptr, &pipeline_);
  vkDestroyShaderModule(ctx.device(), module, nullptr);
  vkCheck(r, ("creating pipeline " + shader).c_str());
}

ComputePipeline::~ComputePipeline() { vkDestroyPipeline(ctx_.device(), pipeline_, nullptr); }

void computeBarrier(VkCommandBuffer cmd) {
  VkMemoryBarrier b{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  b.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  b.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT |
                    VK_ACCESS_TRANSFER_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT |
                           VK_PIPELINE_STAGE_TRANSFER_BIT,
                       0, 1, &b, 0, nullptr, 0, nullptr);
}

}  // namespace mixtrace
