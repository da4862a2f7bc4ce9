#pragma once
// GPU time per pass from Vulkan timestamp queries: a timestamp after each recorded pass; the
// difference to the previous one is charged to that pass. Totals accumulate over submissions.
// The timer counts the passes marked since begin() (also on a device without timestamps), so a
// renderer can size its submissions by what it recorded (room()).
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace mixtrace {

class VulkanContext;

class PassTimer {
 public:
  PassTimer(VulkanContext& ctx, uint32_t capacity);
  ~PassTimer();
  PassTimer(const PassTimer&) = delete;
  PassTimer& operator=(const PassTimer&) = delete;

  bool enabled() const { return pool_ != VK_NULL_HANDLE; }
  uint32_t capacity() const { return capacity_; }
  uint32_t marked() const { return uint32_t(labels_.size()); }      // passes marked since begin()
  uint32_t room() const { return capacity_ - 1 - marked(); }        // marks that still fit
  void begin(VkCommandBuffer cmd);                 // resets the pool, writes the first timestamp
  void mark(VkCommandBuffer cmd, const char* pass); // after a pass
  void collect();                                  // after the submission completed
  const std::map<std::string, double>& totalsMs() const { return totalsMs_; }

 private:
  VulkanContext& ctx_;
  VkQueryPool pool_ = VK_NULL_HANDLE;
  uint32_t capacity_;
  std::vector<const char*> labels_;  // labels_[i] = pass ending at query i + 1
  std::map<std::string, double> totalsMs_;
};

}  // namespace mixtrace
