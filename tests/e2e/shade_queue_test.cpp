// The wavefront's shade queue (IntersectConstants.queueForShade): where rays that hit nothing end
// their paths (no environment light, no CMS terms to settle) and enough of them escape, intersect
// queues only the hits for the shade pass. The paths are the same either way: the image and the
// ray counts equal the fused schedule's, which has no queues; the stats say which queue shade read.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "compare/image_compare.h"
#include "support/render_with_stats.h"

namespace {

namespace fs = std::filesystem;
using namespace mixtrace;
using namespace mixtrace::testing;

std::string scene(const char* name) { return std::string(MIXTRACE_SOURCE_DIR) + "/scenes/" + name; }

RenderWithStats render(const std::string& args, const fs::path& out) {
  return renderWithStats(args + " --width 32 --height 24 --spp 3 --seed 9 --variance", out, 600);
}

// textured.glb: about two in five rays escape into the dark.
TEST(ShadeQueue, OnlyTheHitsAreShadedWhereEscapedRaysEndTheirPaths) {
  const fs::path dir = scratchDir("shade-queue");
  for (const char* method : {"pt-power", "pt-bvh"}) {
    const std::string args = scene("textured.glb") + " --method " + method;
    const RenderWithStats w = render(args + " --schedule wavefront", dir / "w.exr");
    const RenderWithStats f = render(args + " --schedule fused", dir / "f.exr");
    ASSERT_EQ(w.exitCode, 0) << w.stderrText;
    ASSERT_EQ(f.exitCode, 0) << f.stderrText;
    EXPECT_EQ(w.stats["shade_queue"], "hits") << method;
    EXPECT_FALSE(f.stats.contains("shade_queue")) << "the fused schedule has no queues";
    EXPECT_EQ(w.stats["extension_rays"], f.stats["extension_rays"]) << method;
    EXPECT_EQ(w.stats["shadow_rays"], f.stats["shadow_rays"]) << method;
    const ComparisonResult c = compareImages(f.mean, f.variance, w.mean, w.variance);
    EXPECT_LT(c.relMse, 1e-9) << method << ": " << c.summary();
  }
}

// Where escaped rays still carry light (an environment) or terms (CMS), shade reads every ray; and
// where almost none escape (many_lights.gltf is closed), queueing would cost intersect more than it
// saves shade, so after the first submission shade reads the ray queue again.
TEST(ShadeQueue, EveryRayIsShadedWhereEscapedRaysMatterOrAlmostNoneEscape) {
  const fs::path dir = scratchDir("shade-queue-rays");
  struct Case {
    std::string args;
    const char* why;
  };
  for (const Case& k : {Case{scene("textured.glb") + " --method pt-power --env-color 0.2,0.3,0.4", "environment"},
                        Case{scene("veach_mis.gltf") + " --method cms", "cms"},
                        Case{scene("many_lights.gltf") + " --method pt-power", "closed scene"}}) {
    const RenderWithStats w = render(k.args + " --schedule wavefront", dir / "w.exr");
    ASSERT_EQ(w.exitCode, 0) << k.why << ": " << w.stderrText;
    EXPECT_EQ(w.stats["shade_queue"], "rays") << k.why;
  }
  // And the environment still lights the escaped rays: the wavefront agrees with the fused kernel.
  const std::string env = scene("textured.glb") + " --method pt-power --env-color 0.2,0.3,0.4";
  const RenderWithStats w = render(env + " --schedule wavefront", dir / "ew.exr");
  const RenderWithStats f = render(env + " --schedule fused", dir / "ef.exr");
  ASSERT_EQ(w.exitCode, 0) << w.stderrText;
  ASSERT_EQ(f.exitCode, 0) << f.stderrText;
  const ComparisonResult c = compareImages(f.mean, f.variance, w.mean, w.variance);
  EXPECT_LT(c.relMse, 1e-9) << c.summary();
}

}  // namespace
