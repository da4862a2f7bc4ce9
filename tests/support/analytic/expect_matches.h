#pragma once
// The per-pixel check of a render against its expectation, then its power: the same check must
// reject the expectation scaled by 5 % (a test that cannot see a 5 % bias proves nothing).
#include <cstdio>

#include <gtest/gtest.h>

#include "support/analytic/pixel_ztest.h"
#include "support/analytic/render.h"

namespace mixtrace::testing::analytic {

inline void expectMatches(const RenderedImage& img, int spp, const Expectation& expected, double relTolerance) {
  const ZTestResult r = zTest(img.mean, img.variance, spp, expected, relTolerance);
  EXPECT_TRUE(r.passed()) << r.summary();
  std::printf("check: %s\n", r.summary().c_str());
  for (double scale : {0.95, 1.05}) {
    const ZTestResult wrong = zTest(img.mean, img.variance, spp, expected, relTolerance, scale);
    EXPECT_FALSE(wrong.passed()) << "the check accepts an expectation scaled by " << scale << ": " << wrong.summary();
    std::printf("power (expectation x %.2f): %s\n", scale, wrong.summary().c_str());
  }
}

}  // namespace mixtrace::testing::analytic
