// The light BVH of method pt-bvh (scene/light_bvh.h built, shared/light_bvh.h compiled as C++) on
// every shipped scene, at shading points on the scene's surfaces: the pmf selectLightBvh returns
// is exactly the pmf lightBvhPmf evaluates for the light it picked (the MIS weight of a BSDF sample
// that hits the light uses the latter); the evaluated pmfs over all lights sum to at most 1, the
// rest being the probability that no light is chosen (a node whose children both have importance
// 0 at the point: none of its lights reaches it, as in pbrt-v4); selection frequencies, no light
// included, follow them (chi-square); and a light whose pmf is 0 sends nothing to the point
// (the importance bounds are conservative, so selection is unbiased).
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "gltf/gltf_loader.h"
#include "scene/light_bvh.h"
#include "scene/light_selection.h"
#include "scene/prepared_scene.h"
namespace light_bvh_test {
const mixtrace::PreparedScene* gScene = nullptr;
const std::vector<mixtrace::shared::LightSelectionGpu>* gSelection = nullptr;
const std::vector<mixtrace::shared::LightBvhNodeGpu>* gBvh = nullptr;
}  // namespace light_bvh_test
#define SHARED_SCENE (*::light_bvh_test::gScene)
#define SHARED_LIGHT_SELECTION (*::light_bvh_test::gSelection)
#define SHARED_LIGHT_BVH (*::light_bvh_test::gBvh)
#include "scene/shared_scene_access.h"
#include "support/chi2.h"
#include "support/shipped_scenes.h"
#include "support/surface_points.h"

using namespace mixtrace;
using mixtrace::testing::sceneStem;
using mixtrace::testing::shippedScenes;
using mixtrace::testing::ShadingPoint;
using mixtrace::testing::surfacePoints;

namespace {

class LightBvhOnScene : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    scene_ = prepareScene(loadGltf(GetParam()));
    selection_ = buildLightSelection(scene_.lights, LightSelection::Bvh);
    bvh_ = buildLightBvh(scene_);
    light_bvh_test::gScene = &scene_;
    light_bvh_test::gSelection = &selection_;
    light_bvh_test::gBvh = &bvh_;
  }
  uint32_t lightCount() const { return uint32_t(scene_.lights.lights.size()); }
  PreparedScene scene_;
  std::vector<shared::LightSelectionGpu> selection_;
  std::vector<shared::LightBvhNodeGpu> bvh_;
};

TEST_P(LightBvhOnScene, EveryLightHasOneEntryAndATrailToIt) {
  ASSERT_GE(bvh_.size(), 1u + lightCount());
  for (uint32_t i = 0; i < lightCount(); ++i) {
    const shared::LightBvhNodeGpu& e = bvh_[1 + i];
    EXPECT_EQ(e.first, i);
    if (e.kind == shared::kLightBvhDirectional) continue;
    ASSERT_EQ(e.kind, shared::kLightBvhLeaf);
    ASSERT_LE(e.third, 32u);
    uint32_t node = bvh_[0].first;
    for (uint32_t d = 0; d < e.third; ++d) {
      ASSERT_EQ(bvh_[node].kind, shared::kLightBvhInterior);
      node = (e.second >> d) & 1u ? bvh_[node].second : bvh_[node].first;
    }
    EXPECT_EQ(node, 1 + i) << "light " << i;
  }
}

TEST_P(LightBvhOnScene, ReturnedPmfEqualsEvaluatedPmfAndPmfsSumToOne) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  int selected = 0;
  for (const ShadingPoint& s : surfacePoints(scene_, 12, 5)) {
    double sum = 0.0;
    for (uint32_t l = 0; l < lightCount(); ++l) {
      float pmf = shared::lightBvhPmf(s.p, s.n, l);
      ASSERT_TRUE(pmf >= 0.0f && pmf <= 1.0f) << pmf;
      sum += pmf;
    }
    EXPECT_LE(sum, 1.0 + 1e-4);
    EXPECT_GT(sum, 0.0);
    for (int i = 0; i < 2000; ++i) {
      float pmf = -1.0f;
      uint32_t light = shared::selectLightBvh(s.p, s.n, u(rng), pmf);
      if (light == shared::kNoLightBvhNode) {
        EXPECT_EQ(pmf, 0.0f);
        continue;
      }
      ++selected;
      ASSERT_LT(light, lightCount());
      ASSERT_GT(pmf, 0.0f);
      ASSERT_EQ(pmf, shared::lightBvhPmf(s.p, s.n, light)) << "light " << light;
      // What the render calls: the same through lights.h's selection.
      float viaLights;
      ASSERT_EQ(shared::selectLightAt(s.p, s.n, u(rng), lightCount(), viaLights) < lightCount(), true);
    }
  }
  EXPECT_GT(selected, 0);
}

TEST_P(LightBvhOnScene, SelectionFrequenciesFollowThePmf) {
  if (lightCount() < 2) GTEST_SKIP() << "one light";
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (const ShadingPoint& s : surfacePoints(scene_, 3, 9)) {
    const int n = 100000;
    // One cell per light and a last one for "no light".
    std::vector<double> counts(lightCount() + 1, 0.0), expected(lightCount() + 1, 0.0);
    for (int i = 0; i < n; ++i) {
      float pmf;
      uint32_t light = shared::selectLightBvh(s.p, s.n, u(rng), pmf);
      counts[light != shared::kNoLightBvhNode ? light : lightCount()] += 1.0;
    }
    double sum = 0.0;
    for (uint32_t l = 0; l < lightCount(); ++l) {
      expected[l] = n * double(shared::lightBvhPmf(s.p, s.n, l));
      sum += expected[l];
    }
    expected[lightCount()] = std::max(0.0, n - sum);
    chi2::ChiSquareResult r = chi2::chiSquareTest(counts, expected);
    EXPECT_GT(r.pValue, 1e-4) << "chi2 " << r.statistic << " dof " << r.dof;
  }
}

TEST_P(LightBvhOnScene, ALightWithPmfZeroSendsNothing) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (const ShadingPoint& s : surfacePoints(scene_, 12, 21)) {
    for (uint32_t l = 0; l < lightCount(); ++l) {
      if (shared::lightBvhPmf(s.p, s.n, l) > 0.0f) continue;
      for (int i = 0; i < 200; ++i) {
        shared::LightSample ls;
        if (!shared::sampleLightPoint(s.p, l, u(rng), glm::vec2(u(rng), u(rng)), ls)) continue;
        // Reflection only: a light behind the surface sends nothing; grazing ones are rounding.
        EXPECT_LT(glm::dot(ls.direction, s.n), 1e-3f) << "light " << l << " reaches a point where its pmf is 0";
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, LightBvhOnScene, ::testing::ValuesIn(shippedScenes()),
                         [](const auto& info) { return sceneStem(info.param); });

}  // namespace
