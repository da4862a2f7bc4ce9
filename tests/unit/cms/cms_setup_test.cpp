// What cms says when it runs as plain MIS: true for the scene at hand (a scene without lights is
// not "lights that form one cluster"; the render that says it: tests/e2e/no_lights_test.cpp).
#include "cms/cms_setup.h"

#include <gtest/gtest.h>

namespace mixtrace {
namespace {

TEST(CmsSetup, PlainMisNoteSaysNoLightsForASceneWithout) {
  CmsScene none;
  EXPECT_NE(plainMisNote(none, "pt-bvh").find("no lights"), std::string::npos) << plainMisNote(none, "pt-bvh");
  EXPECT_EQ(plainMisNote(none, "pt-bvh").find("one cluster"), std::string::npos) << plainMisNote(none, "pt-bvh");
  CmsScene one;
  one.clusters.lightCluster = {0u};
  one.clusters.clusters.resize(1);
  EXPECT_NE(plainMisNote(one, "pt-bvh").find("one cluster"), std::string::npos) << plainMisNote(one, "pt-bvh");
  EXPECT_NE(plainMisNote(one, "pt-bvh").find("pt-bvh's estimator"), std::string::npos) << "names what runs instead";
}

}  // namespace
}  // namespace mixtrace
