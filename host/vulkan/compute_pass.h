#pragma once
// One compute pass as its interface header declares it (e.g. shaders/wavefront/shade_interface.h):
// a descriptor set of exactly the buffers it lists, a pipeline layout whose push-constant range is
// its own constants struct, and its pipeline. Its record functions bind both, push, dispatch,
// make the writes visible to what follows and mark the pass in the GPU timings, so the timer
// counts what is recorded.
#include <cstdint>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "vulkan/pipeline.h"

// The binding numbers of an interface's list of rows (shaders/shared/buffer_table.h):
// BINDINGS_OF(SHADE_BUFFERS) is a std::vector<uint32_t>.
#define PASS_BINDING_NUMBER(ID, name, binding, access, Type, extent, label) ::mixtrace::shared::BINDING_##ID,
#define BINDINGS_OF(LIST) (std::vector<uint32_t>{LIST(PASS_BINDING_NUMBER)})

namespace mixtrace {

class Buffer;
class PassTimer;
class VulkanContext;

class ComputePass {
 public:
  // `shader`: the embedded module; `name`: what the timings call it (default: the shader's).
  ComputePass(VulkanContext& ctx, const std::string& shader, const std::vector<uint32_t>& bindings,
              uint32_t constantBytes, const std::vector<uint32_t>& specialization, const std::string& name = "");

  void bind(const BufferBindings& buffers) { set_.bindAll(buffers); }
  void bind(uint32_t binding, const Buffer& buffer) { set_.bind(binding, buffer); }
  const std::string& name() const { return pipeline_.name(); }

  // groupsX x groupsY workgroups; `constants` must be the pass's struct (constantBytes).
  template <class Constants>
  void record(VkCommandBuffer cmd, PassTimer& timer, const Constants& constants, uint32_t groupsX,
              uint32_t groupsY = 1, const char* label = nullptr) const {
    dispatch(cmd, &constants, sizeof(constants), groupsX, groupsY);
    finish(cmd, timer, label);
  }
  // The workgroup counts from `args` at `offset` (a VkDispatchIndirectCommand the GPU wrote).
  template <class Constants>
  void recordIndirect(VkCommandBuffer cmd, PassTimer& timer, const Constants& constants, const Buffer& args,
                      VkDeviceSize offset, const char* label = nullptr) const {
    dispatchIndirect(cmd, &constants, sizeof(constants), args, offset);
    finish(cmd, timer, label);
  }
  // Untimed and without the barrier, for passes recorded outside the renderer's timing (tests,
  // the viewer's display pass, the solve).
  void dispatch(VkCommandBuffer cmd, const void* constants, uint32_t bytes, uint32_t groupsX,
                uint32_t groupsY = 1) const;
  void dispatchIndirect(VkCommandBuffer cmd, const void* constants, uint32_t bytes, const Buffer& args,
                        VkDeviceSize offset) const;

 private:
  void bindAndPush(VkCommandBuffer cmd, const void* constants, uint32_t bytes) const;
  void finish(VkCommandBuffer cmd, PassTimer& timer, const char* label) const;   // barrier, timestamp

  DescriptorSet set_;
  ComputePipeline pipeline_;
};

// Workgroups of shared::kWorkgroupSize invocations for n items.
uint32_t workgroupsFor(uint32_t n);

}  // namespace mixtrace
