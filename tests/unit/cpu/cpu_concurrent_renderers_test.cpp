// Two CPU renderers of different scenes render at once, each on its own thread, and each gives
// exactly the image it gives alone. The shared shader headers read the scene and the CMS state
// through accessor macros; the CPU reference binds them to the calling thread's CpuKernelContext
// (cpu/cpu_kernel_context.h). Bound to a process global instead (as they once were), the two
// renderers would trace each other's scenes.
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "cpu/cpu_renderer.h"
#include "session/method_setup.h"
#include "session/scene_camera.h"
#include "support/shipped_scenes.h"

using namespace mixtrace;

namespace {

struct Rendered {
  std::vector<float> mean;
  std::vector<float> standardError;
};

// One renderer of `scene` with `method`, single-threaded so that the only concurrency is the
// other renderer's.
struct OneRender {
  PreparedScene prepared;
  MethodSetup setup;
  std::unique_ptr<CpuRenderer> renderer;

  OneRender(const std::string& scene, const std::string& method) {
    RenderOptions o;
    o.scene = scene;
    o.method = method;
    o.width = 24;
    o.height = 16;
    o.seed = 3;
    prepared = prepareScene(loadSceneForRendering(scene, o));
    setup = setUpMethod(prepared, o, method);
    setup.settings.threads = 1;
    renderer = std::make_unique<CpuRenderer>(prepared, setup.lights, setup.settings);
  }

  // One sample per call, so the two renderers' passes interleave many times.
  Rendered render(uint32_t spp) {
    for (uint32_t s = 0; s < spp; ++s) renderer->renderSamples(1);
    Image standardError;
    Image mean = renderer->readImage(&standardError);
    return {mean.rgb, standardError.rgb};
  }
};

std::string scenePath(const std::string& file) { return std::string(MIXTRACE_SOURCE_DIR) + "/scenes/" + file; }

void expectConcurrentEqualsAlone(const std::string& method, const std::string& sceneA, const std::string& sceneB) {
  const std::string a = scenePath(sceneA), b = scenePath(sceneB);
  const uint32_t spp = 8;
  Rendered aloneA = OneRender(a, method).render(spp);
  Rendered aloneB = OneRender(b, method).render(spp);

  OneRender renderA(a, method), renderB(b, method);
  Rendered togetherA, togetherB;
  std::thread threadA([&] { togetherA = renderA.render(spp); });
  std::thread threadB([&] { togetherB = renderB.render(spp); });
  threadA.join();
  threadB.join();

  EXPECT_EQ(togetherA.mean, aloneA.mean) << method << ": " << sceneA << " rendered beside " << sceneB;
  EXPECT_EQ(togetherA.standardError, aloneA.standardError) << method;
  EXPECT_EQ(togetherB.mean, aloneB.mean) << method << ": " << sceneB << " rendered beside " << sceneA;
  EXPECT_EQ(togetherB.standardError, aloneB.standardError) << method;
}

}  // namespace

TEST(CpuConcurrentRenderers, PlainPathTracerOfTwoScenesAtOnceGivesEachImageAlone) {
  expectConcurrentEqualsAlone("pt-power", "cornell_box.gltf", "many_lights.gltf");
}

// The learning methods also read the clusters, cell table and solutions of their own renderer
// (two scenes of several light clusters, so that cms learns on both).
TEST(CpuConcurrentRenderers, ControlledMixtureSamplingOfTwoScenesAtOnceGivesEachImageAlone) {
  expectConcurrentEqualsAlone("cms", "veach_mis.gltf", "many_lights.gltf");
}
