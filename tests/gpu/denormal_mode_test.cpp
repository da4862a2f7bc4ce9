// A CPU Vulkan driver's compute threads flush denormals (host/vulkan/denormal_mode.h), and
// creating the context leaves the calling thread's floating-point mode as it was.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "tests/float_mode_interface.h"
#include "vulkan/buffer.h"
#include "vulkan/buffer_rows.h"
#include "vulkan/compute_pass.h"
#include "vulkan/context.h"
#include "vulkan/denormal_mode.h"

namespace mixtrace {
namespace {

TEST(DenormalMode, ScopeFlushesAndRestores) {
  const bool before = threadFlushesDenormals();
  {
    FlushDenormalsInScope flush;
#if defined(__x86_64__) || defined(__aarch64__)
    EXPECT_TRUE(threadFlushesDenormals());
    volatile float tiny = 1e-30f;
    volatile float product = tiny * 1e-10f;
    EXPECT_EQ(product, 0.0f) << "a denormal result is flushed inside the scope";
#endif
  }
  EXPECT_EQ(threadFlushesDenormals(), before);
}

TEST(DenormalMode, ContextLeavesTheCallersModeAlone) {
  const bool before = threadFlushesDenormals();
  { VulkanContext ctx(ContextOptions{"", true}); }
  EXPECT_EQ(threadFlushesDenormals(), before);
  volatile float tiny = 1e-30f;
  volatile float product = tiny * 1e-10f;
  if (!before) EXPECT_GT(product, 0.0f) << "the host keeps IEEE denormals";
}

// On lavapipe a shader's denormal results and operands are zero: without the flush, every masked
// lane computing with a denormal took a microcode assist (the punctual scene's shade pass).
TEST(DenormalMode, CpuDeviceThreadsFlushDenormals) {
  VulkanContext ctx(ContextOptions{"", true});
  if (ctx.properties().deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU)
    GTEST_SKIP() << ctx.deviceName() << " is not a CPU device: its denormal mode is its own";
  const float denormal = 1e-40f;
  ASSERT_GT(denormal, 0.0f);
  ASSERT_LT(denormal, 1.17549435e-38f);
  // (1e-30 * 1e-10: a denormal result; 1e-40 * 1: a denormal operand; 1e-20 * 1e-10: normal.)
  std::vector<glm::vec3> values = {{1e-30f, 1e-30f, 1e-30f}, {denormal, denormal, denormal}, {1e-20f, 2e-20f, 4e-20f}};
  const float scales[] = {1e-10f, 1.0f, 1e-10f};
  for (int k = 0; k < 3; ++k) {
    std::vector<glm::vec3> in(256, values[size_t(k)]);
    Buffer buffer = makeBuffer(ctx, in, "values");
    ComputePass pass(ctx, "float_mode", BINDINGS_OF(FLOAT_MODE_BUFFERS), sizeof(shared::FloatModeConstants), {});
    pass.bind(shared::BINDING_THROUGHPUT, buffer);
    shared::FloatModeConstants pc{uint32_t(in.size()), scales[k]};
    ctx.submitAndWait([&](VkCommandBuffer cmd) { pass.dispatch(cmd, &pc, sizeof(pc), workgroupsFor(pc.count)); });
    std::vector<glm::vec3> out = buffer.downloadAll<glm::vec3>();
    ASSERT_EQ(out.size(), in.size());
    for (size_t i = 0; i < out.size(); ++i) {
      if (k < 2) {
        ASSERT_EQ(out[i].x, 0.0f) << "case " << k << " value " << i;
        ASSERT_EQ(out[i].z, 0.0f) << "case " << k << " value " << i;
      } else {
        ASSERT_NEAR(out[i].y, 2e-30f, 1e-36f) << "value " << i;
      }
    }
  }
  EXPECT_EQ(ctx.validationErrors(), 0u);
}

}  // namespace
}  // namespace mixtrace
