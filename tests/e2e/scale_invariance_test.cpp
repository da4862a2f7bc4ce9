// Issue 11.3: radiance is scale invariant, so the room scaled by 1e-12 or 1e15 must render the
// image of the unscaled room. The light set computed emitter areas in float (1e-24 underflowed to
// "zero area": the lights were dropped and the image black), and the light pdfs squared
// distances and areas in float (shared/lights.h now forms them from scale-free ratios).
// cms_hard_scenes_test covers 1e-4 .. 1e3; this covers the ends of the float range the loader's
// double coordinates round into.
#include <ostream>
#include <string>

#include <gtest/gtest.h>

#include "support/hard_scenes.h"
#include "support/render_agreement.h"

using namespace mixtrace;
using namespace mixtrace::testing;

namespace {

struct ScaleCase {
  const char* backend;
  double scale;
  const char* name;
};

void PrintTo(const ScaleCase& c, std::ostream* os) { *os << c.backend << " scale " << c.scale; }

class ScaleInvariance : public ::testing::TestWithParam<ScaleCase> {};

TEST_P(ScaleInvariance, TheScaledRoomRendersLikeTheUnscaledOne) {
  const ScaleCase c = GetParam();
  RenderWithStats unscaled, scaled;
  ASSERT_NO_FATAL_FAILURE(renderScene("scale_invariance", "room", hard::scaledRoomScene(1.0), c.backend, 1, unscaled));
  ASSERT_NO_FATAL_FAILURE(renderScene("scale_invariance", std::string("room_") + c.name,
                                      hard::scaledRoomScene(c.scale), c.backend, 2, scaled));
  EXPECT_EQ(scaled.stats.value("lights", -1), 1) << "the scaled room's light was dropped";
  EXPECT_EQ(scaled.stats.value("non_finite_samples", -1), 0);
  const ComparisonResult cmp = compareRenders(scaled, unscaled);
  EXPECT_TRUE(cmp.agree) << c.backend << ", scale " << c.scale << ": " << cmp.summary();
}

INSTANTIATE_TEST_SUITE_P(Scales, ScaleInvariance,
                         ::testing::Values(ScaleCase{"vulkan", 1e-12, "1em12"}, ScaleCase{"vulkan", 1e15, "1e15"},
                                           ScaleCase{"cpu", 1e-12, "1em12"}, ScaleCase{"cpu", 1e15, "1e15"}),
                         [](const auto& info) { return std::string(info.param.backend) + "_" + info.param.name; });

}  // namespace
