// The method outside the prepared scene (issue 12): the scene is prepared, and its BVH built, once;
// setting up a method (what `render` does once and the viewer does at each switch to a method not
// yet shown) only reads it and builds the method's own light tables beside it, which both
// backends read.
#include "session/method_setup.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "cms/grid_resolution.h"
#include "cms/methods.h"
#include "cpu/cpu_renderer.h"
#include "scene/light_selection.h"
#include "scene/prepared_scene.h"
#include "session/scene_camera.h"

namespace mixtrace {
namespace {

// Set-up gets the prepared scene read-only: it cannot rebuild or rewrite it.
static_assert(std::is_same_v<decltype(&setUpMethod),
                             MethodSetup (*)(const PreparedScene&, const RenderOptions&, const std::string&)>,
              "setUpMethod takes the prepared scene by const reference");

RenderOptions smallRender() {
  const char* argv[] = {"mixtrace", "render", "--width", "8", "--height", "6", "--max-depth", "3"};
  return parseCommandLine(int(std::size(argv)), argv).render;
}

template <class T> bool sameBytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// many_lights: enough lights for several clusters, so the cluster methods' tables differ from the
// plain ones.
TEST(MethodSetup, EveryMethodSetsUpOnOnePreparedSceneAndBuildsNoBvh) {
  const RenderOptions o = smallRender();
  // As `render` and `view` load it (session/scene_camera.h), prepared once.
  const PreparedScene prepared =
      prepareScene(loadSceneForRendering(std::string(MIXTRACE_SOURCE_DIR) + "/scenes/many_lights.gltf", o));
  const PreparedScene untouched = prepared;
  const uint64_t preparations = preparedSceneCount();
  const size_t lightCount = prepared.lights.lights.size();
  ASSERT_GT(lightCount, 2u);

  for (const MethodInfo& method : methodTable()) {
    SCOPED_TRACE(method.name);
    const MethodSetup setup = setUpMethod(prepared, o, method.name);
    const std::vector<shared::LightSelectionGpu>& table = setup.lights.selection;
    ASSERT_EQ(table.size(), lightCount);
    // The method's selection distribution, as the scene's lights held it before.
    const std::vector<shared::LightSelectionGpu> plain = buildLightSelection(prepared.lights, method.selection);
    const LightClusters& clusters = setup.lights.cms.clusters;
    if (method.clusters) ASSERT_EQ(clusters.lightCluster.size(), lightCount);
    else EXPECT_TRUE(clusters.clusters.empty());
    for (size_t i = 0; i < lightCount; ++i) {
      EXPECT_EQ(table[i].pmf, plain[i].pmf) << "light " << i;
      EXPECT_EQ(table[i].cdf, plain[i].cdf) << "light " << i;
      EXPECT_EQ(table[i].cluster, method.clusters ? clusters.lightCluster[i] : uint32_t(i)) << "light " << i;
      EXPECT_EQ(table[i].clusterPmf, method.clusters ? clusters.lightPmfInCluster[i] : 1.0f) << "light " << i;
    }
    // The CPU backend renders the method from the shared scene and the method's tables.
    CpuRenderer renderer(prepared, setup.lights, setup.settings);
    renderer.renderSamples(1);
    EXPECT_EQ(renderer.samplesPerPixel(), 1u);
  }

  EXPECT_EQ(preparedSceneCount(), preparations) << "setting up a method prepared the scene again (and built a BVH)";
  EXPECT_TRUE(sameBytes(prepared.bvh.nodes, untouched.bvh.nodes));
  EXPECT_TRUE(sameBytes(prepared.lights.lights, untouched.lights.lights)) << "a method's set-up rewrote the lights";
  EXPECT_TRUE(sameBytes(prepared.lights.emitters, untouched.lights.emitters));
  EXPECT_TRUE(sameBytes(prepared.shading, untouched.shading));
}

// --cells N is N for every method with cells; auto is the rule's answer for this scene and image,
// the same for every such method (both backends get it from here).
TEST(MethodSetup, CellsAreGivenOrChosenByTheFootprintRule) {
  const PreparedScene prepared =
      prepareScene(loadSceneForRendering(std::string(MIXTRACE_SOURCE_DIR) + "/scenes/veach_mis.gltf", smallRender()));
  for (const char* method : {"learned", "cv", "cms"}) {
    SCOPED_TRACE(method);
    for (const char* n : {"3", "16", "100"}) {
      const char* argv[] = {"mixtrace", "render", "--width", "160", "--height", "120", "--cells", n};
      const MethodSetup given = setUpMethod(prepared, parseCommandLine(int(std::size(argv)), argv).render, method);
      EXPECT_EQ(given.settings.cells, uint32_t(std::stoi(n)));
      EXPECT_FALSE(given.cellsChosen);
    }
    const char* argv[] = {"mixtrace", "render", "--width", "160", "--height", "120"};
    const MethodSetup chosen = setUpMethod(prepared, parseCommandLine(int(std::size(argv)), argv).render, method);
    EXPECT_TRUE(chosen.cellsChosen);
    const uint32_t clusters = uint32_t(chosen.lights.cms.clusters.clusters.size());
    EXPECT_EQ(chosen.settings.cells, autoGridResolution(prepared, makeCamera(prepared.scene, 160, 120), clusters).cells);
  }
}

}  // namespace
}  // namespace mixtrace
