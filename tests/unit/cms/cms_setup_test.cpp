// What cms says when it runs as plain MIS: true for the scene at hand (a scene without lights is
// not "lights that form one cluster"; the render that says it: tests/e2e/no_lights_test.cpp).
#include "cms/cms_setup.h"

#include <gtest/gtest.h>

namespace mixtrace {
namespace {

TEST(CmsSetup, PlainMisNoteSaysNoLightsForASceneWithout) {
  CmsScene none;
  EXPECT_NE(plainMisNote(none).find("no lights"), std::string::npos) << plainMisNote(none);
  EXPECT_EQ(plainMisNote(none).find("one cluster"), std::string::npos) << plainMisNote(none);
  CmsScene one;
  one.clusters.lightCluster = {0u};
  one.clusters.clusters.resize(1);
  EXPECT_NE(plainMisNote(one).find("one cluster"), std::string::npos) << plainMisNote(one);
}

}  // namespace
}  // namespace mixtrace
