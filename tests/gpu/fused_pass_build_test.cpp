// --schedule auto on a CPU device builds the fused kernel's pipeline only once the first submission
// chose the fused schedule: compiling it on lavapipe took longer than the rest of a small render's
// set-up (0.5-0.75 s), which every render that keeps the wavefront paid for nothing. A render that
// builds it late counts that time as set-up (Renderer::setupSecondsDuringRender), not render time.
#include <string>

#include <gtest/gtest.h>

#include "backend/renderer.h"
#include "cms/method_lights.h"
#include "gltf/gltf_loader.h"
#include "scene/light_selection.h"
#include "scene/prepared_scene.h"
#include "vulkan/context.h"
#include "wavefront/wavefront_renderer.h"

using namespace mixtrace;

namespace {

struct Rendered {
  bool builtBefore = false;   // after set-up, before any sample
  bool builtAfter = false;
  double lateSetupSeconds = 0.0;
  std::string schedule;
};

Rendered renderAuto(VulkanContext& ctx, const std::string& scene) {
  PreparedScene prepared = prepareScene(loadGltf(std::string(MIXTRACE_SOURCE_DIR) + "/scenes/" + scene));
  RenderSettings settings;
  settings.width = 32;
  settings.height = 24;
  settings.maxDepth = 5;
  settings.schedule = RenderSettings::Schedule::Auto;
  MethodLights lights;
  lights.selection = buildLightSelection(prepared.lights, LightSelection::Power);
  WavefrontRenderer renderer(ctx, prepared, lights, settings);
  Rendered r;
  r.builtBefore = renderer.fusedPassBuilt();
  renderer.renderSamples(1);   // the first submission: the wavefront, which decides
  renderer.renderSamples(1);
  r.builtAfter = renderer.fusedPassBuilt();
  r.lateSetupSeconds = renderer.setupSecondsDuringRender();
  r.schedule = renderer.counters().schedule;
  return r;
}

}  // namespace

TEST(FusedPassBuild, AutoBuildsTheFusedKernelOnlyOnceItChoseIt) {
  VulkanContext ctx(ContextOptions{"", true});
  if (ctx.properties().deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU) GTEST_SKIP() << "auto is the wavefront on GPUs";
  // Ray occupancy 0.45 (wavefront kept) and 0.89 (fused chosen): tests/e2e/schedule_test.cpp.
  const Rendered kept = renderAuto(ctx, "textured.glb");
  EXPECT_EQ(kept.schedule, "wavefront");
  EXPECT_FALSE(kept.builtBefore);
  EXPECT_FALSE(kept.builtAfter);
  EXPECT_EQ(kept.lateSetupSeconds, 0.0);
  const Rendered fused = renderAuto(ctx, "many_lights.gltf");
  EXPECT_EQ(fused.schedule, "fused");
  EXPECT_FALSE(fused.builtBefore);
  EXPECT_TRUE(fused.builtAfter);
  EXPECT_GT(fused.lateSetupSeconds, 0.0);
  EXPECT_EQ(ctx.validationErrors(), 0u);
}
