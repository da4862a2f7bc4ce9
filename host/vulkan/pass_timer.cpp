#include "vulkan/pass_timer.h"

#include "vulkan/check.h"
#include "vulkan/context.h"

namespace mixtrace {

PassTimer::PassTimer(VulkanContext& ctx, uint32_t capacity) : ctx_(ctx), capacity_(capacity) {
  if (!ctx.timestampsSupported()) return;
  VkQueryPoolCreateInfo qci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  qci.queryType = VK_QUERY_TYPE_TIMESTAMP;
  qci.queryCount = capacity;
  vkCheck(vkCreateQueryPool(ctx.device(), &qci, nullptr, &pool_), "vkCreateQueryPool");
}

PassTimer::~PassTimer() {
  if (pool_) vkDestroyQueryPool(ctx_.device(), pool_, nullptr);
}

void PassTimer::begin(VkCommandBuffer cmd) {
  labels_.clear();
  if (!pool_) return;
  vkCmdResetQueryPool(cmd, pool_, 0, capacity_);
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, 0);
}

void PassTimer::mark(VkCommandBuffer cmd, const char* pass) {
  if (labels_.size() + 1 >= capacity_) return;
  labels_.push_back(pass);
  if (pool_) vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, uint32_t(labels_.size()));
}

void PassTimer::collect() {
  if (!pool_ || labels_.empty()) {
    labels_.clear();
    return;
  }
  std::vector<uint64_t> ticks(labels_.size() + 1);
  VkResult r = vkGetQueryPoolResults(ctx_.device(), pool_, 0, uint32_t(ticks.size()), ticks.size() * sizeof(uint64_t),
                                     ticks.data(), sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT);
  vkCheck(r, "vkGetQueryPoolResults");
  const double msPerTick = ctx_.timestampPeriodNs() * 1e-6;
  for (size_t i = 0; i < labels_.size(); ++i)
    totalsMs_[labels_[i]] += double(ticks[i + 1] - ticks[i]) * msPerTick;
  labels_.clear();
}

}  // namespace mixtrace
