// A pass that needs more descriptors of a kind than the device allows per shader stage is refused
// with a message naming the limit (host/vulkan/pipeline.h checkDescriptorLimits), before Vulkan
// would fail or misbehave: the texel rows are storage texel buffers, which count against the
// storage-image limit, of which Vulkan guarantees only 4.
#include <string>

#include <gtest/gtest.h>

#include "util/error.h"
#include "vulkan/pipeline.h"

namespace mixtrace {
namespace {

VkPhysicalDeviceLimits limits(uint32_t storageBuffers, uint32_t storageImages) {
  VkPhysicalDeviceLimits l{};
  l.maxPerStageDescriptorStorageBuffers = storageBuffers;
  l.maxPerStageDescriptorStorageImages = storageImages;
  return l;
}

std::string messageOf(uint32_t buffers, uint32_t texels, const VkPhysicalDeviceLimits& l) {
  try {
    checkDescriptorLimits(buffers, texels, l);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(DescriptorLimits, WithinTheLimitsPasses) {
  EXPECT_NO_THROW(checkDescriptorLimits(32, 7, limits(32, 8)));
  EXPECT_NO_THROW(checkDescriptorLimits(0, 0, limits(4, 4)));
}

TEST(DescriptorLimits, TooManyTexelRowsForTheStorageImageLimitIsRefusedNamingIt) {
  const std::string m = messageOf(20, 7, limits(32, 4));
  EXPECT_NE(m.find("7 storage texel buffers"), std::string::npos) << m;
  EXPECT_NE(m.find("allows 4 storage images"), std::string::npos) << m;
}

TEST(DescriptorLimits, TooManyStorageBuffersIsRefusedNamingIt) {
  const std::string m = messageOf(33, 0, limits(32, 64));
  EXPECT_NE(m.find("33 storage buffers"), std::string::npos) << m;
  EXPECT_NE(m.find("allows 32"), std::string::npos) << m;
}

}  // namespace
}  // namespace mixtrace
