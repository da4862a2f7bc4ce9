// What cms says when it runs as plain MIS: true for the scene at hand (a scene without lights is
// not "lights that form one cluster"; the render that says it: tests/e2e/no_lights_test.cpp).
#include "cms/cms_setup.h"

#include <gtest/gtest.h>

namespace mixtrace {
namespace {

TEST(CmsSetup, PlainMisNoteSaysNoLightsForASceneWithout) {
  const std::string noLights = plainMisNote(CmsScene{}, "pt-bvh");
  EXPECT_NE(noLights.find("no lights"), std::string::npos) << noLights;
  EXPECT_EQ(noLights.find("one cluster"), std::string::npos) << noLights;
  CmsScene one;
  one.clusters.lightCluster = {0u};
  one.clusters.clusters.resize(1);
  const std::string oneCluster = plainMisNote(one, "pt-bvh");
  EXPECT_NE(oneCluster.find("one cluster"), std::string::npos) << oneCluster;
  EXPECT_NE(oneCluster.find("pt-bvh's estimator"), std::string::npos) << "names what runs instead";
}

}  // namespace
}  // namespace mixtrace
